// Finding exemplar blocks whose causal neighbourhood matches what synthesis has already placed
// (paper 004 §VII): an exhaustive search, and the projection-kernel rejection search, which
// returns exactly the same candidates much faster.
//
// Rejection (after Hel-Or & Hel-Or 2003): for an orthonormal set of kernels U_1 … U_ℓ,
//   d(N, W) = ‖N − W‖² ≥ Σ_{i ≤ ℓ} (U_i·N − U_i·W)²            (paper eq. 2)
// so a candidate whose bound already exceeds the acceptance threshold is rejected without its
// distance. Our kernels are the normalised indicators of the cells of a partition of the
// neighbourhood, per channel: U·W is a cell sum over 1/√n, O(1) per window from a summed-area
// table, and the bound is Σ_cells Σ_c (S_N − S_W)² / n_cell. Each bound level halves every
// cell: the partitions are nested, the kernel spaces too, so bounds grow level by level
// towards d (Walsh–Hadamard-like box kernels; energy-compact because coefficient fields are
// smooth at the scale of a cell). Only candidates that survive every level get their distance,
// computed by the same code as the exhaustive search, so both return identical sets.
#pragma once

#include <stochtex/image.h>

#include <limits>
#include <vector>

namespace stochtex {

/// A rectangle of texels in a block's own coordinates.
struct BlockRect {
    int x = 0, y = 0, width = 0, height = 0;
};

/// What the output already holds over part of a block: disjoint rectangles, and for each one
/// its texels' values (rows of `width`, `channels` floats per texel: the compared channels).
struct Neighbourhood {
    std::vector<BlockRect> rects;
    std::vector<float> values;
    std::size_t texel_count() const;
};

/// A block of the exemplar at (x, y) (its top-left texel) and its neighbourhood distance.
struct SearchCandidate {
    int x = 0, y = 0;
    double distance = 0;
};

/// Which distances are accepted once the smallest, d_min, is known: d ≤ relative·d_min +
/// absolute. Must not decrease with d_min (the search bounds with the best distance so far).
struct Acceptance {
    double relative = 1.0, absolute = 0.0;
    double threshold(double best) const { return relative * best + absolute; }
};

struct SearchStatistics {
    long long positions = 0;           ///< candidate positions considered
    std::vector<long long> surviving;  ///< passed bound level k (projection search only)
    long long exact_distances = 0;     ///< distances computed (in full or until they exceeded the threshold)
};

class PatchSearch {
public:
    /// Blocks of block × block texels lying wholly inside `source`; distances use its first
    /// `channels` channels.
    PatchSearch(const Image& source, int block, int channels);

    int channels() const { return channels_; }
    /// Squared distance between the neighbourhood and the block at (x, y). Summation stops
    /// once the partial sum exceeds `stop` (the result is then only known to exceed it).
    double distance(const Neighbourhood& neighbourhood, int x, int y,
                    double stop = std::numeric_limits<double>::infinity()) const;
    /// All blocks with d ≤ acceptance.threshold(d_min), in raster order of position.
    std::vector<SearchCandidate> exhaustive(const Neighbourhood& neighbourhood, const Acceptance& acceptance,
                                            SearchStatistics& statistics) const;
    /// The same set, by rejection with the cell bounds.
    std::vector<SearchCandidate> projection(const Neighbourhood& neighbourhood, const Acceptance& acceptance,
                                            SearchStatistics& statistics) const;

    static constexpr int bound_levels = 6;

private:
    /// Sums of every compared channel over texels [x, x + w) × [y, y + h) of the source.
    void window_sums(int x, int y, int w, int h, double* sums) const;

    const Image& source_;
    int block_, channels_;
    int positions_x_, positions_y_;
    std::vector<double> table_;  // summed-area table, (W + 1) × (H + 1) × channels
    double rounding_ = 0;        // bound on the rounding error of one window sum
};

}  // namespace stochtex
