// stochtex — a human-readable summary of a texture description (`stex info`).
#pragma once

#include <stochtex/texture_description.h>

#include <string>

namespace stochtex {

/// Model, scale, colour, histograms and per-band weights with each band's frequency range and
/// the expected standard deviation of each channel (eq. 2, with this build's measured σ_N²).
std::string describe(const TextureDescription& description);

}  // namespace stochtex
