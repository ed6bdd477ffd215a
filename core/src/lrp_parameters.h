// The "lrp" model's parameters block in .stex files (docs/stex-format.md): reading, strict
// validation and canonical writing.
#pragma once

#include "json_fields.h"

#include <stochtex/texture_description.h>

#include <string>

namespace stochtex {

/// Limits (documented in docs/stex-format.md). The cosine budget bounds the cost of one
/// evaluation: 9 windows × (terms + 1) special-function calls per stratum.
constexpr int max_lrp_spectrum_size = 4096;
constexpr int max_lrp_strata = 16;
constexpr int max_lrp_terms = 256;            ///< cosines per window, per stratum or per block
constexpr int max_lrp_substratum_bins = 64;   ///< stored bins per sub-stratum
constexpr int max_lrp_blocks_per_side = 64;

LrpParameters read_lrp_parameters(const json_fields::Field& parameters);
json_fields::Json lrp_parameters_json(const LrpParameters& parameters);
/// Semantic checks: sizes, ranges, bins within the spectrum, finite values.
void validate_lrp(const LrpParameters& parameters, const std::string& source);

}  // namespace stochtex
