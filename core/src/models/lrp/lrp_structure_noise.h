// The fixed-phase part n_R of texture by example (paper 003, §5, eq. 4), with random placement
// and turbulence:
//
//   n_R(ξ) = Σ_i w(‖ξ − ξ_i‖/B) s_b(i)(ξ − ξ_i) / Σ_i w(‖ξ − ξ_i‖/B)
//
// ξ are structure pixels (ξ = x − ½: pixel n of the crop sits at ξ = n), the lattice points ξ_i
// are the block centres (spacing B, the block size) and s_b the block's sum of cosines. Dividing
// by Σw (not √Σw²: these local functions are not independent) makes the windows a partition of
// unity, so with one block the crop's periodic structure comes back exactly.
//
// Random placement (§5.2) shifts ξ by a random offset, uniform over one crop period, per cell of
// half a crop; the cells are cross-faded over ⅛ of a cell on each side of a border (the paper's
// "blocks have to be blended", width unspecified). Turbulence then adds σ·(t₁(x), t₂(x)), two
// decorrelated copies of Σ_S |n_S| (the two most energetic strata, four cosines each — one lane
// group of sum_terms: the paper's "rough stratification and low budget"), centred and scaled to
// unit variance. Placement comes first, so the displacement field is one continuous field over
// all cells.
//
// Filtering: every term, the blocks' constant terms included, fades with the pixel filter's
// response at its frequency plus the window's spectral spread (lrp_noise.h). The block means
// average to the crop's mean, which is zero, so minification converges to the texture's mean.
#pragma once

#include "models/lrp/lrp_noise.h"
#include "numerics/constants.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/lrp_parameters.h>

#include <array>
#include <cmath>
#include <vector>

namespace stochtex {

/// Where eval_with evaluates n_R for one point: structure positions after placement and
/// turbulence, each with its placement weight (`blended`: combine as Σ weight·value, else take
/// the one value as it is).
struct LrpStructureSamples {
    struct Sample {
        double xi = 0, eta = 0;
        float weight = 1;
    };
    int count = 0;
    bool blended = false;
    Sample sample[4];
};

class LrpStructureNoise {
public:
    struct Options {
        std::uint64_t seed = 1;
        /// Periodic: the texture's period in exemplar pixels (the structure is stretched so a
        /// whole number of crops fits it), else zeros.
        std::array<double, 2> period{0, 0};
    };
    /// `strata`: the texture's random-phase strata (the turbulence is drawn from them).
    LrpStructureNoise(const LrpStructure& structure, int spectrum_size, const std::vector<LrpStratum>& strata,
                      const Options& options);

    /// n_R at (x, y) exemplar pixels, after placement and turbulence.
    void eval(double x, double y, const LrpFilter& filter, float out[3]) const;
    /// n_R at a structure position, without placement or turbulence; `terms_of(block)` gives the
    /// block's (filtered) terms.
    template <class TermsOf>
    void eval_structure(double xi, double eta, const TermsOf& terms_of, float out[3]) const
    {
        if (single_block()) {
            // Every lattice point holds the same T-periodic function and the windows are a
            // partition of unity: their blend is that function (9 times cheaper).
            float dx, dy;
            nearest_offset(xi, eta, dx, dy);
            sum_terms(terms_of(0), dx, dy, out);
            return;
        }
        sum_windows<LrpTermSum::direct>(lattice_, LrpNormalisation::partition, xi, eta,
                    [&](std::int64_t i, std::int64_t j) {
                        return terms_of(int(lattice_.wrapped(1, j) * blocks_per_side_ + lattice_.wrapped(0, i)));
                    },
                    out);
    }
    /// One block for the whole crop: n_R is sum_terms of its terms at nearest_offset.
    bool single_block() const { return blocks_per_side_ == 1; }
    /// The offset of structure position (xi, eta) from its nearest lattice point.
    void nearest_offset(double xi, double eta, float& dx, float& dy) const
    {
        const std::int64_t i = lattice_.nearest(0, xi), j = lattice_.nearest(1, eta);
        dx = float(xi - (lattice_.origin[0] + double(i) * lattice_.spacing[0]));
        dy = float(eta - (lattice_.origin[1] + double(j) * lattice_.spacing[1]));
    }
    /// eval_with's evaluation positions for exemplar position (x, y).
    template <class TurbulenceOf>
    LrpStructureSamples samples(double x, double y, const TurbulenceOf& turbulence_of) const;
    /// Block b's terms under `filter`.
    void draw_block(int block, const LrpFilter& filter, LrpTerms& terms) const;
    /// eval() with the blocks' filtered terms from `terms_of` and the turbulence strata's values
    /// from `turbulence_of(component, k, x, y, out)` (caches, for eval_region).
    template <class TermsOf, class TurbulenceOf>
    void eval_with(double x, double y, const TermsOf& terms_of, const TurbulenceOf& turbulence_of, float out[3]) const;
    /// The strata of displacement component 0 or 1 (empty without turbulence).
    const std::vector<LrpStratumNoise>& turbulence_strata(int component) const { return turbulence_strata_[component]; }

    int block_count() const { return blocks_per_side_ * blocks_per_side_; }
    /// Each channel's variance (the blocks' mean energy).
    const std::array<double, 3>& variance() const { return variance_; }
    /// Each channel's variance share that `filter` keeps.
    std::array<double, 3> kept_variance_fraction(const LrpFilter& filter) const;
    /// n_R evaluations per point on average (placement blends) and turbulence cosines, for cost reports.
    double mean_evaluations_per_point() const;
    int turbulence_terms() const;

private:
    struct Block {
        std::vector<float> fx, fy;              // cycles per structure pixel
        std::array<std::vector<float>, 3> re, im;
    };
    /// Structure position of exemplar pixel position x along an axis.
    double structure_position(int axis, double x) const { return x * scale_[axis] - 0.5; }
    template <class TurbulenceOf>
    std::array<double, 2> displacement(double x, double y, const TurbulenceOf& turbulence_of) const;
    std::array<double, 2> placement_shift(std::int64_t cell_x, std::int64_t cell_y) const;
    float exemplar_response(const LrpFilter& filter, float fx, float fy) const;

    int size_;
    int blocks_per_side_;
    LrpLattice lattice_;
    double scale_[2] = {1, 1};  // structure pixels per exemplar pixel (1 unless stretched to a period)
    double spread_;          // the window's spectral spread, cycles per structure pixel
    std::vector<Block> blocks_;
    bool placement_;
    double placement_cell_;
    std::int64_t placement_wrap_[2] = {0, 0};
    std::uint64_t key_;
    double turbulence_;
    std::vector<LrpStratumNoise> turbulence_strata_[2];
    std::array<double, 3> variance_{};
};

/// Cross-fade weights of random placement along one axis: the cells a position draws from.
struct LrpPlacementWeights {
    int count = 1;
    std::int64_t cell[2] = {0, 0};
    float weight[2] = {1, 0};
};
LrpPlacementWeights lrp_placement_weights(double position, double cell_size);

template <class TurbulenceOf>
std::array<double, 2> LrpStructureNoise::displacement(double x, double y, const TurbulenceOf& turbulence_of) const
{
    if (!(turbulence_ > 0) || turbulence_strata_[0].empty()) return {0, 0};
    // Σ_S |n_S| of unit-variance, roughly Gaussian strata: mean n√(2/π), variance n(1 − 2/π).
    const double n = double(turbulence_strata_[0].size());
    const double mean = n * std::sqrt(2 / kPi), deviation = std::sqrt(n * (1 - 2 / kPi));
    std::array<double, 2> d{};
    for (int component = 0; component < 2; ++component) {
        double sum = 0;
        for (std::size_t k = 0; k < turbulence_strata_[component].size(); ++k) {
            float value[3];
            turbulence_of(component, k, x, y, value);
            sum += std::abs(value[0]);
        }
        d[std::size_t(component)] = turbulence_ * scale_[component] * (sum - mean) / deviation;
    }
    return d;
}

template <class TurbulenceOf>
LrpStructureSamples LrpStructureNoise::samples(double x, double y, const TurbulenceOf& turbulence_of) const
{
    const double xi = structure_position(0, x), eta = structure_position(1, y);
    const std::array<double, 2> d = displacement(x, y, turbulence_of);
    LrpStructureSamples s;
    if (!placement_) {
        s.count = 1;
        s.sample[0] = {xi + d[0], eta + d[1], 1.0f};
        return s;
    }
    s.blended = true;
    const LrpPlacementWeights wx = lrp_placement_weights(xi, placement_cell_), wy = lrp_placement_weights(eta, placement_cell_);
    for (int b = 0; b < wy.count; ++b)
        for (int a = 0; a < wx.count; ++a) {
            const std::array<double, 2> shift = placement_shift(wx.cell[a], wy.cell[b]);
            s.sample[s.count++] = {xi + shift[0] + d[0], eta + shift[1] + d[1], wx.weight[a] * wy.weight[b]};
        }
    return s;
}

template <class TermsOf, class TurbulenceOf>
void LrpStructureNoise::eval_with(double x, double y, const TermsOf& terms_of, const TurbulenceOf& turbulence_of,
                                  float out[3]) const
{
    const LrpStructureSamples s = samples(x, y, turbulence_of);
    if (!s.blended) return eval_structure(s.sample[0].xi, s.sample[0].eta, terms_of, out);
    for (int c = 0; c < 3; ++c) out[c] = 0;
    for (int k = 0; k < s.count; ++k) {
        float value[3];
        eval_structure(s.sample[k].xi, s.sample[k].eta, terms_of, value);
        for (int c = 0; c < 3; ++c) out[c] += s.sample[k].weight * value[c];
    }
}

}  // namespace stochtex
