// The tiling model's parameters block in .stex files (docs/stex-format.md): reading, strict
// validation and canonical writing. The exemplar and the colour map travel as base64 PNG
// (quantised_image.h).
#pragma once

#include "schema/parameter_schema.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/tiling_parameters.h>

#include <string>

namespace stochtex {

/// Limits (documented in docs/stex-format.md): exemplar sides are powers of two in
/// [16, 1024] (periodic MIP pyramids need them), colour maps [8, 1024]; the base64 text of one
/// image at most 16 MiB.
constexpr int min_tiling_exemplar_side = 16, max_tiling_exemplar_side = 1024;
constexpr int min_colour_map_side = 8, max_colour_map_side = 1024;
constexpr std::size_t max_image_payload_chars = std::size_t(16) << 20;

/// The declaration of the parameters block (read, write, checks of sizes, ranges, samples and
/// output vs channels).
ParameterSchema<TilingParameters> tiling_schema();
/// What a tiling output other than colour requires of the shared colour fields.
void validate_tiling_colour_fields(const TextureDescription& description, const std::string& source);

}  // namespace stochtex
