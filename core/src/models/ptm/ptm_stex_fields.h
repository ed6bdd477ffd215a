// The ptm model's block of a .stex file (docs/stex-format.md, "ptm"): reading, writing and
// validating `parameters`, and the coefficient file beside the .stex. Used by ptm_model.cpp.
#pragma once

#include "schema/parameter_schema.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/ptm_parameters.h>

#include <string>

namespace stochtex {

/// The declaration of the parameters block. Reading loads the coefficient maps it names from the
/// folder of the .stex (ReadContext::stex_path).
ParameterSchema<PtmParameters> ptm_schema();
/// What the model asks of the rest of the description (identity colour, no histograms).
void validate_ptm_colour_fields(const TextureDescription& description, const std::string& source);
/// Writes the maps beside `stex_path` as "<stem>.ptm.exr" and returns the description naming
/// that file (write_stex writes this one).
TextureDescription write_ptm_coefficients_beside(const std::string& stex_path, const TextureDescription& description);

}  // namespace stochtex
