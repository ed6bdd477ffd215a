// stochtex — OSL shaders from a texture description (`stex osl`; docs/osl.md).
//
// The shader is osl/stochtex_wavelet.osl with osl/stochtex_wavelet.h inlined and the texture's
// numbers (core: wavelet_shader_data.h) as its parameters' defaults: one self-contained file.
// It reads two noise tiles (the core's Cook–DeRose coefficients) with closest-texel texture()
// lookups; write_noise_tiles() writes them.
#pragma once

#include <stochtex/texture_description.h>

#include <string>

namespace stochtex::osl {

/// Whether `model` has an OSL transcription (the others: osl/stochtex_texture.osl through the
/// OIIO plugin, or a baked map).
bool has_osl_form(const std::string& model);

struct OslShaderOptions {
    std::string shader_name;   ///< an OSL identifier; validated
    std::string tile_2d_path;  ///< as written into the shader (absolute, or as the renderer resolves it)
    std::string tile_3d_path;
    std::string source_name;   ///< the .stex file's name, for the header comment
};

/// Throws Error for a model without an OSL form or an invalid shader name.
std::string make_osl_shader(const TextureDescription& description, const OslShaderOptions& options);

/// A valid shader name from a file name ("out/rust 2.osl" → "stochtex_rust_2").
std::string osl_shader_name_from_path(const std::string& path);

/// Writes the 2D tile (size² texels) and the 3D tile as an atlas of 8 × 8 slices, single-channel
/// float EXR, scanline (no MIP levels: the shader reads single texels). Throws Error on failure.
void write_noise_tiles(const std::string& path_2d, const std::string& path_3d);

/// The shaders' sources, as built into this program (osl/*.osl, osl/*.h).
const std::string& wavelet_shader_source();
const std::string& wavelet_header_source();

}  // namespace stochtex::osl
