// stochtex — POV-Ray 3.7 includes from a texture description (`stex pov`; docs/pov.md).
//
// POV-Ray has no plugin API, so a texture reaches it as scene description language (SDL):
//   * procedural: POV-Ray evaluates the texture itself, as a solid texture, from its own noise
//     (octaves calibrated against the measured spectrum of that noise), the PCA colour basis and
//     the histogram maps as colour_maps. Models with Gaussian, isotropic channels only.
//   * baked: the core renders one tileable period into a linear EXR and the include maps it with
//     image_map { exr … interpolate 2 } at the texture's scale. Any model.
// Each include is self-contained (no other include file, include guard) and documents its knobs:
// NAME_Scale, NAME_Seed, … are #declared only if the scene has not declared them before.
#pragma once

#include <stochtex/image.h>
#include <stochtex/texture_description.h>

#include <string>

namespace stochtex::pov {

enum class PovMode { procedural, baked };
PovMode pov_mode_from_string(const std::string& text);  // throws Error naming --mode
const char* to_string(PovMode mode);

/// Whether `model` can be written in procedural mode (baked mode takes any model).
bool has_procedural_form(const std::string& model);

/// Throws Error unless `name` makes safe POV-Ray identifiers with its suffixes: an upper-case
/// ASCII letter, then letters, digits or '_', at most 24 characters. (POV-Ray's keywords are all
/// lower case, so a capitalised name never collides with one; the suffixes stay within the
/// parser's identifier length.)
void validate_pov_name(const std::string& name);
/// A valid name derived from a file name ("out/concrete_512.inc" → "Concrete_512").
std::string pov_name_from_path(const std::string& path);

struct PovIncludeOptions {
    std::string name;                         ///< identifier prefix (validated)
    PovMode mode = PovMode::procedural;
    /// baked: the image's file name as the include refers to it (POV-Ray looks it up beside the
    /// scene and in +L library paths); the caller writes PovInclude::baked_image there.
    std::string image_file_name;
    /// baked: pixels per side of the baked period; 0 = one texture unit at the photo's pixel
    /// scale (pixels_per_unit), capped at 2048.
    int bake_size = 0;
    std::string source_name;  ///< the .stex file's name, for the header comment
};

struct PovInclude {
    std::string text;      ///< the .inc file
    Image baked_image;     ///< baked mode: scene-linear RGB, one period (write as float EXR)
    std::string summary;   ///< a few lines for the user: what was written, fit quality
};

/// Throws Error for an invalid name, a model without a procedural form in procedural mode (the
/// message suggests --mode baked) or a bake size out of range.
PovInclude make_pov_include(const TextureDescription& description, const PovIncludeOptions& options);

}  // namespace stochtex::pov
