// The ptm model's block of a .stex file (docs/stex-format.md, "ptm"): reading, writing and
// validating `parameters`, and the coefficient file beside the .stex. Called by stex_file.cpp.
#pragma once

#include "json_fields.h"

#include <stochtex/texture_description.h>

#include <string>

namespace stochtex {

/// Reads `parameters` of a ptm file and loads the coefficient maps it names from the folder of
/// `stex_path` (the file the text came from).
PtmParameters read_ptm_parameters(const json_fields::Field& parameters, const std::string& stex_path);
void write_ptm_parameters(json_fields::Json& parameters, const PtmParameters& ptm);
/// The ptm parameters' own constraints and what the model asks of the rest of the description
/// (identity colour, no histograms).
void validate_ptm(const TextureDescription& description, const std::string& source);
/// Writes the maps beside `stex_path` as "<stem>.ptm.exr" and returns the description naming
/// that file (write_stex writes this one).
TextureDescription write_ptm_coefficients_beside(const std::string& stex_path, const TextureDescription& description);

}  // namespace stochtex
