// The colour-map lookup's accuracy (docs/models/tiling.md, "Colour-mapped noise vector fields"):
//
//   1. the lookup alone, Ŝ(μ, Σ) from ColourMapFilter::lookup (what renders run) against the
//      quadrature oracle E[S(N)], N ~ 𝒩(μ, Σ) (ColourMapFilter::expected), on the named maps at
//      correlations up to a perfect one, with the lookup's time per call; a perfect one also
//      against a fine line integral (the oracle's own error there);
//   2. whole renders: a tiling texture's filtered eval() against the box-supersampled mean of its
//      point evaluations over the footprint (magnified, 1 px, minified 4–64×, anisotropic), for
//      the colour-map textures (one photo twice: a perfect correlation; the photo and its
//      transpose: nearly none) and phasor noise.
//
// Mean ‖· − truth‖ ×1000 in linear RGB. Usage: colour_map_accuracy [--quick]
#include <stochtex/footprint.h>
#include <stochtex/image.h>
#include <stochtex/texture.h>
#include <stochtex/models/tiling.h>

#include "photo_crop.h"
#include "models/tiling/colour_map_filter.h"
#include "models/tiling/colour_maps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace stochtex;

double distance(const Rgb& x, const Rgb& y)
{
    double s = 0;
    for (int c = 0; c < 3; ++c) s += double(x[c] - y[c]) * (x[c] - y[c]);
    return std::sqrt(s);
}

ColourMapFilter linear_map(const std::string& name)
{
    std::vector<float> map = named_colour_map(name, 256);
    for (float& v : map) v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
    return ColourMapFilter(map, 256);
}

/// Section 1's grid of lookups: spreads σ (σ_a), signs of the correlation and means (a, b).
template <typename Visit>
void for_each_spread_and_mean(const Visit& visit)
{
    for (double sigma : {0.003, 0.01, 0.03, 0.08, 0.15})
        for (double sign : {-1.0, 1.0})
            for (double ma : {0.35, 0.5, 0.62})
                for (double mb : {0.4, 0.55}) visit(sigma, sign, ma, mb);
}

void lookup_table()
{
    std::printf("## 1. The lookup alone: Ŝ(μ, Σ) (lookup()) vs E[S(N)] (expected())\n\n");
    std::printf("256² maps; σ_a ∈ {0.003, 0.01, 0.03, 0.08, 0.15}, σ_b = 0.8 σ_a (ρ = 1: σ_b = σ_a), ±ρ, means a ∈ {0.35, 0.5, "
                "0.62} × b ∈ {0.4, 0.55}; mean (max) ‖Ŝ − E[S]‖ ×1000; ns per lookup() call.\n\n");
    std::printf("| map | ρ | covariance lookup | ns/lookup |\n|---|---|---|---|\n");
    for (const char* name : {"green", "rgb", "phasor-square", "phasor-sine"}) {
        const ColourMapFilter map = linear_map(name);
        for (double rho : {0.0, 0.6, 0.9, 0.99, 1.0}) {
            double error = 0, worst = 0, seconds = 0;
            int count = 0, calls = 0;
            for_each_spread_and_mean([&](double sigma, double sign, double ma, double mb) {
                            const double ratio = rho == 1.0 ? 1.0 : 0.8;
                            const PairCovariance c{sigma * sigma, sign * rho * sigma * sigma * ratio, sigma * sigma * ratio * ratio};
                            const Rgb truth = map.expected(ma, mb, c);
                            const Rgb got = map.lookup(ma, mb, c, ColourMapMethod::covariance);
                            const auto start = std::chrono::steady_clock::now();
                            float sink = 0;
                            for (int r = 0; r < 200; ++r) sink += map.lookup(ma + 1e-9 * r, mb, c, ColourMapMethod::covariance)[0];
                            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                            calls += 200;
                            if (sink < 0) std::printf("?");
                            const double e = distance(got, truth);
                            error += e, worst = std::max(worst, e), ++count;
                        });
            std::printf("| %s | %.2f | %.2f (%.1f) | %.0f |\n", name, rho, 1000 * error / count, 1000 * worst, 1e9 * seconds / calls);
        }
    }
    std::printf("\n");
}

/// A perfect correlation of equal spreads (ρ = 1 above) against a fine line integral of the map:
/// the oracle's 64 uniform nodes per axis are themselves off by up to ~1e-2 there on the sharp
/// maps (a step moves its sum by a node's weight), so the ρ = 1 row above measures the oracle too.
void perfect_correlation_table()
{
    std::printf("## 1b. ρ = 1 against a fine line integral\n\n");
    std::printf("N = μ + σ t (1, ±1), E[S(N)] by 20000 midpoints over ±7σ of point() (the spreads and means of section 1); "
                "mean (max) ‖· − line integral‖ ×1000 of lookup() and of the oracle expected().\n\n");
    std::printf("| map | lookup() | expected() |\n|---|---|---|\n");
    for (const char* name : {"green", "rgb", "phasor-square", "phasor-sine"}) {
        const ColourMapFilter map = linear_map(name);
        double error[2] = {0, 0}, worst[2] = {0, 0};
        int count = 0;
        for_each_spread_and_mean([&](double sigma, double sign, double ma, double mb) {
                        double sum[3] = {0, 0, 0}, total = 0;
                        constexpr int nodes = 20000;
                        for (int k = 0; k < nodes; ++k) {
                            const double t = -7 + 14 * (k + 0.5) / nodes, w = std::exp(-0.5 * t * t);
                            const Rgb v = map.point(std::clamp(ma + sigma * t, 0.0, 1.0), std::clamp(mb + sign * sigma * t, 0.0, 1.0));
                            for (int c = 0; c < 3; ++c) sum[c] += w * v[c];
                            total += w;
                        }
                        const Rgb truth{float(sum[0] / total), float(sum[1] / total), float(sum[2] / total)};
                        const PairCovariance c{sigma * sigma, sign * sigma * sigma, sigma * sigma};
                        const double e[2] = {distance(map.lookup(ma, mb, c, ColourMapMethod::covariance), truth),
                                             distance(map.expected(ma, mb, c), truth)};
                        for (int m = 0; m < 2; ++m) error[m] += e[m], worst[m] = std::max(worst[m], e[m]);
                        ++count;
                    });
        std::printf("| %s | %.2f (%.1f) | %.2f (%.1f) |\n", name, 1000 * error[0] / count, 1000 * worst[0], 1000 * error[1] / count,
                    1000 * worst[1]);
    }
    std::printf("\n");
}

struct Case {
    const char* name;
    Footprint2D footprint;  // exemplar pixels
};

/// The box-supersampled mean of point evaluations over the footprint's parallelogram.
Rgb supersampled(const Texture& t, const Vec2& uv, const Footprint2D& f)
{
    const int nx = std::clamp(int(std::ceil(2 * std::hypot(f.dudx, f.dvdx))), 4, 32);
    const int ny = std::clamp(int(std::ceil(2 * std::hypot(f.dudy, f.dvdy))), 4, 32);
    double sum[3] = {0, 0, 0};
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const double s = (i + 0.5) / nx - 0.5, r = (j + 0.5) / ny - 0.5;
            const Rgb v = t.eval({uv[0] + s * f.dudx + r * f.dudy, uv[1] + s * f.dvdx + r * f.dvdy}, Footprint2D::point());
            for (int c = 0; c < 3; ++c) sum[c] += v[c];
        }
    const double n = double(nx) * ny;
    return {float(sum[0] / n), float(sum[1] / n), float(sum[2] / n)};
}

void render_table(bool quick)
{
    const Image photo = read_image_linear(STOCHTEX_SOURCE_DIR "/data/exemplars/concrete_512.png");
    const Image transposed = bench::transposed(photo);
    const TilingSourceOptions source;
    const std::pair<const char*, TextureDescription> textures[] = {
        {"colour map rgb, one photo twice (ρ = 1)", colour_mapped_texture(photo, photo, "rgb", source)},
        {"colour map rgb, photo and transpose", colour_mapped_texture(photo, transposed, "rgb", source)},
        {"colour map green, one photo twice", colour_mapped_texture(photo, photo, "green", source)},
        {"phasor square, 1/16", phasor_texture("phasor-square", 1.0 / 16, source)},
        {"phasor sine, 1/16", phasor_texture("phasor-sine", 1.0 / 16, source)},
    };
    const double c30 = std::cos(0.52), s30 = std::sin(0.52);
    const Case cases[] = {
        {"0.25 px (magnified)", Footprint2D::square(0.25)},
        {"1 px", Footprint2D::square(1)},
        {"4 px", Footprint2D::square(4)},
        {"16 px", Footprint2D::square(16)},
        {"64 px", Footprint2D::square(64)},
        {"16 × 2 px at 30°", {16 * c30, 16 * s30, -2 * s30, 2 * c30}},
    };
    const int pixels = quick ? 150 : 600;
    std::printf("## 2. Renders: filtered eval() vs the supersampled mean of point evaluations\n\n");
    std::printf("%d random positions per cell, supersampling 4–32 per footprint axis; mean (95th percentile) ×1000, linear RGB.\n\n",
                pixels);
    std::printf("| texture |");
    for (const Case& c : cases) std::printf(" %s |", c.name);
    std::printf("\n|---|");
    for (std::size_t i = 0; i < std::size(cases); ++i) std::printf("---|");
    std::printf("\n");
    for (const auto& [name, description] : textures) {
        const std::unique_ptr<Texture> texture = make_texture(description);
        const double ppu = description.pixels_per_unit;
        std::printf("| %s |", name);
        for (const Case& c : cases) {
            std::mt19937 random(11);
            std::uniform_real_distribution<double> where(0, 4096);
            const Footprint2D f = c.footprint.scaled(1 / ppu);
            std::vector<double> errors;
            for (int p = 0; p < pixels; ++p) {
                const Vec2 uv{where(random) / ppu, where(random) / ppu};
                errors.push_back(distance(texture->eval(uv, f), supersampled(*texture, uv, f)));
            }
            double mean = 0;
            for (double e : errors) mean += e;
            std::sort(errors.begin(), errors.end());
            std::printf(" %.2f (%.1f) |", 1000 * mean / pixels, 1000 * errors[std::size_t(0.95 * (pixels - 1))]);
            std::fflush(stdout);
        }
        std::printf("\n");
    }
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv)
{
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    lookup_table();
    perfect_correlation_table();
    render_table(quick);
}
