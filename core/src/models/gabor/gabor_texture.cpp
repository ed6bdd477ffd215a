#include "models/gabor/gabor_texture.h"
#include <stochtex/models/gabor_parameters.h>

#include "models/gabor/gabor_statistics.h"
#include "numerics/random.h"
#include "numerics/constants.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

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
    if (gabor.kind == GaborKind::oriented) {
        const double theta = gabor.orientations[k] * kPi / 180;
        noise.direction = {std::cos(theta), std::sin(theta), 0};
        noise.oriented_fraction = gabor.oriented_fractions[k];
    }
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
        GaborNoise noise(parameters);  // validates the octave, whatever its weights
        // An octave of weight 0 in every channel adds exact zeros to the sums (which start at
        // +0, so stay unchanged) and nothing to the dropped variance: not evaluated at all.
        if (weight[0] == 0 && weight[1] == 0 && weight[2] == 0) continue;
        octaves_.push_back({std::move(noise), weight});
    }
}

GaborTexture::Plan GaborTexture::plan(const Symmetric2& footprint, const TangentFrame& frame) const
{
    Plan plan;
    std::array<double, 3> dropped{};
    for (const auto& weight : missing_weights_)
        for (int c = 0; c < 3; ++c) dropped[c] += weight[c] * weight[c];
    for (std::size_t k = 0; k < octaves_.size(); ++k) {
        const Octave& octave = octaves_[k];
        const GaborNoiseParameters& parameters = octave.noise.parameters();
        const GaborFilter filter(parameters.bandwidth, footprint);
        const float fade = octave_fade(1 / filter.amplitude);
        if (tracks_dropped_variance_) {
            const double retained = fade > 0 ? fade * fade * gabor_retained_variance(parameters, frame, filter) : 0.0;
            for (int c = 0; c < 3; ++c) dropped[c] += (1 - retained) * octave.weight[c] * octave.weight[c];
        }
        if (fade > 0) plan.octaves.push_back({k, filter, fade});
    }
    for (int c = 0; c < 3; ++c)
        if (sigma_m_[c] > 0) plan.dropped_sigma[c] = std::sqrt(std::max(0.0, dropped[c])) / sigma_m_[c];
    return plan;
}

namespace {

/// Rows of pixels summed together before their colour mapping.
constexpr std::size_t band_rows = 16;

struct SynthesisScratch {
    std::vector<double> kept;
    std::vector<float> value;
    std::vector<double> x, y;
    std::vector<double> dropped_sigma;  // eval_solid_points: each point's
};

/// Kept per thread: a render's row band or a plugin tile allocates nothing once its thread has
/// seen one as large.
SynthesisScratch& synthesis_scratch()
{
    thread_local SynthesisScratch scratch;
    return scratch;
}

/// The blur a footprint adds to the texture: the pixel filter's covariance (exemplar pixels²)
/// less the exemplar pixel's own, which the photo — and so the fitted octaves — already holds.
Symmetric2 render_blur(const Symmetric2& pixel_filter)
{
    return without_isotropic_blur(pixel_filter, pixel_filter_sigma * pixel_filter_sigma);
}

}  // namespace

void GaborTexture::add_octave(const Plan::Kept& planned, const float* const value[3], double* const kept[3],
                              std::size_t count) const
{
    const Octave& octave = octaves_[planned.octave];
    const bool shared = octave.noise.parameters().channels == 1;  // rgb-shared: one noise
    for (int c = 0; c < 3; ++c) {
        const float* v = value[shared ? 0 : c];
        for (std::size_t p = 0; p < count; ++p) kept[c][p] += planned.fade * octave.weight[c] * v[p];
    }
}

template <class GridNoise>
void GaborTexture::synthesize(const Plan& plan, const Grid& grid, const RgbOutput& out, const GridNoise& grid_noise) const
{
    SynthesisScratch& scratch = synthesis_scratch();
    const std::size_t band = grid.nx * std::min(band_rows, grid.ny);
    scratch.kept.resize(3 * band);
    scratch.value.resize(3 * band);
    double* const kept[3] = {&scratch.kept[0], &scratch.kept[band], &scratch.kept[2 * band]};
    float* const value[3] = {&scratch.value[0], &scratch.value[band], &scratch.value[2 * band]};
    for (std::size_t first_row = 0; first_row < grid.ny; first_row += band_rows) {
        const std::size_t rows = std::min(band_rows, grid.ny - first_row), pixels = rows * grid.nx;
        for (int c = 0; c < 3; ++c) std::fill(kept[c], kept[c] + pixels, 0.0);
        // m_c = Σ_k fade_k · w_ck · n_k, octave after octave: the same order for every pixel.
        for (const Plan::Kept& planned : plan.octaves) {
            grid_noise(octaves_[planned.octave].noise, planned.filter, grid.x, grid.nx, grid.y + first_row, rows, value);
            add_octave(planned, value, kept, pixels);
        }
        colour_.to_rgb({kept[0], kept[1], kept[2]}, 1.0, plan.dropped_sigma, out, first_row * grid.nx, pixels);
    }
}

void GaborTexture::eval_2d(const Footprint2D& footprint, const Grid& grid, const RgbOutput& out) const
{
    const Plan octaves = plan(render_blur(filter_covariance(footprint, description().pixels_per_unit)), TangentFrame{});
    synthesize(octaves, grid, out,
               [](const GaborNoise& noise, const GaborFilter& filter, const double* x, std::size_t nx, const double* y,
                  std::size_t ny, float* const* value) { noise.eval_2d_grid(x, nx, y, ny, filter, value); });
}

GaborTexture::Plan GaborTexture::solid_plan(const SurfacePoint& point, TangentFrame& frame) const
{
    frame = tangent_frame(point.n, point.dpdx);
    // The screen-to-tangent Jacobian: the footprint's derivatives in the (t, b) frame (paper §5).
    return plan(render_blur(filter_covariance(tangent_footprint(frame, point), description().pixels_per_unit)), frame);
}

void GaborTexture::eval_sliced(const SurfacePoint& shared, const Grid& grid, const RgbOutput& out) const
{
    TangentFrame frame;
    const Plan octaves = solid_plan(shared, frame);
    synthesize(octaves, grid, out,
               [&](const GaborNoise& noise, const GaborFilter& filter, const double* x, std::size_t nx, const double* y,
                   std::size_t ny, float* const* value) { noise.eval_sliced_grid(x, nx, y, ny, grid.z, frame, filter, value); });
}

Rgb GaborTexture::eval(const Vec2& uv, const Footprint2D& footprint) const
{
    const double ppu = description().pixels_per_unit;
    const double x = uv[0] * ppu, y = uv[1] * ppu;
    Rgb rgb;
    eval_2d(footprint, {&x, 1, &y, 1, 0}, RgbOutput::interleaved(rgb.data()));
    return rgb;
}

Rgb GaborTexture::eval_solid(const SurfacePoint& point) const
{
    const double ppu = description().pixels_per_unit;
    const double x = point.p[0] * ppu, y = point.p[1] * ppu;
    Rgb rgb;
    eval_sliced(point, {&x, 1, &y, 1, point.p[2] * ppu}, RgbOutput::interleaved(rgb.data()));
    return rgb;
}

namespace {

/// A region's pixel centres in exemplar pixels, as eval() computes them.
void region_positions(const RasterRegion& region, double ppu, std::vector<double>& x, std::vector<double>& y)
{
    x.resize(std::size_t(region.width)), y.resize(std::size_t(region.height));
    for (int i = 0; i < region.width; ++i) x[std::size_t(i)] = region.u(i) * ppu;
    for (int j = 0; j < region.height; ++j) y[std::size_t(j)] = region.v(j) * ppu;
}

}  // namespace

void GaborTexture::eval_region(const RasterRegion& region, const RgbOutput& out) const
{
    if (region.width <= 0 || region.height <= 0) return;
    SynthesisScratch& scratch = synthesis_scratch();
    region_positions(region, description().pixels_per_unit, scratch.x, scratch.y);
    // (synthesize() uses the scratch's other arrays.)
    eval_2d(region.footprint, {scratch.x.data(), scratch.x.size(), scratch.y.data(), scratch.y.size(), 0}, out);
}

void GaborTexture::eval_solid_region(const SolidRegion& region, const RgbOutput& out) const
{
    if (region.plane.width <= 0 || region.plane.height <= 0) return;
    const double ppu = description().pixels_per_unit;
    SynthesisScratch& scratch = synthesis_scratch();
    region_positions(region.plane, ppu, scratch.x, scratch.y);
    // Every pixel has the plane's normal and footprint (SolidRegion::point), so one frame.
    eval_sliced(region.point(0, 0), {scratch.x.data(), scratch.x.size(), scratch.y.data(), scratch.y.size(), region.w * ppu},
                out);
}

void GaborTexture::eval_solid_points(const SurfaceBatch& batch, const RgbOutput& out) const
{
    // Each point has its own frame and footprint, so nothing of the plan or of the octaves'
    // prepared impulses is shared as on a plane: each point's noises are eval_solid()'s, a grid
    // of one point each, summed in eval_solid()'s order. What the batch shares is the colour
    // mapping, vectorised over a chunk with each point's own dropped σ (a cache of the cells
    // consecutive points meet was measured slower than hashing them again: docs/models/gabor.md).
    constexpr std::size_t chunk = 256;
    SynthesisScratch& scratch = synthesis_scratch();  // (the noises below do not use it)
    scratch.kept.resize(3 * chunk);
    scratch.dropped_sigma.resize(3 * chunk);
    double* const sums[3] = {&scratch.kept[0], &scratch.kept[chunk], &scratch.kept[2 * chunk]};
    double* const dropped[3] = {&scratch.dropped_sigma[0], &scratch.dropped_sigma[chunk], &scratch.dropped_sigma[2 * chunk]};
    const double ppu = description().pixels_per_unit;
    for (std::size_t start = 0; start < batch.count; start += chunk) {
        const std::size_t n = std::min(chunk, batch.count - start);
        for (std::size_t k = 0; k < n; ++k) {
            const SurfacePoint& point = batch.points[start + k];
            TangentFrame frame;
            const Plan octaves = solid_plan(point, frame);
            const double x = point.p[0] * ppu, y = point.p[1] * ppu, z = point.p[2] * ppu;
            double* const kept[3] = {sums[0] + k, sums[1] + k, sums[2] + k};
            for (int c = 0; c < 3; ++c) *kept[c] = 0, dropped[c][k] = octaves.dropped_sigma[c];
            float value[GaborNoise::max_channels] = {};
            float* const channels[GaborNoise::max_channels] = {&value[0], &value[1], &value[2]};
            for (const Plan::Kept& planned : octaves.octaves) {
                octaves_[planned.octave].noise.eval_sliced_grid(&x, 1, &y, 1, z, frame, planned.filter, channels);
                add_octave(planned, channels, kept, 1);
            }
        }
        colour_.to_rgb({sums[0], sums[1], sums[2]}, 1.0, {dropped[0], dropped[1], dropped[2]}, out, start, n);
    }
}

}  // namespace stochtex
