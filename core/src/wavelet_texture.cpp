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

WaveletTexture::WaveletTexture(const TextureDescription& description)
    : Texture(description),
      sigma_m_(band_sigmas(*description.wavelet)),
      solid_gain_(std::sqrt(WaveletNoise2D::shared().variance() / WaveletNoise3D::shared().variance())),
      colour_(description, sigma_m_)
{
    const auto& weights = description.wavelet->band_weights;
    // Offsets cover a whole tile; the 3D tile is smaller, so 3D takes each offset modulo it.
    const double tile = WaveletNoise2D::shared().tile_size();
    for (int c = 0; c < 3; ++c) {
        const int offset_channel = description.colour_mode == ColourMode::rgb_shared ? 0 : c;
        for (std::size_t j = 0; j < weights[c].size(); ++j) {
            SplitMix64 rng(mix_seed(description.seed, j, offset_channel));
            Band band{weights[c][j], std::ldexp(description.pixels_per_unit, -int(j)), {}};
            // Whole-lattice random offsets decorrelate bands and channels; the fractional part
            // of the fine bands is the balanced phase, so a render at the photo's pixel scale
            // (pixel centres at (x + ½)·2^-j) shows each band with its true variance.
            const bool balanced = j < std::size_t(WaveletNoise2D::balanced_phase_count);
            const double grid_phase = 0.5 * std::ldexp(1.0, -int(j));
            for (double& o : band.offset)
                o = balanced ? std::floor(tile * rng.uniform()) +
                                   WaveletNoise2D::shared().balanced_phase(int(j)) - grid_phase
                             : tile * rng.uniform();
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
    for (std::size_t j = 0; j < band_count; ++j) fades[j] = band_fade(int(j), footprint_px);
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
    const WaveletNoise2D& noise = WaveletNoise2D::shared();
    const double footprint_px = footprint.major_axis() * description().pixels_per_unit;
    return synthesize(footprint_px, 1.0, [&](const Band& band) {
        return noise.eval(uv[0] * band.frequency_scale + band.offset[0], uv[1] * band.frequency_scale + band.offset[1]);
    });
}

Rgb WaveletTexture::eval_solid(const SurfacePoint& point) const
{
    const WaveletNoise3D& noise = WaveletNoise3D::shared();
    const double footprint_px = point.major_axis() * description().pixels_per_unit;
    const auto& p = point.p;
    return synthesize(footprint_px, solid_gain_, [&](const Band& band) {
        return noise.eval(p[0] * band.frequency_scale + band.offset[0], p[1] * band.frequency_scale + band.offset[1],
                          p[2] * band.frequency_scale + band.offset[2]);
    });
}

}  // namespace stochtex
