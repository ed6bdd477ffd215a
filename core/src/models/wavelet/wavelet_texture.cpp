#include "models/wavelet/wavelet_texture.h"
#include <stochtex/models/wavelet_parameters.h>

#include "models/wavelet/band_filter.h"
#include "numerics/random.h"
#include "models/wavelet/wavelet_noise.h"
#include "models/wavelet/wavelet_raster_kernels.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <cstdint>

namespace stochtex {

namespace {

std::array<double, 3> band_sigmas(const WaveletParameters& parameters)
{
    std::array<double, 3> sigma{};
    for (int c = 0; c < 3; ++c) sigma[c] = wavelet_channel_sigma(parameters.band_weights[c]);
    return sigma;
}

}  // namespace

double wavelet_channel_sigma(const std::vector<double>& band_weights)
{
    double sum = 0;
    for (double w : band_weights) sum += w * w;
    return std::sqrt(WaveletNoise2D::shared().variance() * sum);
}

namespace {

/// How a periodic texture lays out one band along one axis: `repeats` copies of a tile of
/// `tile` lattice cells fill the period. The lattice period tile·repeats is the closest we can
/// get to the band's natural one, `natural` cells (period × ppu · 2^-j).
/// `repeats` is 64-bit: a period may span up to max_position_pixels cells (2^35 tiles), past int.
struct BandLattice {
    int tile = 0;  // 0: the band does not fit the period
    std::int64_t repeats = 1;
};

BandLattice band_lattice(double natural)
{
    constexpr int shared_tile = 256, largest_tile = 1024;
    // A band needs a few lattice cells to exist at all: its wavelengths are 2–4 cells.
    if (!(natural >= 3)) return {};
    const double cells = std::round(natural);
    if (std::fmod(cells, shared_tile) == 0) return {shared_tile, std::int64_t(cells / shared_tile)};
    const std::int64_t repeats = std::int64_t(std::ceil(natural / largest_tile));
    const int tile = std::max(4, 2 * int(std::lround(natural / (2.0 * double(repeats)))));
    return {tile, repeats};
}

}  // namespace

WaveletTexture::WaveletTexture(const TextureDescription& description) : WaveletTexture(description, nullptr) {}

WaveletTexture::WaveletTexture(const TextureDescription& description, const Vec2& period)
    : WaveletTexture(description, &period)
{
}

WaveletTexture::WaveletTexture(const TextureDescription& description, const Vec2* period)
    : Texture(description),
      sigma_m_(band_sigmas(description.parameters.get<WaveletParameters>())),
      colour_(description, sigma_m_)
{
    const auto& weights = description.parameters.get<WaveletParameters>().band_weights;
    const WaveletNoise2D& shared = WaveletNoise2D::shared();
    present_bands_ = weights[0].size();
    for (std::size_t j = 0; j < weights[0].size(); ++j) {
        const double natural_scale = std::ldexp(description.pixels_per_unit, -int(j));
        const WaveletNoise2D* tile = &shared;
        double scale[2] = {natural_scale, natural_scale};
        if (period) {
            const BandLattice x = band_lattice((*period)[0] * natural_scale);
            const BandLattice y = band_lattice((*period)[1] * natural_scale);
            if (x.tile == 0 || y.tile == 0) {
                // Kept in bands_ (its weight counts as dropped variance) but never synthesised.
                present_bands_ = std::min(present_bands_, j);
            } else {
                tile = &WaveletNoise2D::with_period(x.tile, y.tile);
                scale[0] = double(x.tile * x.repeats) / (*period)[0];
                scale[1] = double(y.tile * y.repeats) / (*period)[1];
            }
        }
        const double gain = std::sqrt(shared.variance() / tile->variance());
        for (int c = 0; c < 3; ++c) {
            const int offset_channel = description.colour_mode == ColourMode::rgb_shared ? 0 : c;
            SplitMix64 rng(mix_seed(description.seed, j, offset_channel));
            Band band{weights[c][j], tile, gain, {scale[0], scale[1]}, natural_scale, {}};
            // Whole-lattice random offsets decorrelate bands and channels; the fractional part
            // of the fine bands is the balanced phase, so a render at the photo's pixel scale
            // (pixel centres at (x + ½)·2^-j) shows each band with its true variance. Offsets
            // cover a whole tile; the 3D tile is smaller, so 3D takes each offset modulo it.
            const bool balanced = j < std::size_t(WaveletNoise2D::balanced_phase_count);
            const double grid_phase = 0.5 * std::ldexp(1.0, -int(j));
            for (int axis = 0; axis < 3; ++axis) {
                const double cells = axis == 1 ? tile->period_y() : tile->period_x();
                band.offset[axis] = balanced ? std::floor(cells * rng.uniform()) + tile->balanced_phase(int(j)) - grid_phase
                                             : cells * rng.uniform();
            }
            bands_[c].push_back(band);
        }
    }
}

double WaveletTexture::solid_gain()
{
    // The 3D tile (64³ coefficients and its measured variance) is the costliest table of the
    // model: built here, at the first solid evaluation, not with every texture.
    static const double gain = std::sqrt(WaveletNoise2D::shared().variance() / WaveletNoise3D::shared().variance());
    return gain;
}

WaveletTexture::Fades WaveletTexture::fades(double footprint_px) const
{
    // The fade depends on the band only, not on the channel.
    Fades result;
    const std::size_t band_count = bands_[0].size();
    for (std::size_t j = 0; j < band_count; ++j)
        result.band[j] = j < present_bands_ ? band_fade(int(j), footprint_px) : 0.0f;
    for (int c = 0; c < 3; ++c) {
        double dropped_variance = 0;
        for (std::size_t j = 0; j < band_count; ++j) {
            const double weight = bands_[c][j].weight;
            const float fade = result.band[j];
            if (fade < 1) dropped_variance += (1 - double(fade) * fade) * weight * weight;
        }
        const double sigma = sigma_m_[c];
        result.dropped_sigma[c] = sigma > 0 ? std::sqrt(dropped_variance * WaveletNoise2D::shared().variance()) / sigma : 0;
    }
    return result;
}

Rgb WaveletTexture::finish(const std::array<double, 3>& kept, double gain, const Fades& fades) const
{
    std::array<double, 3> z{};
    for (int c = 0; c < 3; ++c)
        if (sigma_m_[c] > 0) z[c] = gain * kept[c] / sigma_m_[c];
    return colour_.to_rgb(z, fades.dropped_sigma);
}

template <class BandSum>
void WaveletTexture::for_each_kept_band(const Fades& fades, const BandSum& band_sum) const
{
    // synthesize()'s loop: channel by channel, band by band, the bands the fades keep.
    for (int c = 0; c < 3; ++c) {
        const auto& bands = bands_[c];
        for (std::size_t j = 0; j < bands.size(); ++j) {
            const float fade = fades.band[j];
            if (fade > 0 && bands[j].weight != 0) band_sum(c, bands[j], fade * bands[j].weight);
        }
    }
}

template <class BandNoise>
Rgb WaveletTexture::synthesize(double footprint_px, double gain, const BandNoise& band_noise) const
{
    const Fades f = fades(footprint_px);
    std::array<double, 3> kept{};
    for_each_kept_band(f, [&](int c, const Band& band, double fade_weight) { kept[c] += fade_weight * band_noise(band); });
    return finish(kept, gain, f);
}

Rgb WaveletTexture::eval(const Vec2& uv, const Footprint2D& footprint) const
{
    const double footprint_px = footprint.major_axis() * description().pixels_per_unit;
    return synthesize(footprint_px, 1.0, [&](const Band& band) {
        return band.gain * band.tile->eval(uv[0] * band.scale[0] + band.offset[0], uv[1] * band.scale[1] + band.offset[1]);
    });
}

Rgb WaveletTexture::eval_solid(const SurfacePoint& point) const
{
    const WaveletNoise3D& noise = WaveletNoise3D::shared();
    const double footprint_px = point.major_axis() * description().pixels_per_unit;
    const auto& p = point.p;
    return synthesize(footprint_px, solid_gain(), [&](const Band& band) {
        const double s = band.solid_scale;
        return noise.eval(p[0] * s + band.offset[0], p[1] * s + band.offset[1], p[2] * s + band.offset[2]);
    });
}

}  // namespace stochtex

namespace stochtex {

struct WaveletTexture::RasterScratch {
    std::vector<double> kept;  // 3 planes of `pixels`: Σ_j fade_j w_cj (gain_j) N_j per channel
    std::vector<std::int32_t> index, group;
    std::vector<float> w0, w1, w2, combined;
    wavelet_raster::ColumnSplines columns() const { return {index.data(), w0.data(), w1.data(), w2.data(), group.data()}; }
    void column_splines(const wavelet_raster::ColumnPositions& positions, std::size_t count)
    {
        wavelet_raster::column_splines(positions, count, index.data(), w0.data(), w1.data(), w2.data());
    }
    void plan(std::size_t count) { wavelet_raster::plan_columns(index.data(), count, group.data()); }
    void reserve_combined(std::size_t span)
    {
        if (combined.size() < span + wavelet_raster::combined_padding) combined.assign(span + wavelet_raster::combined_padding, 0.0f);
    }
};

WaveletTexture::RasterScratch& WaveletTexture::raster_scratch(std::size_t pixels, std::size_t columns, std::size_t span)
{
    // Kept per thread: a plugin tile or a render's row band allocates nothing once its thread
    // has seen a region as large.
    thread_local RasterScratch scratch;
    scratch.kept.assign(3 * pixels, 0.0);
    if (scratch.index.size() < columns) {
        scratch.index.resize(columns), scratch.group.resize(columns);
        scratch.w0.resize(columns), scratch.w1.resize(columns), scratch.w2.resize(columns);
    }
    scratch.reserve_combined(span);
    return scratch;
}

void WaveletTexture::eval_region(const RasterRegion& region, const RgbOutput& rgb) const
{
    // eval() at every pixel, with the work that depends on one coordinate only done once: the
    // fades for the whole region, a band's x-spline once per column, and per row its y-spline
    // and the three coefficient rows combined once (then 3 products per pixel instead of 12).
    // The per-pixel loops and the colour mapping are vectorised (wavelet_raster_kernels.h,
    // ColourMapping's batch to_rgb) with eval()'s arithmetic in eval()'s order: bit-identical.
    const Fades f = fades(region.footprint.major_axis() * description().pixels_per_unit);
    const std::size_t width = std::size_t(region.width), pixels = width * std::size_t(region.height);
    RasterScratch& scratch = raster_scratch(pixels, width, 0);
    for_each_kept_band(f, [&](int c, const Band& band, double fade_weight) {
        double* kept = &scratch.kept[std::size_t(c) * pixels];
        const WaveletNoise2D& tile = *band.tile;
        // tile.spline_x() of every column, vectorised; then the padded columns it reads.
        scratch.column_splines({region.origin_u, region.du, region.x0, band.scale[0], band.offset[0],
                                tile.period_x(), 1.0 / tile.period_x()},
                               width);
        const auto [lo_at, hi_at] = std::minmax_element(scratch.index.begin(), scratch.index.begin() + std::ptrdiff_t(width));
        const std::int32_t lo = *lo_at, hi = *hi_at + 2;
        for (std::size_t i = 0; i < width; ++i) scratch.index[i] -= lo;
        scratch.plan(width);
        const std::size_t span = std::size_t(hi - lo + 1);
        scratch.reserve_combined(span);
        for (int y = 0; y < region.height; ++y) {
            const LatticeSpline row = tile.spline_y(region.v(y) * band.scale[1] + band.offset[1]);
            wavelet_raster::combine_rows(row.w, tile.padded_row(row.first) + lo, tile.padded_width(), span,
                                         scratch.combined.data());
            wavelet_raster::accumulate_band(scratch.columns(), scratch.combined.data(), band.gain, fade_weight,
                                            kept + std::size_t(y) * width, width);
        }
    });
    colour_.to_rgb({&scratch.kept[0], &scratch.kept[pixels], &scratch.kept[2 * pixels]}, 1.0, f.dropped_sigma, rgb, 0,
                   pixels);
}

void WaveletTexture::eval_solid_region(const SolidRegion& region, const RgbOutput& rgb) const
{
    // eval_solid() on a plane w = const: every pixel has the plane's footprint (one set of
    // fades), a band's x-spline is shared by a column, and a row shares its y- and z-splines:
    // WaveletNoise3D::eval_row combines the row's 3 × 3 coefficient rows once for every lattice
    // column, leaving 3 products per pixel (eval()'s order: bit-identical values).
    const RasterRegion& plane = region.plane;
    const Fades f = fades(region.point(0, 0).major_axis() * description().pixels_per_unit);
    const WaveletNoise3D& noise = WaveletNoise3D::shared();
    const std::size_t width = std::size_t(plane.width), pixels = width * std::size_t(plane.height);
    RasterScratch& scratch = raster_scratch(pixels, width, std::size_t(noise.tile_size()) + 2);
    for_each_kept_band(f, [&](int c, const Band& band, double fade_weight) {
        double* kept = &scratch.kept[std::size_t(c) * pixels];
        const double s = band.solid_scale;
        // QuadraticBSplineWeights of every column, the first index wrapped into the tile.
        scratch.column_splines({plane.origin_u, plane.du, plane.x0, s, band.offset[0], noise.tile_size(),
                                1.0 / noise.tile_size()},
                               width);
        scratch.plan(width);
        const double z = region.w * s + band.offset[2];
        for (int y = 0; y < plane.height; ++y) {
            noise.eval_row(plane.v(y) * s + band.offset[1], z, scratch.combined.data());
            // gain 1: the solid band's value enters the sum as it is (eval_solid()).
            wavelet_raster::accumulate_band(scratch.columns(), scratch.combined.data(), 1.0, fade_weight,
                                            kept + std::size_t(y) * width, width);
        }
    });
    colour_.to_rgb({&scratch.kept[0], &scratch.kept[pixels], &scratch.kept[2 * pixels]}, solid_gain(), f.dropped_sigma,
                   rgb, 0, pixels);
}

void WaveletTexture::eval_solid_points(const SurfaceBatch& batch, const RgbOutput& rgb) const
{
    // eval_solid() at scattered surface points (a position-map bake): each point has its own
    // footprint, so no lattice work is shared as on a plane. What a batch shares is the loops:
    // each band a chunk's fades keep is evaluated at all of the chunk's points by one vector
    // kernel (the 27 coefficients gathered), and the colour mapping runs over the chunk with each
    // point's own dropped σ. eval_solid()'s operations in its order: bit-identical values.
    constexpr std::size_t chunk = 256;
    const WaveletNoise3D& noise = WaveletNoise3D::shared();
    struct Scratch {
        std::array<double, chunk> x, y, z;
        std::array<float, chunk> value;
        std::array<Fades, chunk> fades;
        std::array<std::array<double, chunk>, 3> kept, dropped_sigma;
    };
    thread_local std::unique_ptr<Scratch> scratch_holder;  // ~50 kB: allocated once per thread
    if (!scratch_holder) scratch_holder = std::make_unique<Scratch>();
    Scratch& scratch = *scratch_holder;
    for (std::size_t start = 0; start < batch.count; start += chunk) {
        const std::size_t n = std::min(chunk, batch.count - start);
        for (std::size_t k = 0; k < n; ++k) {
            const SurfacePoint& point = batch.points[start + k];
            Fades& f = scratch.fades[k];
            f = fades(point.major_axis() * description().pixels_per_unit);
            scratch.x[k] = point.p[0], scratch.y[k] = point.p[1], scratch.z[k] = point.p[2];
            for (int c = 0; c < 3; ++c) scratch.kept[c][k] = 0, scratch.dropped_sigma[c][k] = f.dropped_sigma[c];
        }
        for (int c = 0; c < 3; ++c) {
            const auto& bands = bands_[c];
            for (std::size_t j = 0; j < bands.size(); ++j) {
                const Band& band = bands[j];
                if (band.weight == 0) continue;
                bool kept_somewhere = false;
                for (std::size_t k = 0; k < n && !kept_somewhere; ++k) kept_somewhere = scratch.fades[k].band[j] > 0;
                if (!kept_somewhere) continue;
                wavelet_raster::solid_noise_at_points(
                    {scratch.x.data(), scratch.y.data(), scratch.z.data(), band.solid_scale, band.offset}, n,
                    noise.coefficients().data(), noise.tile_size(), scratch.value.data());
                double* kept = scratch.kept[c].data();
                for (std::size_t k = 0; k < n; ++k) {
                    const float fade = scratch.fades[k].band[j];
                    // for_each_kept_band's fade · weight, then synthesize()'s sum.
                    if (fade > 0) {
                        const double fade_weight = fade * band.weight;
                        kept[k] += fade_weight * scratch.value[k];
                    }
                }
            }
        }
        colour_.to_rgb({scratch.kept[0].data(), scratch.kept[1].data(), scratch.kept[2].data()}, solid_gain(),
                       {scratch.dropped_sigma[0].data(), scratch.dropped_sigma[1].data(), scratch.dropped_sigma[2].data()},
                       rgb, start, n);
    }
}

}  // namespace stochtex
