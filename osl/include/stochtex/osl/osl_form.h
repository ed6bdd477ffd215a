// stochtex — a model's OSL form, and the kit its shader is built with (docs/osl.md).
//
// `stex osl` names no model: each model with an OSL form registers one (an OslFormRegistration in
// core/src/models/<name>/front_ends/<name>_osl.cpp, compiled into this front-end, not the core),
// and the generator asks the registry. A form says which images its shader reads, fills its
// template's parameter block with the texture's numbers, and writes those images; the kit below
// is what the forms share: number and array formatting, the colour blocks of stochtex_colour.h,
// template instantiation and float EXR writing.
#pragma once

#include <stochtex/osl/osl_shader.h>
#include <stochtex/models/shader_colour_data.h>
#include <stochtex/texture_description.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace stochtex::osl {

struct OslForm {
    std::string model;  ///< the registry's model name
    /// The images the shader reads (besides the row probe every shader reads), in `folder`, in the
    /// order the shader declares them; `shader_stem` names the texture-specific ones.
    std::function<std::vector<OslImage>(const std::string& folder, const std::string& shader_stem)> images;
    /// The generated shader: the model's template instantiated with the texture's numbers.
    std::function<std::string(const TextureDescription&, const OslShaderOptions&)> shader;
    /// Writes the images `images` named at the paths of `files` (the row probe is written for it).
    std::function<void(const TextureDescription&, const OslImagePaths& files)> write_images;
};

/// Registers a model's OSL form (a static object of this type in the form's file).
struct OslFormRegistration {
    explicit OslFormRegistration(OslForm form);
};

/// The registered form of `model`, or nullptr.
const OslForm* find_osl_form(const std::string& model);

// ---- The kit the forms share ----------------------------------------------------------------

/// A number as the shaders declare it: %.9g, enough for a float to round-trip.
std::string osl_number(double value);

/// "{ a, b, … }" padded with zeros to `size` entries, wrapped for reading.
std::string osl_array(const std::vector<double>& values, std::size_t size);

/// `text` as an OSL string literal; throws Error for a path OSL could not hold.
std::string osl_quoted(const std::string& text);

/// A shader's parameter declarations, one a line.
struct ParameterBlock {
    std::string text;
    void add(const std::string& declaration) { text += "    " + declaration + ",\n"; }
    void add_int_array(const std::string& name, const std::vector<int>& values);
};

/// stochtex_colour.h's parameters: the histogram maps, the Gauss–Hermite rule, mean and basis.
void add_colour(ParameterBlock& block, const ShaderColourData& colour);

/// stochtex_colour.h's joint colour (knot count 0: independent channels).
void add_joint_colour(ParameterBlock& block, const ChromaGivenBrightness& curves);

/// A 64-bit value as stochtex_u64.h's four 16-bit limbs, least significant first.
void append_limbs(std::vector<int>& out, std::uint64_t value);

/// `value` as hi + lo with hi of at most `bits` significant bits: products of hi by small integers
/// are exact in float (the shaders' exact cell and tile positions).
void split_significant_bits(double value, int bits, double& hi, double& lo);

/// A shader template (shader `template_name`, its parameter block between the lines
/// `    // @stochtex-parameters-begin` and `    // @stochtex-parameters-end`, a parameter
/// `float Scale = 1.0 [[`) with its parameter block replaced by the row probe and `parameters`,
/// its `#include "file"` lines inlined from the built-in sources, renamed, and Scale defaulting to
/// 1 / unit_size_m (coordinates in metres).
std::string instantiate_template_text(std::string text, const std::string& template_name, const std::string& parameters,
                                      const TextureDescription& description, const OslShaderOptions& options);

/// instantiate_template_text() of the built-in template `file` (osl/<file>).
std::string instantiate_template(const std::string& file, const std::string& template_name, const std::string& parameters,
                                 const TextureDescription& description, const OslShaderOptions& options);

/// A single-channel ("Y") or multi-channel float EXR, scanline, no MIP levels (the shaders read
/// single texels); `what` names it in errors. A failed write keeps the previous file.
void write_float_exr(const std::string& path, int width, int height, const std::vector<std::string>& channels,
                     const float* values, const char* what);

}  // namespace stochtex::osl
