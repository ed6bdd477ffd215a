// Filtered lookups in a 2D colour map: Ŝ(μ, Σ) ≈ E[S(N)], N ~ 𝒩(μ, Σ), the colour a pixel shows
// when the noise pair (N_a, N_b) indexing the map varies inside its footprint with mean μ and
// covariance Σ (paper 002 §6.2; notes P2.5).
//
// S is an RGB map over [0, 1]² (linear light; lookups clamp to the edge, as the noise does).
// A table of pre-blurred copies holds S blurred by σ_i along a and σ_j along b for every pair
// of levels (i, j): σ_0 = 0, σ_k = 2^(k−1) map texels, the last level the full average. Coarse
// levels are stored at lower resolution (two samples per σ), so a 256² map's table takes 12 MB
// instead of 50.
//
// Methods (the ablations of docs/models/tiling.md):
//   reference   — as in the authors' code: per axis the level round(log2(1 + σ_texels)), one
//                 bilinear fetch, the a–b covariance ignored;
//   interpolated — the fractional level 1 + log2 σ (σ in texels; σ itself below 1 texel)
//                 on each axis, blended linearly between the neighbouring levels (on a
//                 triangle of the level square: up to 3 fetches);
//   covariance  — interpolated, plus the covariance: Σ = diag(d) + u uᵀ with u along the
//                 correlation (the largest axis-aligned part d that leaves a rank-one rest), the
//                 diag(d) blur from the table and the rank-one part by quadrature along u
//                 (uniform, Gauss–Hermite or equal-weight nodes: line()). Exact for any S
//                 whenever the table's blurs are and the nodes resolve them. A line along a
//                 diagonal of the map with no axis-aligned rest (var_a = var_b = |cov|: one
//                 noise indexing both axes, or a noise and its mirror) reads tables pre-blurred
//                 along that diagonal instead (colour_map_diagonal_blur.h, built on first use):
//                 one table, a few Gauss–Hermite nodes for what its blur leaves, where the
//                 raw map needs 31 nodes; near such a line (a rest of less than
//                 diagonal_zone texel²) the two readings are blended, so the lookup stays
//                 continuous in Σ.
#pragma once

#include <stochtex/texture.h>

#include <algorithm>
#include <array>
#include <memory>
#include <mutex>
#include <vector>

namespace stochtex {

enum class ColourMapMethod { reference, interpolated, covariance };
const char* to_string(ColourMapMethod method);

/// Second moments of the noise pair: var_a, cov_ab, var_b (noise units: the map spans [0, 1]).
struct PairCovariance {
    double aa = 0, ab = 0, bb = 0;
};

class ColourMapFilter {
public:
    /// rgb: size × size texels (x: noise a, y: noise b), linear RGB; size a power of two ≥ 8.
    ColourMapFilter(const std::vector<float>& rgb, int size);

    int size() const { return size_; }
    /// S at (a, b): bilinear, clamped to the map.
    Rgb point(double a, double b) const { return fetch(0, 0, a, b); }
    /// The reference implementation (double-precision fetches, one per blur-level pair).
    Rgb filtered(double mean_a, double mean_b, const PairCovariance& covariance, ColourMapMethod method) const;
    /// filtered() as the texture evaluates it: the same nodes, levels and weights, in single
    /// precision, each node's (up to three) blurred tables read as RGB vectors of four floats with
    /// the node and level weights folded into the bilinear weights, the nodes' addresses computed
    /// across the nodes (colour_map_kernels.h). Within ~1e-5 of filtered()
    /// (tests/raster_paths_test.cpp measures the colour-map output against it).
    Rgb lookup(double mean_a, double mean_b, const PairCovariance& covariance, ColourMapMethod method) const;
    /// lookup() of `count` items into out[i], bit-identical to it: the lines of a chunk of items
    /// set up first, then read — the set-up's chains of roots and divisions, independent from one
    /// item to the next, overlap instead of waiting between two line quadratures.
    void lookup_row(std::size_t count, const double* mean_a, const double* mean_b, const PairCovariance* covariance,
                    ColourMapMethod method, Rgb* out) const;
    /// E[S(N)] by brute-force quadrature over the unblurred map (a test oracle; slow).
    Rgb expected(double mean_a, double mean_b, const PairCovariance& covariance) const;

private:
    struct Blurred {
        int width = 0, height = 0;  // texels along a and b
        std::vector<float> rgb;
    };
    Rgb fetch(int level_a, int level_b, double a, double b) const;
    /// One table's bilinear value at (a, b) (map units), clamped to its texel centres.
    static Rgb fetch(const Blurred& table, double a, double b);
    /// The table level pairs around fractional levels and their weights: linear interpolation
    /// on the triangle of the level square that holds (level_a, level_b) — three tables, where
    /// a bilinear blend of the four corners reads four — the zero-weight ones dropped.
    struct LevelBlend {
        int count = 0;
        std::array<int, 3> level_a{}, level_b{};
        std::array<double, 3> weight{};
    };
    LevelBlend level_blend(double level_a, double level_b) const;
    /// The blend of level_blend()'s tables at one position.
    Rgb fetch_fractional(double level_a, double level_b, double a, double b) const;
    /// fetch_fractional() with its levels resolved once, for many positions.
    class Fractional {
    public:
        Fractional(const ColourMapFilter& filter, double level_a, double level_b)
            : filter_(filter), blend_(filter.level_blend(level_a, level_b)) {}
        Rgb fetch(double a, double b) const;

    private:
        const ColourMapFilter& filter_;
        LevelBlend blend_;
    };
    /// The fractional blur level of a variance (texels²).
    double fractional_level(double variance) const;
    /// A quadrature rule along a line: the nodes (a, b) + t_k (α, β) / size (α, β in texels).
    struct Nodes {
        double alpha = 0, beta = 0;  ///< 0 when no covariance is resolved
        const double* node = nullptr;    ///< t_k
        const double* weight = nullptr;  ///< w_k, summing to 1
        const float* node_float = nullptr, * weight_float = nullptr;  ///< the same in single precision
        int count = 1;
    };
    /// The covariance method's rank-one line: Σ = diag(d) + u uᵀ, the table levels of diag(d),
    /// u in texels and the quadrature rule along it (filtered() and lookup() share it); near a
    /// diagonal, the line on a table pre-blurred along it as well, and the share of each.
    struct Line {
        double a, b;            ///< the clamped mean
        double level_a, level_b;  ///< fractional levels of the axis-aligned part
        Nodes nodes;              ///< along u, on the axis-aligned tables
        /// The diagonal reading's weight (1: the axis-aligned one is not read; 0: not this one).
        double diagonal_weight = 0;
        const Blurred* diagonal = nullptr;         ///< the table blurred along the diagonal
        Nodes diagonal_nodes;                      ///< what that table's blur leaves of the line
    };
    /// Line of the interpolated / covariance methods (method ≠ reference).
    Line line(double mean_a, double mean_b, const PairCovariance& covariance, ColourMapMethod method) const;
    /// lookup()'s reading of a line (method ≠ reference).
    Rgb read(const Line& line) const;
    /// The up-to-three tables of a fractional level pair with their weights, resolved once.
    class Packed;

    /// Level k ≥ 1 (σ_k = 2^(k−1) steps) of the tables blurred along the diagonal (1, sign);
    /// level 0 is the raw map. Built on first use, once per sign, shared by copies.
    const Blurred& diagonal_table(int sign, int level) const;
    /// The highest level of the diagonal tables: σ = size / 8 texels (the costlier ones above
    /// would serve only lines longer than that, which take up to 17 nodes on this one).
    int diagonal_levels() const { return std::max(1, levels_ - 3); }
    struct DiagonalTables {
        std::once_flag built[2];
        std::vector<Blurred> tables[2];  // [sign < 0][level − 1]
    };

    int size_;
    int levels_;  // blur levels per axis, the last one the average
    std::vector<Blurred> table_;  // [level_a · levels_ + level_b]
    std::shared_ptr<DiagonalTables> diagonal_ = std::make_shared<DiagonalTables>();
};

}  // namespace stochtex
