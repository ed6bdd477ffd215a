// stochtex — OSL shaders from a texture description (`stex osl`; docs/osl.md).
//
// A model with an OSL form (its registry capability `osl`, and its form in osl_form.h's registry)
// has a shader template osl/stochtex_<model>.osl over a header of its maths osl/stochtex_<model>.h;
// the generated shader is the template with the headers inlined and the texture's numbers (the
// core's <model>_shader_data.h) as its parameters' defaults: one self-contained file. It reads a
// few images with closest-texel texture() lookups — wavelet: two noise tiles; gabor: the
// sphere-average table; tiling: the exemplar's moment pyramid; and every model the row probe that
// tells the shader which way the host's texture() runs rows — which write_osl_images() writes.
#pragma once

#include <stochtex/texture_description.h>

#include <string>
#include <vector>

namespace stochtex::osl {

/// Whether `model` has an OSL transcription (the others: osl/stochtex_texture.osl through the
/// OIIO plugin, or a baked map).
bool has_osl_form(const std::string& model);

/// One image a shader reads: the shader parameter naming it ("tile_2d") and its path.
struct OslImage {
    std::string parameter;
    std::string path;
};

/// The images a shader reads, as written into it (absolute, or as the renderer resolves them):
/// those of its model's form (osl_form.h), and the row probe every shader reads.
struct OslImagePaths {
    std::vector<OslImage> images;  ///< the model's own, in the order its shader declares them
    std::string rows_probe;        ///< every model with a shader: the row probe (stochtex_rows.exr)
    /// The path of the image `parameter`; throws Error if the form named no such image.
    const std::string& path(const std::string& parameter) const;
    /// Every path, the model's first, then the row probe's (empty for a model without a form).
    std::vector<std::string> all() const;
};

/// The paths of the images a description's shader reads, in `folder`; `shader_stem` names the
/// texture-specific ones (the shared noise tiles and table keep their fixed names).
OslImagePaths osl_image_paths(const TextureDescription& description, const std::string& folder,
                              const std::string& shader_stem);

struct OslShaderOptions {
    std::string shader_name;  ///< an OSL identifier; validated
    OslImagePaths images;     ///< as written into the shader
    std::string source_name;  ///< the .stex file's name, for the header comment
};

/// Throws Error for a model without an OSL form (or a tiling texture with a colour map), or an
/// invalid shader name.
std::string make_osl_shader(const TextureDescription& description, const OslShaderOptions& options);

/// Writes the images the description's shader reads at these paths (single- or multi-channel
/// float EXR, scanline, no MIP levels: the shaders read single texels), each through the
/// safe-write helper (a failed write keeps the previous file). Throws Error on failure.
void write_osl_images(const TextureDescription& description, const OslImagePaths& files);

/// A valid shader name from a file name ("out/rust 2.osl" → "stochtex_rust_2").
std::string osl_shader_name_from_path(const std::string& path);

/// A shader source file as built into this program (osl/*.osl, osl/*.h, by file name).
const std::string& shader_source(const std::string& file);

}  // namespace stochtex::osl
