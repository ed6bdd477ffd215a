#include "models/gabor/gabor_texture.h"
#include <stochtex/models/gabor_parameters.h>

#include "models/gabor/gabor_statistics.h"
#include "numerics/random.h"

#include <cmath>
#include <stdexcept>

namespace stochtex {

namespace {

// Octave fade by the filtered support's area, which grows by spread = √det A (A = I + 2πa²Σ_f):
// what an octave costs grows with it (the cells visited cover that area), while what it keeps of
// its variance falls below 1/spread (the kernels' amplitude is |A|^-½ = 1/spread). Kept whole up
// to spread 8, gone at 32 (smoothstep in log2): ≤ 1/8 of the octave's variance is at stake, far
// less for isotropic footprints; the filtering test measures no loss (docs/models/gabor.md).
constexpr double fade_start_spread = 8, fade_end_spread = 32;

float octave_fade(double spread)
{
    if (spread <= fade_start_spread) return 1;
    if (spread >= fade_end_spread) return 0;
    const double t = std::log2(spread / fade_start_spread) / std::log2(fade_end_spread / fade_start_spread);
    return float(1 - t * t * (3 - 2 * t));
}

std::array<double, 3> channel_sigmas(const GaborParameters& parameters)
{
    std::array<double, 3> sigma{};
    for (int c = 0; c < 3; ++c) sigma[c] = gabor_channel_sigma(parameters.weights[c]);
    return sigma;
}

bool any_histogram(const TextureDescription& description)
{
    for (const HistogramMap& map : description.histograms)
        if (map.enabled()) return true;
    return false;
}

}  // namespace

double gabor_channel_sigma(const std::vector<double>& weights)
{
    double sum = 0;
    for (double w : weights) sum += w * w;
    return std::sqrt(sum);
}

GaborNoiseParameters gabor_octave(const TextureDescription& description, std::size_t k)
{
    const GaborParameters& gabor = description.parameters.get<GaborParameters>();
    GaborNoiseParameters noise;
    noise.kind = gabor.kind;
    noise.frequency = gabor.frequencies[k];
    noise.bandwidth = gabor.bandwidth * gabor.frequencies[k];
    noise.direction = gabor.direction;
    noise.impulses_per_kernel = gabor.impulses_per_kernel;
    noise.seed = mix_seed(description.seed, k, 0x6ab0);
    // rgb-shared: one noise for the three channels (perfectly correlated).
    noise.channels = description.colour_mode == ColourMode::rgb_shared ? 1 : 3;
    return noise;
}

GaborTexture::GaborTexture(const TextureDescription& description) : GaborTexture(description, nullptr) {}

GaborTexture::GaborTexture(const TextureDescription& description, const Vec2& period)
    : GaborTexture(description, &period)
{
}

GaborTexture::GaborTexture(const TextureDescription& description, const Vec2* period)
    : Texture(description),
      sigma_m_(channel_sigmas(description.parameters.get<GaborParameters>())),
      tracks_dropped_variance_(any_histogram(description)),
      colour_(description, sigma_m_)
{
    const GaborParameters& gabor = description.parameters.get<GaborParameters>();
    for (std::size_t k = 0; k < gabor.frequencies.size(); ++k) {
        GaborNoiseParameters parameters = gabor_octave(description, k);
        const std::array<double, 3> weight{gabor.weights[0][k], gabor.weights[1][k], gabor.weights[2][k]};
        if (period) {
            parameters.period = {(*period)[0] * description.pixels_per_unit, (*period)[1] * description.pixels_per_unit};
            const double radius = GaborNoise::support_radius(parameters.bandwidth);
            if (!(parameters.period[0] >= 2 * radius && parameters.period[1] >= 2 * radius)) {
                missing_weights_.push_back(weight);
                continue;
            }
        }
        octaves_.push_back({GaborNoise(parameters), weight});
    }
}

template <class OctaveNoise>
Rgb GaborTexture::synthesize(const Symmetric2& footprint, const TangentFrame& frame, const OctaveNoise& octave_noise) const
{
    std::array<double, 3> kept{}, dropped{};
    for (const auto& weight : missing_weights_)
        for (int c = 0; c < 3; ++c) dropped[c] += weight[c] * weight[c];
    for (const Octave& octave : octaves_) {
        const GaborNoiseParameters& parameters = octave.noise.parameters();
        const GaborFilter filter(parameters.bandwidth, footprint);
        const float fade = octave_fade(1 / filter.amplitude);
        if (tracks_dropped_variance_) {
            const double retained = fade > 0 ? fade * fade * gabor_retained_variance(parameters, frame, filter) : 0.0;
            for (int c = 0; c < 3; ++c) dropped[c] += (1 - retained) * octave.weight[c] * octave.weight[c];
        }
        if (fade == 0) continue;
        float value[GaborNoise::max_channels];
        octave_noise(octave.noise, filter, value);
        const int channels = parameters.channels;
        for (int c = 0; c < 3; ++c) kept[c] += fade * octave.weight[c] * value[channels == 1 ? 0 : c];
    }
    std::array<double, 3> z{}, dropped_sigma{};
    for (int c = 0; c < 3; ++c) {
        if (!(sigma_m_[c] > 0)) continue;
        z[c] = kept[c] / sigma_m_[c];
        dropped_sigma[c] = std::sqrt(std::max(0.0, dropped[c])) / sigma_m_[c];
    }
    return colour_.to_rgb(z, dropped_sigma);
}

namespace {

/// The blur a footprint adds to the texture: the pixel filter's covariance (exemplar pixels²)
/// less the exemplar pixel's own, which the photo — and so the fitted octaves — already holds.
Symmetric2 render_blur(const Symmetric2& pixel_filter)
{
    return without_isotropic_blur(pixel_filter, pixel_filter_sigma * pixel_filter_sigma);
}

}  // namespace

Rgb GaborTexture::eval(const Vec2& uv, const Footprint2D& footprint) const
{
    const double ppu = description().pixels_per_unit;
    const Symmetric2 covariance =
        render_blur(filter_covariance(footprint, ppu));
    const double x = uv[0] * ppu, y = uv[1] * ppu;
    return synthesize(covariance, TangentFrame{}, [&](const GaborNoise& noise, const GaborFilter& filter, float* value) {
        noise.eval_2d(x, y, filter, value);
    });
}

Rgb GaborTexture::eval_solid(const SurfacePoint& point) const
{
    const double ppu = description().pixels_per_unit;
    const TangentFrame frame = tangent_frame(point.n, point.dpdx);
    // The screen-to-tangent Jacobian: the footprint's derivatives in the (t, b) frame (paper §5).
    const Symmetric2 covariance = render_blur(filter_covariance(tangent_footprint(frame, point), ppu));
    const Vec3 p{point.p[0] * ppu, point.p[1] * ppu, point.p[2] * ppu};
    return synthesize(covariance, frame, [&](const GaborNoise& noise, const GaborFilter& filter, float* value) {
        noise.eval_sliced(p, frame, filter, value);
    });
}

}  // namespace stochtex
