// The tiling model's fast footprint estimator: TilingNoise::footprint_estimate in single precision,
// with what depends only on the footprint or the grid resolved once (docs/models/tiling.md,
// "Where the time goes").
//
// Same estimator, term for term (per tap N̂ = ν + Σ w_i (E_l,i − ν), Ĉ = Σ w_i² C_l,i; the taps
// combined by the law of total variance with TapPlan's ratios), but
//   - the pyramid is PackedMomentPyramid: per texel one record of 8 floats, the means stored
//     centred on the exemplar's mean ν (so single precision keeps their small differences), then
//     only the second moments an output reads (3 channels: the variances, all colour uses; 1–2
//     channels: all of them); each row holds one extra record, a copy of its first, so a
//     bilinear lookup's two texels along x are always adjacent — two reads of 16 floats;
//   - positions go by rows: a raster row's taps of one index lie on one line, which fixes the
//     triangle row and the two vertex rows whose tile translations (the whole-pixel shift and
//     the period shift as one vector, drawn once and cached per thread) the line reads; the y
//     side of the lookups is computed once per vertex of those rows, the triangles, weights and
//     the rest of the lookup addresses across the row's pixels, and the lookups made per pixel,
//     all by Highway kernels (tiling_raster_kernels.h);
//   - the level choice, the level's geometry and the mixture's ratios as floats are resolved
//     once per footprint (Plan).
// Accuracy against the double estimator (tests/raster_paths_test.cpp): ≤ 1.9e-4 σ of each RGB
// channel (docs/models/tiling.md, "Precision"). eval() and the batch methods all run this code,
// so they stay bit-identical to each other, for any thread count and region split.
#pragma once

#include "models/tiling/tiling_noise.h"
#include "models/tiling/tiling_raster_kernels.h"

#include <array>
#include <cstdint>
#include <vector>

namespace stochtex {

class PackedMomentPyramid {
public:
    static constexpr int record = 8;  ///< floats per texel
    /// The moments of `pyramid`, centred on its global mean; 3-channel pyramids keep the variances only.
    explicit PackedMomentPyramid(const MomentPyramid& pyramid);

    struct Level {
        const float* data;          ///< texel (x, y) at data + (y · row + x) · record
        std::size_t row;            ///< records per row: width + 1 (the copy of the first)
        std::int64_t mask_x, mask_y;  ///< width − 1, height − 1 (sides are powers of two)
        double scale_x, scale_y;    ///< texels of this level per level-0 pixel
    };
    int channels() const { return channels_; }
    /// Floats of a record in use: the means, then the second moments kept.
    int used() const { return used_; }
    int level_count() const { return int(levels_.size()); }
    const Level& level(int l) const { return levels_[std::size_t(l)]; }

private:
    int channels_, used_;
    std::vector<float> data_;
    std::vector<Level> levels_;
};

/// Record lanes of the kept second moments: lane channels() + p holds moment(first[p], second[p]).
struct PackedPairs {
    int count;
    std::array<int, 6> first, second;
};
PackedPairs packed_pairs(int channels);

class TilingRaster {
public:
    TilingRaster(const TilingNoise& noise, const PackedMomentPyramid& pyramid);

    /// A footprint's taps resolved for this estimator (from TilingNoise::plan: the same taps).
    struct Plan {
        TapPlan taps;
        const PackedMomentPyramid::Level* lower = nullptr;
        const PackedMomentPyramid::Level* upper = nullptr;  ///< null when the level is whole
        tiling_raster::LevelGeometry lower_geometry{}, upper_geometry{};
        float t = 0;                                        ///< towards `upper`
        std::array<float, TapPlan::max_planned_taps> ratio{}, scatter{};
        float weight = 1, inverse_total = 1;
    };
    Plan plan(const Footprint2D& footprint_px, const FootprintSampling& sampling) const;
    /// Whether estimate_row() serves this plan: linear interpolation and ≤
    /// TapPlan::max_planned_taps taps (else TilingNoise::footprint_estimate, the double path,
    /// with plan.taps).
    static bool serves(const Plan& plan)
    {
        return plan.taps.interpolation == TexelInterpolation::linear && plan.taps.na * plan.taps.nb <= TapPlan::max_planned_taps;
    }

    /// One thread's state: the vertices' tile translations of recent lookups (direct-mapped on
    /// the low bits of the lattice indices; the values are the grid's, so caching changes no
    /// bit) and the address stage's buffers. A raster wants 64 × 16 slots (a 512-pixel row at 4
    /// exemplar pixels per pixel crosses ~30 vertex columns); one eval() needs only a few.
    class Workspace {
    public:
        explicit Workspace(int bits_i = 6, int bits_j = 4);
        /// Forgets the cached translations (before serving another grid), keeps the buffers.
        void invalidate();

    private:
        friend class TilingRaster;
        struct Slot {
            std::int64_t i, j;
            double dx, dy;
        };
        std::vector<Slot> slots_;
        std::uint64_t mask_i_, mask_j_;
        int shift_j_;
        std::vector<double> x_, rows_;
        std::vector<float> vertex_fy_;
        std::vector<std::int32_t> vertex_rows_;
        std::vector<std::int32_t> offsets_;
        std::vector<float> fractions_;
    };

    /// The footprint's moments at (x[i], y), i < count (exemplar pixels; x monotone, as along a
    /// raster row), packed as the pyramid's records at out + 8 i: the means centred on
    /// global().mean, then the kept second moments. A position's values depend on it alone, not
    /// on count or its place among the x.
    void estimate_row(const double* x, std::size_t count, double y, const Plan& plan, Workspace& workspace, float* out) const;
    /// The packed record as Moments (means made absolute; moments not kept are 0).
    Moments unpack(const float* packed) const;
    const TilingNoise& noise() const { return noise_; }

private:
    template <int Channels>
    void estimate_chunk(const double* x, std::size_t count, double y, const Plan& plan, Workspace& workspace, float* out) const;
    /// Vertex (i, j)'s translation: the tile at that vertex reads the exemplar at p + translation.
    const double* translation(std::int64_t i, std::int64_t j, Workspace& workspace) const;
    /// A slot's translation computed (translation()'s miss, kept out of its line).
    void fill(Workspace::Slot& slot, std::int64_t i, std::int64_t j) const;

    const TilingNoise& noise_;
    const PackedMomentPyramid& pyramid_;
    PackedPairs pairs_;
};

}  // namespace stochtex
