// The measurements of docs/models/tiling.md (issue 8's acceptance), as markdown on stdout and,
// with an output folder, the pictures:
//
//   tiling_report [--out DIR] [--exemplars DIR] [--size N] [--quick]
//
// 1. Identities of the moment pyramid (coarsest level = exact moments; level 0 variance 0).
// 2. Moment estimator errors |μ̂−μ|, |σ̂−σ| (mean and 95th percentile over k×k blocks) against
//    the brute-force reference (models/tiling/tiling_estimator_reference.h) at k = 1 … 128 on a 1024² noise pair.
// 3. Colour errors ‖Ŝ−S̄‖ for the four ablations (exact/estimated mean × exact/estimated spread)
//    on a smooth and a saturated colour map and on phasor noise; rows: the paper's method
//    (one texel estimate, rounded blur level, no covariance), then each improvement added.
// 4. Flicker under a slow zoom, with and without pre-filtering.
// 5. LEAN normal-map filtering vs the filtered mean normal, against supersampled shading.
// Needs ../shared/exemplars for the 1024² inputs (else the committed 512² exemplar is used).
#include "models/tiling/colour_map_filter.h"
#include "models/tiling/colour_maps.h"
#include "models/tiling/normal_map_filter.h"
#include "models/tiling/phasor_field.h"
#include "models/tiling/tiling_estimator_reference.h"
#include "models/tiling/tiling_exemplar.h"
#include "models/tiling/tiling_noise.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace stochtex;

struct Settings {
    std::string out, exemplars = STOCHTEX_SHARED_DIR "/exemplars";
    int size = 1024;  // exemplar side and brute-force window
    bool quick = false;
};

// ---- Inputs ---------------------------------------------------------------------------------------

std::vector<float> luminance_plane(const Image& image)
{
    std::vector<float> plane(image.pixel_count());
    for (std::size_t i = 0; i < plane.size(); ++i)
        plane[i] = 0.2126f * image.pixels[3 * i] + 0.7152f * image.pixels[3 * i + 1] + 0.0722f * image.pixels[3 * i + 2];
    return plane;
}

/// A photo's luminance, periodic, at side², mapped to [0, 1] by mean ± 3σ (as `stex tiling colour-map`).
std::vector<double> noise_plane(const std::string& path, int side, bool transpose)
{
    const Image image = read_image_linear(path);
    const int crop = std::min({side, power_of_two_floor(image.width), power_of_two_floor(image.height)});
    if (crop != side) throw Error(path + ": smaller than " + std::to_string(side));
    std::vector<float> p = periodic_crop(luminance_plane(image), image.width, image.height, side, side);
    double sum = 0, sum2 = 0;
    for (float v : p) sum += v, sum2 += double(v) * v;
    const double mean = sum / p.size(), sigma = std::sqrt(sum2 / p.size() - mean * mean);
    std::vector<double> out(p.size());
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const float v = transpose ? p[std::size_t(x) * side + y] : p[std::size_t(y) * side + x];
            out[std::size_t(y) * side + x] = std::clamp(0.5 + (v - mean) / (6 * sigma), 0.0, 1.0);
        }
    return out;
}

double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

ColourMapFilter colour_map(const std::string& name)
{
    std::vector<float> map = named_colour_map(name, 256);
    for (float& v : map) v = float(srgb_to_linear(v));
    return ColourMapFilter(map, 256);
}

TilingNoise make_noise(const std::vector<std::vector<double>>& planes, int side)
{
    return TilingNoise(std::make_shared<const MomentPyramid>(planes, side, side), TilingGrid(1, side / (2 * std::sqrt(3.0))));
}

// ---- Estimators and colour methods (the rows of the tables) ---------------------------------------

struct Estimator {
    const char* name;
    FootprintSampling sampling;
};
const Estimator paper_estimator{"1 texel", {1, 1, TexelInterpolation::linear}};
const Estimator mixture_estimator{"1 texel, mixture", {1, 1, TexelInterpolation::mixture}};
const Estimator tap_estimator{"2×2 taps", {2, 8, TexelInterpolation::linear}};

struct ColourRow {
    const char* name;
    const Estimator* estimator;
    ColourMapMethod method;
};
const ColourRow colour_rows[] = {
    {"paper: 1 texel, rounded level, no cov", &paper_estimator, ColourMapMethod::reference},
    {"+ blur-level interpolation", &paper_estimator, ColourMapMethod::interpolated},
    {"+ covariance", &paper_estimator, ColourMapMethod::covariance},
    {"+ 2×2 taps (stochtex default)", &tap_estimator, ColourMapMethod::covariance},
};

PairCovariance pair(const Moments& m) { return {m.moment(0, 0), m.moment(0, 1), m.moment(1, 1)}; }

Rgb filtered(const ColourMapFilter& map, const Moments& mean_from, const Moments& spread_from, ColourMapMethod method)
{
    return map.filtered(mean_from.mean[0], mean_from.mean[1], pair(spread_from), method);
}

std::string cell(const ErrorSummary& e, double scale)
{
    char text[64];
    std::snprintf(text, sizeof text, "%.2f (%.2f)", e.mean * scale, e.p95 * scale);
    return text;
}

std::vector<int> footprints(const Settings& s)
{
    std::vector<int> k;
    for (int f = 1; f <= 128 && f <= s.size / 8; f *= 2) k.push_back(f);
    return k;
}

// ---- 1. Identities --------------------------------------------------------------------------------

void identities(const std::vector<std::vector<double>>& planes, int side)
{
    const MomentPyramid pyramid(planes, side, side);
    const Moments top = pyramid.global();
    // Direct two-pass double computation over all pixels.
    double worst_mean = 0, worst_cov = 0;
    for (int a = 0; a < 2; ++a) {
        double mean = 0;
        for (double v : planes[a]) mean += v;
        mean /= planes[a].size();
        worst_mean = std::max(worst_mean, std::abs(top.mean[a] - mean));
        for (int b = 0; b < 2; ++b) {
            double meanb = 0;
            for (double v : planes[b]) meanb += v;
            meanb /= planes[b].size();
            double cov = 0;
            for (std::size_t i = 0; i < planes[a].size(); ++i) cov += (planes[a][i] - mean) * (planes[b][i] - meanb);
            cov /= planes[a].size();
            worst_cov = std::max(worst_cov, std::abs(top.moment(a, b) - cov));
        }
    }
    const TilingNoise noise = make_noise(planes, side);
    double worst_estimate = 0, worst_level0 = 0;
    for (int i = 0; i < 1000; ++i) {
        const double x = 7919.0 * i / 1000, y = 104729.0 * i / 1000;
        const Moments m = noise.texel_estimate(x, y, 1e9, TexelInterpolation::linear);
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) worst_estimate = std::max(worst_estimate, std::abs(m.moment(a, b) - top.moment(a, b)));
        for (int a = 0; a < 2; ++a) worst_estimate = std::max(worst_estimate, std::abs(m.mean[a] - top.mean[a]));
        const Moments p = noise.point(x, y);
        worst_level0 = std::max({worst_level0, std::abs(p.moment(0, 0)), std::abs(p.moment(1, 1))});
    }
    std::printf("## 1. Identities (%d² exemplar, %d levels)\n\n", side, pyramid.level_count());
    std::printf("| check | worst absolute difference |\n|---|---|\n");
    std::printf("| coarsest level mean vs two-pass double mean | %.2e |\n", worst_mean);
    std::printf("| coarsest level (co)variances vs two-pass double | %.2e |\n", worst_cov);
    std::printf("| estimator at the coarsest level vs (ν, Cov E), 1000 random points | %.2e |\n", worst_estimate);
    std::printf("| level-0 variance estimate, 1000 random points | %.2e |\n\n", worst_level0);
}

// ---- 2. and 3. Estimator and colour error tables -------------------------------------------------

struct BlockEstimates {
    std::vector<NoiseBlock> blocks;
    std::vector<Moments> paper, mixture, taps;
};

BlockEstimates estimate_blocks(const TilingNoise& noise, const NoiseRaster& raster, int k, const MomentColour& point_colour)
{
    BlockEstimates e;
    e.blocks = noise_blocks(raster, k, point_colour);
    for (const NoiseBlock& b : e.blocks) {
        const Footprint2D f = Footprint2D::square(k);
        e.paper.push_back(noise.footprint_estimate(b.x, b.y, f, paper_estimator.sampling));
        e.mixture.push_back(noise.footprint_estimate(b.x, b.y, f, mixture_estimator.sampling));
        e.taps.push_back(noise.footprint_estimate(b.x, b.y, f, tap_estimator.sampling));
    }
    return e;
}

void moment_table(const TilingNoise& noise, const NoiseRaster& raster, const Settings& s)
{
    std::printf("## 2. Moment estimators (noise pair, values in [0, 1]; errors ×1000, mean (95th percentile) over blocks and both noises)\n\n");
    std::printf("| k px | blocks | |μ̂−μ| 1 texel | |μ̂−μ| 2×2 taps | |σ̂−σ| 1 texel | |σ̂−σ| 1 texel, mixture | |σ̂−σ| 2×2 taps |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (int k : footprints(s)) {
        const BlockEstimates e = estimate_blocks(noise, raster, k, [](const Moments&) { return Rgb{0, 0, 0}; });
        std::vector<double> mu_paper, mu_taps, sd_paper, sd_mixture, sd_taps;
        for (std::size_t i = 0; i < e.blocks.size(); ++i)
            for (int a = 0; a < 2; ++a) {
                const Moments& x = e.blocks[i].exact;
                const double sd = std::sqrt(std::max(0.0, x.moment(a, a)));
                auto sd_of = [&](const Moments& m) { return std::abs(std::sqrt(std::max(0.0, m.moment(a, a))) - sd); };
                mu_paper.push_back(std::abs(e.paper[i].mean[a] - x.mean[a]));
                mu_taps.push_back(std::abs(e.taps[i].mean[a] - x.mean[a]));
                sd_paper.push_back(sd_of(e.paper[i]));
                sd_mixture.push_back(sd_of(e.mixture[i]));
                sd_taps.push_back(sd_of(e.taps[i]));
            }
        std::printf("| %d | %zu | %s | %s | %s | %s | %s |\n", k, e.blocks.size(), cell(summarise(mu_paper), 1000).c_str(),
                    cell(summarise(mu_taps), 1000).c_str(), cell(summarise(sd_paper), 1000).c_str(),
                    cell(summarise(sd_mixture), 1000).c_str(), cell(summarise(sd_taps), 1000).c_str());
        std::fflush(stdout);
    }
    std::printf("\n");
}

/// Returns, per footprint, the mean ‖Ŝ−S̄‖ of (paper row, default row) for the (μ̂, σ̂) ablation.
std::vector<std::pair<double, double>> colour_table(const char* title, const TilingNoise& noise, const NoiseRaster& raster,
                                                   const ColourMapFilter& map, const Settings& s)
{
    std::printf("### %s\n\n‖Ŝ−S̄‖ in linear RGB ×1000, mean (95th percentile) over blocks.\n\n", title);
    std::printf("| k px | method | unfiltered S(N(centre)) | Ŝ(μ, σ) | Ŝ(μ̂, σ) | Ŝ(μ, σ̂) | Ŝ(μ̂, σ̂) |\n|---|---|---|---|---|---|---|\n");
    std::vector<std::pair<double, double>> summary;
    const MomentColour point_colour = [&](const Moments& m) { return map.point(m.mean[0], m.mean[1]); };
    for (int k : footprints(s)) {
        const BlockEstimates e = estimate_blocks(noise, raster, k, point_colour);
        std::vector<double> unfiltered;
        for (const NoiseBlock& b : e.blocks) unfiltered.push_back(colour_distance(map.point(noise.point(b.x, b.y).mean[0], noise.point(b.x, b.y).mean[1]), b.box_colour));
        double paper = 0, ours = 0;
        for (const ColourRow& row : colour_rows) {
            const std::vector<Moments>& est = row.estimator == &tap_estimator ? e.taps : e.paper;
            std::vector<double> errors[4];
            for (std::size_t i = 0; i < e.blocks.size(); ++i) {
                const Moments& x = e.blocks[i].exact;
                const Rgb& target = e.blocks[i].box_colour;
                errors[0].push_back(colour_distance(filtered(map, x, x, row.method), target));
                errors[1].push_back(colour_distance(filtered(map, est[i], x, row.method), target));
                errors[2].push_back(colour_distance(filtered(map, x, est[i], row.method), target));
                errors[3].push_back(colour_distance(filtered(map, est[i], est[i], row.method), target));
            }
            ErrorSummary summaries[4];
            for (int a = 0; a < 4; ++a) summaries[a] = summarise(errors[a]);
            std::printf("| %d | %s | %s | %s | %s | %s | %s |\n", k, row.name,
                        &row == &colour_rows[0] ? cell(summarise(unfiltered), 1000).c_str() : "",
                        cell(summaries[0], 1000).c_str(), cell(summaries[1], 1000).c_str(), cell(summaries[2], 1000).c_str(),
                        cell(summaries[3], 1000).c_str());
            if (&row == &colour_rows[0]) paper = summaries[3].mean;
            if (&row == &colour_rows[3]) ours = summaries[3].mean;
        }
        summary.push_back({paper, ours});
        std::fflush(stdout);
    }
    std::printf("\n");
    return summary;
}

/// The lookup alone: Ŝ(μ, Σ) against the quadrature oracle E[S(N)], N ~ 𝒩(μ, Σ), by correlation.
void lookup_table(const ColourMapFilter& green, const ColourMapFilter& rgb)
{
    std::printf("### The lookup alone: Ŝ(μ, Σ) vs E[S(N)], N ~ 𝒩(μ, Σ) (quadrature oracle)\n\n");
    std::printf("σ_a ∈ {0.01, 0.03, 0.08, 0.15}, σ_b = 0.8 σ_a, correlation ±ρ, means a ∈ {0.35, 0.5, 0.62} × b ∈ {0.4, 0.55}; mean ‖Ŝ − E[S]‖ ×1000.\n\n");
    std::printf("| map | ρ | reference (rounded level, no cov) | interpolated | covariance |\n|---|---|---|---|---|\n");
    for (const auto& [name, map] : {std::pair<const char*, const ColourMapFilter*>{"green", &green}, {"rgb", &rgb}})
        for (double rho : {0.0, 0.6, 0.9}) {
            double error[3] = {0, 0, 0};
            int count = 0;
            for (double sigma : {0.01, 0.03, 0.08, 0.15})
                for (double sign : {-1.0, 1.0})
                    for (double ma : {0.35, 0.5, 0.62})
                        for (double mb : {0.4, 0.55}) {
                            const PairCovariance c{sigma * sigma, sign * rho * sigma * sigma * 0.8, sigma * sigma * 0.64};
                            const Rgb truth = map->expected(ma, mb, c);
                            int m = 0;
                            for (ColourMapMethod method : {ColourMapMethod::reference, ColourMapMethod::interpolated, ColourMapMethod::covariance})
                                error[m++] += colour_distance(map->filtered(ma, mb, c, method), truth);
                            ++count;
                        }
            std::printf("| %s | %.1f | %.2f | %.2f | %.2f |\n", name, rho, 1000 * error[0] / count, 1000 * error[1] / count,
                        1000 * error[2] / count);
        }
    std::printf("\n");
}

// ---- 4. Flicker ------------------------------------------------------------------------------------

void flicker_table(const std::vector<std::pair<const char*, std::pair<const TilingNoise*, const ColourMapFilter*>>>& inputs,
                   const Settings& s)
{
    const int frames = s.quick ? 60 : 200, frame = s.quick ? 32 : 64;
    std::printf("## 4. Flicker under a slow zoom\n\n");
    std::printf("%d frames of %d² pixels, pixel size 1 → 64 exemplar pixels (×%.3f per frame: content moves < 0.7 px "
                "between frames). Flicker = mean ‖F_{t+1}(p) − F_t(p)‖ at fixed pixels p, linear RGB ×1000, per third "
                "of the zoom.\n\n",
                frames, frame, std::pow(64.0, 1.0 / (frames - 1)));
    std::printf("| input | rendering | 1–4 px | 4–16 px | 16–64 px | whole zoom |\n|---|---|---|---|---|---|\n");
    for (const auto& [name, input] : inputs) {
        const TilingNoise& noise = *input.first;
        const ColourMapFilter& map = *input.second;
        const double cx = 0.37 * noise.width(), cy = 0.61 * noise.height();
        const std::pair<const char*, std::function<Rgb(double, double, double)>> renderings[] = {
            {"point-sampled (no filtering)", [&](double x, double y, double) { const Moments m = noise.point(x, y); return map.point(m.mean[0], m.mean[1]); }},
            {"mean only: S(μ̂) (a MIP-mapped noise)", [&](double x, double y, double px) {
                 const Moments m = noise.footprint_estimate(x, y, Footprint2D::square(px), tap_estimator.sampling);
                 return map.point(m.mean[0], m.mean[1]); }},
            {"paper: Ŝ(μ̂, σ̂), 1 texel, rounded level", [&](double x, double y, double px) {
                 const Moments m = noise.footprint_estimate(x, y, Footprint2D::square(px), paper_estimator.sampling);
                 return filtered(map, m, m, ColourMapMethod::reference); }},
            {"stochtex: Ŝ(μ̂, σ̂), taps, interpolated, covariance", [&](double x, double y, double px) {
                 const Moments m = noise.footprint_estimate(x, y, Footprint2D::square(px), tap_estimator.sampling);
                 return filtered(map, m, m, ColourMapMethod::covariance); }},
        };
        for (const auto& [label, render_pixel] : renderings) {
            const std::vector<double> change = zoom_flicker(render_pixel, cx, cy, frame, frames, 1, 64);
            double third[3] = {0, 0, 0}, all = 0;
            int count[3] = {0, 0, 0};
            for (std::size_t t = 0; t < change.size(); ++t) {
                const int part = std::min(2, int(3 * t / change.size()));
                third[part] += change[t], count[part] += 1, all += change[t];
            }
            std::printf("| %s | %s | %.1f | %.1f | %.1f | %.1f |\n", name, label, 1000 * third[0] / count[0], 1000 * third[1] / count[1],
                        1000 * third[2] / count[2], 1000 * all / change.size());
            std::fflush(stdout);
        }
    }
    std::printf("\n");
}

// ---- 5. LEAN -------------------------------------------------------------------------------------

void lean_table(const std::vector<std::vector<double>>& heights, int side, const Settings& s)
{
    // Slopes of the height noise (central differences, strength chosen for slopes σ ≈ 0.3).
    std::vector<std::vector<double>> slopes(2, std::vector<double>(heights[0].size()));
    auto h = [&](int x, int y) { return heights[0][std::size_t((y + side) % side) * side + std::size_t((x + side) % side)]; };
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            slopes[0][std::size_t(y) * side + x] = 0.5 * (h(x + 1, y) - h(x - 1, y));
            slopes[1][std::size_t(y) * side + x] = 0.5 * (h(x, y + 1) - h(x, y - 1));
        }
    double sum2 = 0;
    for (double v : slopes[0]) sum2 += v * v;
    const double gain = 0.3 / std::sqrt(sum2 / slopes[0].size());
    for (auto& plane : slopes)
        for (double& v : plane) v *= gain;
    const TilingNoise noise = make_noise(slopes, side);
    const NoiseRaster raster = sample_noise(noise, 0, 0, s.size);
    const double base = 0.05 * 0.05;
    std::printf("## 5. Normal maps: LEAN vs the filtered mean normal\n\n");
    std::printf("Height = the noise-a exemplar, slopes σ = 0.3, base roughness 0.05; specular NDF D(h) for three half "
                "vectors (0°, 20°, 40° from the normal); error relative to the reference's mean D, mean (95th percentile) %%.\n\n");
    std::printf("| k px | half vector | mean normal: D(μ̂) | LEAN: D(μ̂, Σ̂) | LEAN with the exact (μ, Σ) |\n|---|---|---|---|---|\n");
    for (int k : footprints(s)) {
        if (k == 1) continue;
        for (double degrees : {0.0, 20.0, 40.0}) {
            const double t = degrees * M_PI / 180;
            const Direction half{std::sin(t) * 0.6, std::sin(t) * 0.8, std::cos(t)};
            const MomentColour ndf = [&](const Moments& m) { const float d = float(facet_ndf(m.mean[0], m.mean[1], base, half)); return Rgb{d, d, d}; };
            const std::vector<NoiseBlock> blocks = noise_blocks(raster, k, ndf);
            double reference_mean = 0;
            for (const NoiseBlock& b : blocks) reference_mean += b.box_colour[0];
            reference_mean /= blocks.size();
            std::vector<double> naive, lean, exact;
            for (const NoiseBlock& b : blocks) {
                const Moments m = noise.footprint_estimate(b.x, b.y, Footprint2D::square(k), tap_estimator.sampling);
                naive.push_back(100 * std::abs(facet_ndf(m.mean[0], m.mean[1], base, half) - b.box_colour[0]) / reference_mean);
                lean.push_back(100 * std::abs(lean_ndf(m, base, half) - b.box_colour[0]) / reference_mean);
                exact.push_back(100 * std::abs(lean_ndf(b.exact, base, half) - b.box_colour[0]) / reference_mean);
            }
            std::printf("| %d | %.0f° | %s | %s | %s |\n", k, degrees, cell(summarise(naive), 1).c_str(), cell(summarise(lean), 1).c_str(),
                        cell(summarise(exact), 1).c_str());
        }
        std::fflush(stdout);
    }
    std::printf("\n");
}

// ---- Pictures --------------------------------------------------------------------------------------

/// Rows of cells (cell² pixels each) rendered by functions of (x, y, pixel size), one column per footprint.
void write_grid(const std::string& path, const std::vector<std::function<Rgb(double, double, double)>>& rows,
                const std::vector<double>& scales, int cell_size, double cx, double cy)
{
    Image image(int(scales.size()) * (cell_size + 4) - 4, int(rows.size()) * (cell_size + 4) - 4, 3);
    std::fill(image.pixels.begin(), image.pixels.end(), 1.0f);
    for (std::size_t r = 0; r < rows.size(); ++r)
        for (std::size_t c = 0; c < scales.size(); ++c)
            for (int j = 0; j < cell_size; ++j)
                for (int i = 0; i < cell_size; ++i) {
                    const double px = scales[c];
                    const Rgb v = rows[r](cx + (i + 0.5 - 0.5 * cell_size) * px, cy + (j + 0.5 - 0.5 * cell_size) * px, px);
                    for (int ch = 0; ch < 3; ++ch) image.at(int(c) * (cell_size + 4) + i, int(r) * (cell_size + 4) + j, ch) = v[ch];
                }
    write_image(path, image);
    std::printf("wrote %s\n", path.c_str());
}

/// S̄ of a pixel by stratified supersampling (at most 32² samples).
Rgb supersampled(const std::function<Rgb(double, double)>& sample, double x, double y, double px)
{
    const int n = std::clamp(int(std::ceil(px)), 1, 32);
    double sum[3] = {0, 0, 0};
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Rgb v = sample(x + ((i + 0.5) / n - 0.5) * px, y + ((j + 0.5) / n - 0.5) * px);
            for (int c = 0; c < 3; ++c) sum[c] += v[c];
        }
    return {float(sum[0] / (n * n)), float(sum[1] / (n * n)), float(sum[2] / (n * n))};
}

void colour_map_figure(const std::string& path, const TilingNoise& noise, const ColourMapFilter& map)
{
    auto point = [&](double x, double y) { const Moments m = noise.point(x, y); return map.point(m.mean[0], m.mean[1]); };
    auto estimate = [&](const Estimator& e, ColourMapMethod method) {
        return [&noise, &map, &e, method](double x, double y, double px) {
            const Moments m = noise.footprint_estimate(x, y, Footprint2D::square(px), e.sampling);
            return map.filtered(m.mean[0], m.mean[1], pair(m), method);
        };
    };
    write_grid(path,
               {[&](double x, double y, double px) { return supersampled(point, x, y, px); },
                estimate(tap_estimator, ColourMapMethod::covariance), estimate(paper_estimator, ColourMapMethod::reference),
                [&](double x, double y, double) { return point(x, y); }},
               {1, 4, 16, 64}, 96, 0.37 * noise.width(), 0.61 * noise.height());
}

}  // namespace

int main(int argc, char** argv)
{
    Settings s;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out" && i + 1 < argc) s.out = argv[++i];
        else if (arg == "--exemplars" && i + 1 < argc) s.exemplars = argv[++i];
        else if (arg == "--size" && i + 1 < argc) s.size = std::atoi(argv[++i]);
        else if (arg == "--quick") s.quick = true;
        else {
            std::fprintf(stderr, "usage: tiling_report [--out DIR] [--exemplars DIR] [--size N] [--quick]\n");
            return 2;
        }
    }
    try {
        const auto start = std::chrono::steady_clock::now();
        std::string a = s.exemplars + "/concrete.png", b = s.exemplars + "/sandy_rock.png";
        bool transpose_b = false;
        if (!fs::exists(a) || !fs::exists(b)) {
            a = b = STOCHTEX_SOURCE_DIR "/data/exemplars/concrete_512.png";
            transpose_b = true;
            s.size = std::min(s.size, 512);
            std::printf("(../shared/exemplars not found: using the committed 512² exemplar and its transpose)\n\n");
        }
        const int side = s.size;
        const std::vector<std::vector<double>> pair_planes{noise_plane(a, side, false), noise_plane(b, side, transpose_b)};
        std::printf("# Tiling estimator report\n\nNoise pair: luminance of %s and %s%s, %d² periodic crops mapped to [0, 1] "
                    "(mean ± 3σ); triangle edge %.0f px; brute-force window %d² samples.\n\n",
                    fs::path(a).filename().c_str(), fs::path(b).filename().c_str(), transpose_b ? " (transposed)" : "", side,
                    side / (2 * std::sqrt(3.0)), side);
        identities(pair_planes, side);
        const TilingNoise pair_noise = make_noise(pair_planes, side);
        const NoiseRaster pair_raster = sample_noise(pair_noise, 0.3 * side, 0.2 * side, side);
        moment_table(pair_noise, pair_raster, s);

        PhasorFieldOptions phasor;
        phasor.size = side;
        phasor.frequency = 1.0 / 32;
        const auto field = phasor_field(phasor);
        const std::vector<std::vector<double>> phasor_planes{{field[0].begin(), field[0].end()}, {field[1].begin(), field[1].end()}};
        const TilingNoise phasor_noise = make_noise(phasor_planes, side);
        const NoiseRaster phasor_raster = sample_noise(phasor_noise, 0.3 * side, 0.2 * side, side);

        const ColourMapFilter green = colour_map("green"), rgb = colour_map("rgb"), square = colour_map("phasor-square"),
                              sine = colour_map("phasor-sine");
        std::printf("## 3. Colour-mapped noise: ‖Ŝ − S̄‖\n\n");
        lookup_table(green, rgb);
        const auto g = colour_table("Smooth map (green)", pair_noise, pair_raster, green, s);
        const auto r = colour_table("Saturated map (rgb)", pair_noise, pair_raster, rgb, s);
        const auto p = colour_table("Phasor noise, square profile (f = 1/32 cycles/px)", phasor_noise, phasor_raster, square, s);
        const auto q = colour_table("Phasor noise, sine profile", phasor_noise, phasor_raster, sine, s);
        std::printf("### Summary: mean ‖Ŝ(μ̂, σ̂) − S̄‖ ×1000, paper method → stochtex default\n\n| k px | green | rgb | phasor square | phasor sine |\n|---|---|---|---|---|\n");
        const std::vector<int> ks = footprints(s);
        for (std::size_t i = 0; i < ks.size(); ++i)
            std::printf("| %d | %.2f → %.2f | %.2f → %.2f | %.2f → %.2f | %.2f → %.2f |\n", ks[i], 1000 * g[i].first, 1000 * g[i].second,
                        1000 * r[i].first, 1000 * r[i].second, 1000 * p[i].first, 1000 * p[i].second, 1000 * q[i].first,
                        1000 * q[i].second);
        std::printf("\n");
        flicker_table({{"rgb map", {&pair_noise, &rgb}}, {"phasor square", {&phasor_noise, &square}}}, s);
        lean_table({pair_planes[0]}, side, s);
        if (!s.out.empty()) {
            fs::create_directories(s.out);
            colour_map_figure(s.out + "/tiling-filter-rgb.jpg", pair_noise, rgb);
            colour_map_figure(s.out + "/tiling-filter-phasor.jpg", phasor_noise, square);
        }
        std::printf("(report took %.0f s)\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tiling_report: %s\n", e.what());
        return 1;
    }
    return 0;
}
