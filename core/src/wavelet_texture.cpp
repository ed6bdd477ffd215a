#include "wavelet_texture.h"

#include "band_filter.h"
#include "random.h"
#include "wavelet_noise.h"

#include <cmath>

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
struct BandLattice {
    int tile = 0;  // 0: the band does not fit the period
    int repeats = 1;
};

BandLattice band_lattice(double natural)
{
    constexpr int shared_tile = 256, largest_tile = 1024;
    // A band needs a few lattice cells to exist at all: its wavelengths are 2–4 cells.
    if (!(natural >= 3)) return {};
    const double cells = std::round(natural);
    if (std::fmod(cells, shared_tile) == 0) return {shared_tile, int(cells / shared_tile)};
    const int repeats = int(std::ceil(natural / largest_tile));
    const int tile = std::max(4, 2 * int(std::lround(natural / (2.0 * repeats))));
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
      sigma_m_(band_sigmas(*description.wavelet)),
      solid_gain_(std::sqrt(WaveletNoise2D::shared().variance() / WaveletNoise3D::shared().variance())),
      colour_(description, sigma_m_)
{
    const auto& weights = description.wavelet->band_weights;
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
                scale[0] = x.tile * x.repeats / (*period)[0];
                scale[1] = y.tile * y.repeats / (*period)[1];
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

template <class BandNoise>
Rgb WaveletTexture::synthesize(double footprint_px, double gain, const BandNoise& band_noise) const
{
    // The fade depends on the band only, not the channel: compute it once per evaluation.
    constexpr std::size_t max_bands = 24;  // validate() bounds the band count
    float fades[max_bands];
    const std::size_t band_count = bands_[0].size();
    for (std::size_t j = 0; j < band_count; ++j) fades[j] = j < present_bands_ ? band_fade(int(j), footprint_px) : 0.0f;
    std::array<double, 3> z{}, dropped{};
    for (int c = 0; c < 3; ++c) {
        double kept = 0, dropped_variance = 0;
        const auto& bands = bands_[c];
        for (std::size_t j = 0; j < bands.size(); ++j) {
            const double weight = bands[j].weight;
            const float fade = fades[j];
            if (fade < 1) dropped_variance += (1 - double(fade) * fade) * weight * weight;
            if (fade > 0 && weight != 0) kept += fade * weight * band_noise(bands[j]);
        }
        const double sigma = sigma_m_[c];
        if (sigma > 0) {
            z[c] = gain * kept / sigma;
            dropped[c] = std::sqrt(dropped_variance * WaveletNoise2D::shared().variance()) / sigma;
        }
    }
    return colour_.to_rgb(z, dropped);
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
    return synthesize(footprint_px, solid_gain_, [&](const Band& band) {
        const double s = band.solid_scale;
        return noise.eval(p[0] * s + band.offset[0], p[1] * s + band.offset[1], p[2] * s + band.offset[2]);
    });
}

}  // namespace stochtex
