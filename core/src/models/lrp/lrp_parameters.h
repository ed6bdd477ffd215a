// The lrp model's parameters block in .stex files (docs/stex-format.md): reading, strict
// validation and canonical writing.
#pragma once

#include "schema/parameter_schema.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/lrp_parameters.h>

#include <string>

namespace stochtex {

/// Limits (documented in docs/stex-format.md). The cosine budget bounds the cost of one
/// evaluation: 9 windows × (terms + 1) special-function calls per stratum.
constexpr int max_lrp_spectrum_size = 4096;
constexpr int max_lrp_strata = 16;
constexpr int max_lrp_terms = 256;            ///< cosines per window, per stratum or per block
constexpr int max_lrp_substratum_bins = 64;   ///< stored bins per sub-stratum
constexpr int max_lrp_blocks_per_side = 64;

/// The declaration of the parameters block (read, write and validate_lrp).
ParameterSchema<LrpParameters> lrp_schema();
/// Semantic checks: sizes, ranges, bins within the spectrum, finite values.
void validate_lrp(const LrpParameters& parameters, const std::string& source);

}  // namespace stochtex
