#include "models/lrp/lrp_structure_noise.h"

#include "numerics/exact_rounding.h"
#include "numerics/random.h"

#include <stochtex/error.h>
#include <stochtex/models/lrp_parameters.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {

/// Cross-fade width of random placement on each side of a cell border, in cells.
constexpr double placement_blend = 1.0 / 8;
/// Turbulence: from the first strata, with the first sub-strata of each.
constexpr std::size_t turbulence_stratum_count = 2, turbulence_cosines = 4;

}  // namespace

LrpPlacementWeights lrp_placement_weights(double position, double cell_size)
{
    LrpPlacementWeights result;
    const double scaled = position / cell_size;
    const std::int64_t cell = std::int64_t(floor_exact(scaled));  // (no libm call: per sample)
    const double t = scaled - double(cell);
    result.cell[0] = cell;
    // Own weight ½ on the border rising to 1 at `placement_blend` inside, smoothstep-shaped (C¹).
    const double edge = std::min(t, 1 - t) / placement_blend;
    if (edge >= 1) return result;
    const double own = 0.5 + 0.5 * edge * edge * (3 - 2 * edge);
    result.count = 2;
    result.cell[1] = t < 0.5 ? cell - 1 : cell + 1;
    result.weight[0] = float(own);
    result.weight[1] = float(1 - own);
    return result;
}

LrpStructureNoise::LrpStructureNoise(const LrpStructure& structure, int spectrum_size, const std::vector<LrpStratum>& strata,
                                     const Options& options)
    : size_(spectrum_size),
      blocks_per_side_(spectrum_size / structure.block_size),
      placement_(structure.random_placement),
      placement_cell_(0.5 * spectrum_size),
      key_(mix_seed(options.seed, 0x5eed, 0x57c7)),
      turbulence_(structure.turbulence)
{
    const bool periodic = options.period[0] > 0 && options.period[1] > 0;
    if (periodic) {
        // A whole number of crops per period on each axis: the structure is scaled by
        // crops·T/period, within [2/3, 2], within 20 % once a period holds two crops, and not at
        // all when the period is a multiple of the crop (the plugin's default 16384 pixels).
        for (int axis = 0; axis < 2; ++axis) {
            const double crops = std::round(options.period[std::size_t(axis)] / size_);
            if (crops < 1)
                throw Error("periodic texture: an lrp structure (fixed phases) repeats every " + std::to_string(size_) +
                            " exemplar pixels and cannot fit a period of " +
                            std::to_string(options.period[std::size_t(axis)]) +
                            " exemplar pixels; use a period of at least " + std::to_string(size_ / 2) +
                            " exemplar pixels, or analyse with --r 0");
            scale_[axis] = crops * size_ / options.period[std::size_t(axis)];
            placement_wrap_[axis] = std::int64_t(2 * crops);
        }
    }
    const double b = structure.block_size;
    lattice_ = LrpLattice(b, b, 0.5 * (b - 1), 0.5 * (b - 1));
    lattice_.wrap[0] = lattice_.wrap[1] = blocks_per_side_;
    spread_ = lrp_window_spread_2d(0.75) / b;
    const double inverse_fit = 1.0 / structure.fit_size;
    for (const LrpBlock& source : structure.blocks) {
        Block block;
        std::array<double, 3> energy{};
        for (std::size_t t = 0; 2 * t < source.frequencies.size(); ++t) {
            const int kx = source.frequencies[2 * t], ky = source.frequencies[2 * t + 1];
            block.fx.push_back(float(kx * inverse_fit));
            block.fy.push_back(float(ky * inverse_fit));
            for (int c = 0; c < 3; ++c) {
                const double re = source.coefficients[c][2 * t], im = source.coefficients[c][2 * t + 1];
                block.re[c].push_back(float(re));
                block.im[c].push_back(float(im));
                // A constant term (k = 0) contributes re² (its im multiplies sin 0); a cosine half its amplitude².
                energy[c] += kx == 0 && ky == 0 ? re * re : 0.5 * (re * re + im * im);
            }
        }
        for (int c = 0; c < 3; ++c) variance_[c] += energy[c] / double(structure.blocks.size());
        blocks_.push_back(std::move(block));
    }
    if (turbulence_ > 0) {
        for (int component = 0; component < 2; ++component)
            for (std::size_t s = 0; s < std::min(turbulence_stratum_count, strata.size()); ++s) {
                LrpStratum rough = strata[s];
                rough.substrata.resize(std::min(turbulence_cosines, rough.substrata.size()));
                rough.sigma = {1, 0, 0};
                LrpStratumNoise::Options noise;
                noise.seed = mix_seed(options.seed, 0x7ab0 + s, std::uint64_t(component));
                noise.period = options.period;
                turbulence_strata_[component].emplace_back(rough, spectrum_size, noise);
            }
    }
}

float LrpStructureNoise::exemplar_response(const LrpFilter& filter, float fx, float fy) const
{
    // Frequencies are per structure pixel; the filter works in exemplar pixels.
    return filter.response(fx * scale_[0], fy * scale_[1], spread_ * std::max(scale_[0], scale_[1]));
}

std::array<double, 2> LrpStructureNoise::placement_shift(std::int64_t cell_x, std::int64_t cell_y) const
{
    auto wrapped = [this](int axis, std::int64_t cell) {
        const std::int64_t wrap = placement_wrap_[axis];
        if (!wrap) return cell;
        const std::int64_t r = cell % wrap;
        return r < 0 ? r + wrap : r;
    };
    SplitMix64 rng(mix_seed(key_, std::uint64_t(wrapped(0, cell_x)), std::uint64_t(wrapped(1, cell_y))));
    // Any offset within one crop period: the structure repeats with that period.
    return {rng.uniform() * size_, rng.uniform() * size_};
}

void LrpStructureNoise::draw_block(int block, const LrpFilter& filter, LrpTerms& terms) const
{
    const Block& b = blocks_[std::size_t(block)];
    for (std::size_t t = 0; t < b.fx.size(); ++t) {
        const float response = exemplar_response(filter, b.fx[t], b.fy[t]);
        if (!(response > 0)) continue;
        float re[3], im[3];
        for (int c = 0; c < 3; ++c) re[c] = b.re[c][t] * response, im[c] = b.im[c][t] * response;
        terms.push(b.fx[t], b.fy[t], re, im);
    }
    terms.pad();
}

void LrpStructureNoise::eval(double x, double y, const LrpFilter& filter, float out[3]) const
{
    LrpTerms scratch;
    eval_with(
        x, y,
        [&](int block) {
            scratch.count = 0;
            draw_block(block, filter, scratch);
            return scratch.view();
        },
        [&](int component, std::size_t k, double px, double py, float value[3]) {
            turbulence_strata_[component][k].eval(px, py, LrpFilter{}, value);
        },
        out);
}

std::array<double, 3> LrpStructureNoise::kept_variance_fraction(const LrpFilter& filter) const
{
    if (filter.identity) return {1, 1, 1};
    std::array<double, 3> kept{}, total{};
    for (const Block& b : blocks_)
        for (std::size_t t = 0; t < b.fx.size(); ++t) {
            const double r = exemplar_response(filter, b.fx[t], b.fy[t]);
            const bool constant = b.fx[t] == 0 && b.fy[t] == 0;
            for (int c = 0; c < 3; ++c) {
                const double energy = constant ? b.re[c][t] * b.re[c][t] : 0.5 * (b.re[c][t] * b.re[c][t] + b.im[c][t] * b.im[c][t]);
                kept[std::size_t(c)] += r * r * energy;
                total[std::size_t(c)] += energy;
            }
        }
    for (int c = 0; c < 3; ++c) kept[std::size_t(c)] = total[std::size_t(c)] > 0 ? kept[std::size_t(c)] / total[std::size_t(c)] : 1;
    return kept;
}

double LrpStructureNoise::mean_evaluations_per_point() const
{
    // A border band of `placement_blend` on each side of each axis blends two cells.
    return placement_ ? (1 + 2 * placement_blend) * (1 + 2 * placement_blend) : 1;
}

int LrpStructureNoise::turbulence_terms() const
{
    int terms = 0;
    for (const auto& component : turbulence_strata_)
        for (const LrpStratumNoise& stratum : component) terms += stratum.term_count();
    return terms;
}

}  // namespace stochtex
