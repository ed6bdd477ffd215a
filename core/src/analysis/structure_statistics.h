// Portilla–Simoncelli-style structure statistics of an RGB image and the normalised distance
// between two images' (the `structure` part of compare_images; docs/metrics.md, "Structure").
#pragma once

#include <stochtex/image.h>
#include <stochtex/metrics.h>

#include <array>
#include <vector>

namespace stochtex {

/// The statistics, grouped as StructureDistance's parts. Every value is dimensionless (a
/// correlation coefficient, a skewness, a log ratio), so differences in a group compare.
struct StructureStatistics {
    bool measurable = false;  ///< false for images too small (a side under 64) or flat
    std::array<std::vector<double>, StructureDistance::kParts> groups;
    /// Per statistic, the share of the image's pixels it was estimated from (1 at full
    /// resolution, 1/4^s at level s): a statistic's sampling noise grows as 1/√pixels, so the
    /// coarse levels' (a 256² crop's coarsest band is 32² pixels) weigh less.
    std::array<std::vector<double>, StructureDistance::kParts> weights;
};

/// The statistics of the largest centred crop whose sides are multiples of 16 (the pyramid's
/// 4 halvings), luma normalised to zero mean and unit variance (contrast is the other metrics').
StructureStatistics structure_statistics(const Image& rgb);

/// Per group, the RMS of the differences of its statistics weighted by their `weights`
/// (NaN where either is not measurable).
std::array<double, StructureDistance::kParts> structure_group_rms(const StructureStatistics& a,
                                                                  const StructureStatistics& b);

/// The image with each channel's Fourier amplitudes (of its periodic component) and one shared
/// set of random phases: the same spectrum and colour covariance, no structure. Deterministic
/// in seed.
Image random_phase_image(const Image& rgb, unsigned seed);

/// The photo's side of the structure distance, made once: its statistics and, per group, the
/// distance to its own random-phase version (the unit of the normalised parts).
class StructureReference {
public:
    explicit StructureReference(const Image& reference);
    StructureDistance distance_to(const Image& test) const;

private:
    StructureStatistics reference_;
    std::array<double, StructureDistance::kParts> unit_{};
};

}  // namespace stochtex
