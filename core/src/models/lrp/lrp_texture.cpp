#include "models/lrp/lrp_texture.h"
#include <stochtex/models/lrp_parameters.h>

#include "models/lrp/lrp_parameters.h"
#include "models/lrp/lrp_raster.h"
#include "models/lrp/lrp_raster_kernels.h"
#include "numerics/random.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace stochtex {

namespace {

std::array<double, 3> channel_sigmas(const LrpParameters& parameters, const std::optional<LrpStructureNoise>& structure)
{
    std::array<double, 3> variance = structure ? structure->variance() : std::array<double, 3>{};
    for (const LrpStratum& stratum : parameters.strata)
        for (int c = 0; c < 3; ++c) variance[std::size_t(c)] += stratum.sigma[std::size_t(c)] * stratum.sigma[std::size_t(c)];
    return {std::sqrt(variance[0]), std::sqrt(variance[1]), std::sqrt(variance[2])};
}

std::optional<LrpStructureNoise> make_structure(const TextureDescription& description, const std::array<double, 2>& period)
{
    const LrpParameters& lrp = description.parameters.get<LrpParameters>();
    if (!lrp.structure) return std::nullopt;
    LrpStructureNoise::Options options;
    options.seed = description.seed;
    options.period = period;
    return LrpStructureNoise(*lrp.structure, lrp.spectrum_size, lrp.strata, options);
}

std::array<double, 2> period_in_pixels(const TextureDescription& description, const Vec2* period)
{
    if (!period) return {0, 0};
    return {(*period)[0] * description.pixels_per_unit, (*period)[1] * description.pixels_per_unit};
}

}  // namespace

LrpTexture::LrpTexture(const TextureDescription& description) : LrpTexture(description, nullptr) {}

LrpTexture::LrpTexture(const TextureDescription& description, const Vec2& period) : LrpTexture(description, &period) {}

LrpTexture::LrpTexture(const TextureDescription& description, const Vec2* period)
    : Texture(description),
      structure_(make_structure(description, period_in_pixels(description, period))),
      sigma_m_(channel_sigmas(description.parameters.get<LrpParameters>(), structure_)),
      tracks_dropped_variance_(std::any_of(description.histograms.begin(), description.histograms.end(),
                                           [](const HistogramMap& map) { return map.enabled(); })),
      colour_(description, sigma_m_)
{
    const LrpParameters& lrp = description.parameters.get<LrpParameters>();
    for (std::size_t s = 0; s < lrp.strata.size(); ++s) {
        LrpStratumNoise::Options options;
        options.seed = mix_seed(description.seed, s, 0x1e9);
        options.shared_phase = description.colour_mode == ColourMode::rgb_shared;
        options.period = period_in_pixels(description, period);
        strata_.emplace_back(lrp.strata[s], lrp.spectrum_size, options);
    }
}

std::array<double, 3> LrpTexture::dropped_sigma(const LrpFilter& filter) const
{
    if (!tracks_dropped_variance_ || filter.identity) return {0, 0, 0};
    std::array<double, 3> dropped{};
    for (const LrpStratumNoise& stratum : strata_) {
        const double lost = stratum.survives(filter) ? 1 - stratum.kept_variance_fraction(filter) : 1;
        for (int c = 0; c < 3; ++c) dropped[std::size_t(c)] += lost * stratum.variance()[std::size_t(c)];
    }
    if (structure_) {
        const std::array<double, 3> kept = structure_->kept_variance_fraction(filter);
        for (int c = 0; c < 3; ++c) dropped[std::size_t(c)] += (1 - kept[std::size_t(c)]) * structure_->variance()[std::size_t(c)];
    }
    for (int c = 0; c < 3; ++c)
        dropped[std::size_t(c)] = sigma_m_[std::size_t(c)] > 0 ? std::sqrt(std::max(0.0, dropped[std::size_t(c)])) / sigma_m_[std::size_t(c)] : 0;
    return dropped;
}

Rgb LrpTexture::finish(const float m[3], const std::array<double, 3>& dropped) const
{
    std::array<double, 3> z{};
    for (int c = 0; c < 3; ++c)
        if (sigma_m_[std::size_t(c)] > 0) z[std::size_t(c)] = double(m[c]) / sigma_m_[std::size_t(c)];
    return colour_.to_rgb(z, dropped);
}

Rgb LrpTexture::eval(const Vec2& uv, const Footprint2D& footprint) const
{
    const double ppu = description().pixels_per_unit;
    const LrpFilter filter = LrpFilter::from_footprint(footprint, ppu);
    const double x = uv[0] * ppu, y = uv[1] * ppu;
    float m[3] = {0, 0, 0};
    for (const LrpStratumNoise& stratum : strata_) {
        if (!stratum.survives(filter)) continue;
        float value[3];
        stratum.eval(x, y, filter, value);
        for (int c = 0; c < 3; ++c) m[c] += value[c];
    }
    if (structure_) {
        float value[3];
        structure_->eval(x, y, filter, value);
        for (int c = 0; c < 3; ++c) m[c] += value[c];
    }
    return finish(m, dropped_sigma(filter));
}

namespace {

/// One thread's term caches, reused stratum after stratum and region after region: a fresh one per
/// stratum grew its buffers term by term (reallocations and copies were ~6 % of eval_region).
/// Cache 0 serves stratum_values (one stratum after another); SharedWindows holds one per stratum
/// it sums together.
LrpTermCache& thread_term_cache(int index = 0)
{
    thread_local LrpTermCache caches[lrp_raster::max_layers];
    return caches[index];
}

/// The lattice points whose windows reach a raster region, with their terms drawn once for the
/// region, when the region is dense enough for that to pay (a coarse MIP level spans many lattice
/// cells per pixel: those draw per pixel, as eval() does).
struct RegionTerms {
    bool cached = false;
    LrpTermCache& terms;

    /// Whether drawing the region's windows once pays (not more than ~4 per pixel).
    static bool pays(const LrpGridWindows& box, std::size_t pixels)
    {
        return double(box.i_end - box.i_begin) * double(box.j_end - box.j_begin) <= 4.0 * double(pixels) + 64;
    }

    RegionTerms(const LrpStratumNoise& stratum, const LrpFilter& filter, const LrpGridWindows& box, std::size_t pixels,
                LrpTermCache& cache = thread_term_cache())
        : cached(pays(box, pixels)), terms(cache)
    {
        if (cached)
            terms.fill(box.i_begin, box.j_begin, int(box.i_end - box.i_begin), int(box.j_end - box.j_begin),
                       [&](std::int64_t i, std::int64_t j, LrpTerms& out) { stratum.draw(i, j, filter, out); });
    }
};

/// One thread's buffers for eval_region, reused region after region.
struct RegionScratch {
    std::vector<double> x, y;
    std::vector<float> m[3], value[3];
    std::vector<double> kept[3];               // m in double, for the colour mapping
    std::vector<float> turbulence[2][2];  // component, stratum: channel 0 per pixel
    std::vector<LrpStructureSamples> samples;  // per pixel of a chunk
    std::vector<float> dx, dy, sums[3];        // per structure sample
};

RegionScratch& region_scratch()
{
    thread_local RegionScratch s;
    return s;
}

/// `stratum` under `filter` at every pixel of the grid into out[c][pixel]: where the terms can be
/// drawn once for the region, the lattice-row raster drawing its own (windows of a few pixels) or
/// the separable raster over the region's term cache; else eval() per pixel (identical values).
/// With `add`, out[c][pixel] + the value (the strata's sum, in eval()'s order).
void stratum_values(const LrpStratumNoise& stratum, const LrpFilter& filter, const LrpRasterGrid& grid,
                    float* const out[3], bool add)
{
    const std::size_t pixels = std::size_t(grid.width) * std::size_t(grid.height);
    const LrpGridWindows box(stratum.lattice(), grid);
    if (RegionTerms::pays(box, pixels) && lrp_raster_prefers_lattice_rows(stratum, grid))
        return lrp_raster_stratum_drawn(stratum, filter, grid, out, add);
    const RegionTerms region(stratum, filter, box, pixels);
    if (region.cached) return lrp_raster_stratum(stratum, region.terms, grid, out, LrpRasterMethod::separable, add);
    for (int r = 0; r < grid.height; ++r)
        for (int k = 0; k < grid.width; ++k) {
            float value[3];
            stratum.eval(grid.x[k], grid.y[r], filter, value);
            const std::size_t pixel = std::size_t(r) * std::size_t(grid.width) + std::size_t(k);
            for (int c = 0; c < 3; ++c) out[c][pixel] = add ? out[c][pixel] + value[c] : value[c];
        }
}

/// Strata that share their windows (lrp_raster_shares_windows) and take the separable raster
/// over cached terms (stratum_values' choice for them), summed by one pass (lrp_raster_strata):
/// each window's weights computed once for all. Each stratum's terms go to a cache of its own.
class SharedWindows {
public:
    SharedWindows(const LrpRasterGrid& grid) : grid_(grid) {}

    /// Takes `stratum` (out, add: as stratum_values') where it shares the first one's windows and
    /// stratum_values would take the separable raster; false (nothing done) where not, or full.
    bool take(const LrpStratumNoise& stratum, const LrpFilter& filter, float* const out[3], bool add)
    {
        const std::size_t pixels = std::size_t(grid_.width) * std::size_t(grid_.height);
        const LrpGridWindows box(stratum.lattice(), grid_);
        if (count_ == lrp_raster::max_layers || !RegionTerms::pays(box, pixels) || lrp_raster_prefers_lattice_rows(stratum, grid_) ||
            (count_ > 0 && !lrp_raster_shares_windows(*layers_[0].noise, stratum)))
            return false;
        const RegionTerms terms(stratum, filter, box, pixels, thread_term_cache(count_));
        layers_[count_++] = {&stratum, &terms.terms, {out[0], out[1], out[2]}, add};
        return true;
    }
    void run() const { lrp_raster_strata(layers_, count_, grid_); }

private:
    LrpRasterGrid grid_;
    LrpRasterLayer layers_[lrp_raster::max_layers];
    int count_ = 0;
};

}  // namespace

void LrpTexture::eval_region(const RasterRegion& region, const RgbOutput& rgb) const
{
    // eval() at every pixel, rearranged: each lattice point's terms drawn once for the region,
    // the strata summed by the separable raster (lrp_raster.h), the structure's blocks filtered
    // once. The same terms and the same operations per pixel, so bit-identical to eval().
    const double ppu = description().pixels_per_unit;
    const LrpFilter filter = LrpFilter::from_footprint(region.footprint, ppu);
    const std::array<double, 3> dropped = dropped_sigma(filter);
    const std::size_t pixels = std::size_t(region.width) * region.height;
    if (pixels == 0) return;
    if (!(region.du > 0 && region.dv > 0)) return Texture::eval_region(region, rgb);  // the raster needs increasing positions

    RegionScratch& s = region_scratch();
    s.x.resize(std::size_t(region.width));
    s.y.resize(std::size_t(region.height));
    for (int i = 0; i < region.width; ++i) s.x[std::size_t(i)] = region.u(i) * ppu;
    for (int j = 0; j < region.height; ++j) s.y[std::size_t(j)] = region.v(j) * ppu;
    const LrpRasterGrid grid{s.x.data(), region.width, s.y.data(), region.height};
    for (int c = 0; c < 3; ++c) {
        s.m[c].assign(pixels, 0.0f);
        s.value[c].resize(pixels);
    }
    float* const value[3] = {s.value[0].data(), s.value[1].data(), s.value[2].data()};
    float* const m[3] = {s.m[0].data(), s.m[1].data(), s.m[2].data()};
    // The turbulence strata are unfiltered strata on the same grid, each on the lattice of one of
    // the first texture strata: summed with that one where both take the separable raster (the
    // window weights once for all), else on their own.
    bool turbulence_done[2][2] = {};
    for (const LrpStratumNoise& stratum : strata_) {
        if (!stratum.survives(filter)) continue;
        SharedWindows shared(grid);
        if (!shared.take(stratum, filter, m, true)) {
            stratum_values(stratum, filter, grid, m, true);  // m += the stratum
            continue;
        }
        for (int component = 0; structure_ && component < 2; ++component) {
            const std::vector<LrpStratumNoise>& turbulence = structure_->turbulence_strata(component);
            for (std::size_t k = 0; k < turbulence.size(); ++k) {
                std::vector<float>& values = s.turbulence[component][k];
                values.resize(pixels);
                float* const out[3] = {values.data(), nullptr, nullptr};  // (channel 0 alone: σ = (1, 0, 0))
                if (!turbulence_done[component][k]) turbulence_done[component][k] = shared.take(turbulence[k], LrpFilter{}, out, false);
            }
        }
        shared.run();
    }

    if (structure_) {
        // The blocks are drawn once.
        for (int component = 0; component < 2; ++component) {
            const std::vector<LrpStratumNoise>& turbulence = structure_->turbulence_strata(component);
            for (std::size_t k = 0; k < turbulence.size(); ++k) {
                if (turbulence_done[component][k]) continue;
                stratum_values(turbulence[k], LrpFilter{}, grid, value, false);
                s.turbulence[component][k].assign(s.value[0].begin(), s.value[0].begin() + std::ptrdiff_t(pixels));
            }
        }
        LrpTermCache blocks;
        const bool cache_blocks = double(structure_->block_count()) <= 4.0 * double(pixels) + 64;
        if (cache_blocks)
            blocks.fill(0, 0, structure_->block_count(), 1,
                        [&](std::int64_t b, std::int64_t, LrpTerms& terms) { structure_->draw_block(int(b), filter, terms); });
        const auto turbulence_at = [&](std::size_t p) {
            return [&s, p](int component, std::size_t k, double, double, float out[3]) {
                out[0] = s.turbulence[component][k][p], out[1] = out[2] = 0;
            };
        };
        if (cache_blocks && structure_->single_block()) {
            // One block: every sample is sum_terms of the same terms, so the samples go through
            // the SIMD kernel together (pixels as lanes), then combine as eval_with does. In
            // chunks of pixels: a whole region's samples (~100 bytes a pixel) left the cache
            // between their making and their use.
            constexpr std::size_t chunk = 1024;
            for (std::size_t first = 0; first < pixels; first += chunk) {
                const std::size_t end = std::min(pixels, first + chunk);
                s.samples.resize(chunk);
                s.dx.clear(), s.dy.clear();
                for (std::size_t p = first; p < end; ++p) {
                    const double x = s.x[p % std::size_t(region.width)], y = s.y[p / std::size_t(region.width)];
                    LrpStructureSamples& samples = s.samples[p - first];
                    samples = structure_->samples(x, y, turbulence_at(p));
                    for (int k = 0; k < samples.count; ++k) {
                        float dx, dy;
                        structure_->nearest_offset(samples.sample[k].xi, samples.sample[k].eta, dx, dy);
                        s.dx.push_back(dx), s.dy.push_back(dy);
                    }
                }
                const std::size_t n = s.dx.size();
                s.dx.resize(n + lrp_raster::padding, 0.0f), s.dy.resize(n + lrp_raster::padding, 0.0f);
                for (auto& channel : s.sums) channel.resize(std::max(channel.size(), n + lrp_raster::padding));
                float* const sums[3] = {s.sums[0].data(), s.sums[1].data(), s.sums[2].data()};
                lrp_raster::sum_terms_at(blocks.at(0, 0), s.dx.data(), s.dy.data(), n, sums);
                std::size_t next = 0;
                for (std::size_t p = first; p < end; ++p) {
                    const LrpStructureSamples& samples = s.samples[p - first];
                    float structure[3] = {0, 0, 0};
                    for (int k = 0; k < samples.count; ++k, ++next)
                        for (int c = 0; c < 3; ++c)
                            structure[c] = samples.blended ? structure[c] + samples.sample[k].weight * sums[c][next] : sums[c][next];
                    for (int c = 0; c < 3; ++c) s.m[c][p] += structure[c];
                }
            }
        } else {
            for (std::size_t p = 0; p < pixels; ++p) {
                const double x = s.x[p % std::size_t(region.width)], y = s.y[p / std::size_t(region.width)];
                float structure[3];
                if (cache_blocks)
                    structure_->eval_with(x, y, [&](int b) { return blocks.at(b, 0); }, turbulence_at(p), structure);
                else
                    structure_->eval(x, y, filter, structure);
                for (int c = 0; c < 3; ++c) s.m[c][p] += structure[c];
            }
        }
    }
    // finish() for the whole region at once (the batch colour mapping: the same operations).
    for (int c = 0; c < 3; ++c) s.kept[c].assign(s.m[c].begin(), s.m[c].begin() + std::ptrdiff_t(pixels));
    colour_.to_rgb({s.kept[0].data(), s.kept[1].data(), s.kept[2].data()}, 1.0, dropped, rgb, 0, pixels);
}

void LrpTexture::eval_solid_region(const SolidRegion& region, const RgbOutput& rgb) const
{
    // eval_solid is eval at (p.x, p.y) with the (u, v) part of the footprint: on a solid slice
    // that is the plane's own raster.
    eval_region(region.plane, rgb);
}

Rgb LrpTexture::eval_solid(const SurfacePoint& point) const
{
    const Footprint2D footprint{point.dpdx[0], point.dpdx[1], point.dpdy[0], point.dpdy[1]};
    return eval({point.p[0], point.p[1]}, footprint);
}

LrpCost LrpTexture::cost() const
{
    LrpCost cost;
    for (const LrpStratumNoise& stratum : strata_) cost.paper_calls += 9.0 * (stratum.term_count() + 1);
    cost.total_calls = cost.paper_calls;
    if (structure_) {
        int largest = 0;
        for (const LrpBlock& block : description().parameters.get<LrpParameters>().structure->blocks) largest = std::max(largest, int(block.frequencies.size() / 2));
        // One block is one periodic function: no windows (lrp_structure_noise.h).
        const double structure_calls = structure_->block_count() == 1 ? largest : 9.0 * (largest + 1);
        cost.paper_calls += structure_calls;
        cost.total_calls += structure_calls * structure_->mean_evaluations_per_point();
        // Turbulence: two displacement components, each strata of windows and cosines.
        cost.total_calls += 9.0 * structure_->turbulence_terms() +
                            (structure_->turbulence_terms() > 0 ? 9.0 * 2 * std::min<std::size_t>(2, strata_.size()) : 0);
    }
    return cost;
}

std::string describe_lrp(const TextureDescription& description)
{
    const LrpParameters& lrp = description.parameters.get<LrpParameters>();
    const LrpTexture texture(description);
    const LrpCost cost = texture.cost();
    std::ostringstream out;
    char line[256];
    auto print = [&](const char* pattern, auto... values) {
        std::snprintf(line, sizeof line, pattern, values...);
        out << line;
    };
    int random_cosines = 0;
    for (const LrpStratum& stratum : lrp.strata) random_cosines += int(stratum.substrata.size());
    print("lrp          spectrum %d² (bins of 1/%d cycle per exemplar px); %zu strata, %d random-phase cosines per window\n",
          lrp.spectrum_size, lrp.spectrum_size, lrp.strata.size(), random_cosines);
    print("cost         9(J + s) = %.0f special-function calls per sample; %.0f with placement blends and turbulence\n",
          cost.paper_calls, cost.total_calls);
    out << "stratum  spacing px  cosines  stored bins   sigma[0]   sigma[1]   sigma[2]\n";
    for (std::size_t s = 0; s < lrp.strata.size(); ++s) {
        const LrpStratum& stratum = lrp.strata[s];
        std::size_t bins = 0;
        for (const auto& substratum : stratum.substrata) bins += substratum.size() / 2;
        print("%7zu  %10.1f  %7zu  %11zu  %9.5f  %9.5f  %9.5f\n", s, stratum.spacing, stratum.substrata.size(), bins,
              stratum.sigma[0], stratum.sigma[1], stratum.sigma[2]);
    }
    if (lrp.structure) {
        const LrpStructure& r = *lrp.structure;
        std::size_t largest = 0;
        for (const LrpBlock& block : r.blocks) largest = std::max(largest, block.frequencies.size() / 2);
        const int per_side = lrp.spectrum_size / r.block_size;
        print("structure    fixed phases: %dx%d blocks of %d px (fitted on %d px), up to %zu cosines each; random placement "
              "%s; turbulence %.2f px\n",
              per_side, per_side, r.block_size, r.fit_size, largest, r.random_placement ? "on" : "off", r.turbulence);
    } else {
        out << "structure    none (noise by example only, r = 0)\n";
    }
    for (int c = 0; c < 3; ++c) print("sigma_M[%d]   %.5f\n", c, texture.sigma_m()[std::size_t(c)]);
    return out.str();
}

}  // namespace stochtex
