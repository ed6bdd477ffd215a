// The raster paths of the tiling and ptm models (docs/architecture.md, "Evaluation"): eval_region
// and eval_solid_region are bit-identical to eval() / eval_solid() for every tiling output
// (colour, colour map, phasor), for multi-tap and anisotropic footprints, periodic or not, and
// for the ptm model bounded and unbounded, odd map sizes included; renders are bit-identical for
// any thread count; the packed single-precision tiling path stays within its stated tolerance
// (in σ) of the double estimator and reference colour-map lookup; and the tabulated histogram
// maps of the tiling colour output stay within their stated tolerance of the Gauss–Hermite
// rule they tabulate (and no further from the true expectation than that rule).
#include "test_support.h"

#include "colour/tabulated_colour_mapping.h"
#include "models/tiling/tiling_texture.h"

#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>
#include <stochtex/models/tiling.h>

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace stochtex {
namespace {

const Image& photo()
{
    static const Image image = read_image_linear(test::repo_exemplar("concrete_512.png"));
    return image;
}

TextureDescription tiling_colour()
{
    AnalysisOptions options;
    options.model = "tiling";
    options.histogram = HistogramMode::on;
    return analyze(photo(), options);
}

TextureDescription ptm_description(int width, int height, bool unbounded)
{
    PtmMaps maps;
    maps.colour = PtmColour::lrgb;
    maps.coefficients = Image(width, height, ptm_channel_count(maps.colour));
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(0, 1);
    for (std::size_t i = 0; i < maps.coefficients.pixel_count(); ++i) {
        float* texel = &maps.coefficients.pixels[i * maps.coefficients.channels];
        texel[0] = 1.0f + 0.2f * unit(random);
        for (int k = 1; k < 6; ++k) texel[k] = 0.1f * (unit(random) - 0.5f);
        for (int c = 0; c < 3; ++c) texel[6 + c] = 0.7f + 0.6f * unit(random);
    }
    TextureDescription d = make_ptm_description(std::move(maps), {0.5, 0.2, 0.84261});
    d.parameters.get<PtmParameters>().unbounded = unbounded;
    return d;
}

struct Case {
    std::string name;
    TextureDescription description;
};

std::vector<Case> cases()
{
    TilingSourceOptions source;
    source.exemplar_size = 128;
    // A non-default blend contrast sharpens the packed weights outside the vectorised address
    // stage: every path must still agree with the point evaluation and the double estimator.
    TextureDescription sharpened = tiling_colour();
    sharpened.parameters.get<TilingParameters>().blend_contrast = 4;
    return {{"tiling colour", tiling_colour()},
            {"tiling colour contrast 4", sharpened},
            {"tiling colour map", colour_mapped_texture(photo(), photo(), "rgb", source)},
            {"tiling phasor", phasor_texture("phasor-square", 1.0 / 16, source)},
            {"ptm", ptm_description(32, 32, false)},
            {"ptm odd sizes", ptm_description(23, 17, false)},
            {"ptm unbounded", ptm_description(32, 32, true)}};
}

/// Footprints in exemplar pixels: a point, below a pixel, the 2×2-tap case, anisotropic and
/// rotated (more taps along one axis), a huge one (the coarsest level).
std::vector<Footprint2D> footprints_px() { return {{0, 0, 0, 0}, {0.6, 0, 0, 0.6}, {4, 0, 0, 4}, {9, 2.5, -1, 2}, {3000, 0, 0, 3000}}; }

TEST(RasterPaths, RegionsEqualPointEvaluationBitForBit)
{
    for (const Case& c : cases())
        for (const bool periodic : {false, true}) {
            const double ppu = c.description.pixels_per_unit;
            const auto texture = periodic ? make_periodic_texture(c.description, {3, 2}) : make_texture(c.description);
            for (const Footprint2D& f : footprints_px()) {
                RasterRegion region;
                region.origin_u = -1.37, region.origin_v = 0.61;
                region.du = std::max(f.dudx, 0.9) / ppu, region.dv = std::max(f.dvdy, 1.1) / ppu;
                region.x0 = 3, region.y0 = 7, region.width = 37, region.height = 5;
                region.footprint = f.scaled(1 / ppu);
                std::vector<float> raster(std::size_t(region.width) * region.height * 3);
                texture->eval_region(region, raster.data());
                SolidRegion slice{region, 0.25};
                std::vector<float> solid(raster.size());
                texture->eval_solid_region(slice, RgbOutput::interleaved(solid.data()));
                for (int j = 0; j < region.height; ++j)
                    for (int i = 0; i < region.width; ++i) {
                        const Rgb point = texture->eval({region.u(i), region.v(j)}, region.footprint);
                        SurfacePoint surface;
                        surface.p = {region.u(i), region.v(j), slice.w};
                        surface.dpdx = {region.footprint.dudx, region.footprint.dvdx, 0};
                        surface.dpdy = {region.footprint.dudy, region.footprint.dvdy, 0};
                        const Rgb solid_point = texture->eval_solid(surface);
                        for (int k = 0; k < 3; ++k) {
                            const std::size_t at = (std::size_t(j) * region.width + i) * 3 + k;
                            ASSERT_EQ(raster[at], point[k]) << c.name << (periodic ? " periodic" : "") << ", footprint "
                                                            << f.dudx << ", pixel " << i << ", " << j;
                            ASSERT_EQ(solid[at], solid_point[k]) << c.name << " solid, footprint " << f.dudx << ", pixel " << i
                                                                 << ", " << j;
                        }
                    }
            }
        }
}

TEST(RasterPaths, RendersAreBitIdenticalForAnyThreadCount)
{
    for (const Case& c : cases()) {
        const auto texture = make_texture(c.description);
        RenderSettings settings;
        settings.width = 96, settings.height = 61;
        settings.units_per_pixel = 4 / c.description.pixels_per_unit;
        settings.threads = 1;
        const Image one = render(*texture, settings);
        settings.threads = 3;
        EXPECT_EQ(one.pixels, render(*texture, settings).pixels) << c.name;
        settings.solid = true;
        const Image solid = render(*texture, settings);
        settings.threads = 1;
        EXPECT_EQ(solid.pixels, render(*texture, settings).pixels) << c.name << " solid";
    }
}

TEST(RasterPaths, TilingGivesTheSameBitsOnEveryInstructionSet)
{
    // The tiling kernels (address stage, lookups and mixture, the tabulated colour maps' row
    // lookup, the colour-map line quadrature) use lane-wise operations only: every Highway target
    // the CPU runs must give the default target's bits, for a raster (eval_region) and eval().
    for (const Case& c : cases()) {
        if (c.description.model != "tiling") continue;
        const auto texture = make_texture(c.description);
        const double ppu = c.description.pixels_per_unit;
        auto evaluate = [&] {
            std::vector<float> all;
            for (const Footprint2D& f : footprints_px()) {
                RasterRegion region;
                region.origin_u = -0.83, region.origin_v = 0.29;
                region.du = std::max(f.dudx, 0.9) / ppu, region.dv = std::max(f.dvdy, 1.1) / ppu;
                region.width = 29, region.height = 3;
                region.footprint = f.scaled(1 / ppu);
                std::vector<float> raster(std::size_t(region.width) * region.height * 3);
                texture->eval_region(region, raster.data());
                all.insert(all.end(), raster.begin(), raster.end());
                const Rgb point = texture->eval({region.u(5), region.v(1)}, region.footprint);
                all.insert(all.end(), point.begin(), point.end());
            }
            return all;
        };
        const std::vector<float> reference = evaluate();
        std::string targets;
        for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
            hwy::SetSupportedTargetsForTest(target);
            const std::vector<float> values = evaluate();
            ASSERT_EQ(values.size(), reference.size());
            for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], reference[i]) << c.name << ", " << hwy::TargetName(target) << ", value " << i;
            targets += std::string(" ") + hwy::TargetName(target);
        }
        hwy::SetSupportedTargetsForTest(0);
        std::printf("%s: identical values on:%s\n", c.name.c_str(), targets.c_str());
    }
}

/// Each RGB channel's σ over a set of colours.
std::array<double, 3> sigma_of(const std::vector<Rgb>& colours)
{
    std::array<double, 3> sigma{};
    for (int c = 0; c < 3; ++c) {
        double sum = 0, sum2 = 0;
        for (const Rgb& v : colours) sum += v[c], sum2 += double(v[c]) * v[c];
        const double mean = sum / colours.size();
        sigma[c] = std::sqrt(std::max(1e-30, sum2 / colours.size() - mean * mean));
    }
    return sigma;
}

TEST(RasterPaths, PackedEstimatorMatchesTheDoublePath)
{
    // The packed single-precision estimator (TilingRaster: what eval() and the batch methods
    // run) and the colour map's packed lookup (ColourMapFilter::lookup) against the double
    // estimator (TilingTexture::moments) and the reference lookup (ColourMapFilter::filtered)
    // they replace, for colour, colour map and phasor, at footprints from a point to the
    // coarsest level, anisotropic included. Errors in σ of each RGB channel of the texture's
    // point-sampled values (docs/models/tiling.md, "Precision", has the measured figures).
    for (const Case& c : cases()) {
        if (c.name.rfind("tiling", 0) != 0) continue;
        const TilingTexture texture(c.description);
        const double ppu = c.description.pixels_per_unit;
        const ColourMapFilter* map = texture.colour_map_filter();
        auto reference_colour = [&](const Moments& m) {
            if (!map) return texture.colour(m);  // colour: the same (tabulated) histogram maps
            return map->filtered(m.mean[0], m.mean[1], {m.moment(0, 0), m.moment(0, 1), m.moment(1, 1)}, texture.options().colour_map);
        };
        std::array<double, 3> unit{};
        double worst = 0, worst_rms = 0;
        for (const Footprint2D& f : footprints_px()) {
            std::vector<Rgb> packed, reference;
            const Footprint2D footprint = f.scaled(1 / ppu);
            for (int j = 0; j < 48; ++j)
                for (int i = 0; i < 48; ++i) {
                    const Vec2 uv{(i * 3.7 + 0.3) / ppu, (j * 2.9 + 0.6) / ppu};
                    packed.push_back(texture.eval(uv, footprint));
                    reference.push_back(reference_colour(texture.moments(uv, footprint)));
                }
            if (f.dudx == 0) unit = sigma_of(reference);  // the first footprint: a point
            std::array<double, 3> max{}, rms{};
            for (int k = 0; k < 3; ++k) {
                double square = 0;
                for (std::size_t n = 0; n < packed.size(); ++n) {
                    const double d = std::abs(double(packed[n][k]) - reference[n][k]) / unit[std::size_t(k)];
                    max[std::size_t(k)] = std::max(max[std::size_t(k)], d), square += d * d;
                }
                rms[std::size_t(k)] = std::sqrt(square / packed.size());
                worst = std::max(worst, max[std::size_t(k)]), worst_rms = std::max(worst_rms, rms[std::size_t(k)]);
            }
            std::printf("%-18s footprint %6g px: max %.2e %.2e %.2e sigma, RMS %.2e %.2e %.2e sigma\n", c.name.c_str(), f.dudx,
                        max[0], max[1], max[2], rms[0], rms[1], rms[2]);
        }
        EXPECT_LT(worst, 1e-3) << c.name;
        EXPECT_LT(worst_rms, 5e-5) << c.name;
    }
}

/// E[f_c(z + σ Z)] by a fine midpoint sum (the truth both the rule and the table approximate).
double expectation(const ColourMapping& exact, int c, double z, double sigma)
{
    double sum = 0, total = 0;
    for (int k = 0; k < 2000; ++k) {
        const double t = -8 + 16 * (k + 0.5) / 2000, w = std::exp(-0.5 * t * t);
        sum += w * exact.map_channel(c, z + sigma * t, 0), total += w;
    }
    return sum / total;
}

TEST(TabulatedColourMapping, IsAsCloseToTheTrueExpectationAsTheGaussHermiteRule)
{
    // In units of each mapped channel's σ, over the table's domain (z beyond the knots, σ up to
    // σ_max and past it). The table interpolates the 12-node rule's values: within 1.5e-2 σ of
    // them everywhere (the worst next to the map's end knots, where f has a kink that the
    // rule's nodes cross one by one), within 1e-3 σ away from them — while the rule itself is
    // up to ~0.2 σ from the true E[f(z + σZ)] there; the table is never further from the truth
    // than the rule. docs/architecture.md, "Evaluation".
    const TextureDescription d = tiling_colour();
    const TabulatedColourMapping table(d, {1, 1, 1});
    int mapped = 0;
    for (int c = 0; c < 3; ++c) {
        if (!table.exact().has_map(c)) continue;
        ++mapped;
        // The channel's σ after mapping: the spread of f(Z), Z ~ N(0, 1).
        const double mean = expectation(table.exact(), c, 0, 1);
        double second = 0, total = 0;
        for (int k = 0; k < 4000; ++k) {
            const double z = -8 + 16 * (k + 0.5) / 4000, w = std::exp(-0.5 * z * z), v = table.exact().map_channel(c, z, 0);
            second += w * (v - mean) * (v - mean), total += w;
        }
        const double sigma = std::sqrt(second / total);
        double rule_error = 0, table_error = 0, versus_rule = 0, inner = 0;
        for (int i = 0; i <= 240; ++i)
            for (int j = 1; j <= 40; ++j) {
                const double z = -6 + 12.0 * i / 240 + 1e-3 * j, s = 2.1 * j / 40 - 0.05;
                if (s < 1e-4) continue;
                const double truth = expectation(table.exact(), c, z, s);
                const double rule = table.exact().map_channel(c, z, s), tabulated = table.map_channel(c, z, s);
                rule_error = std::max(rule_error, std::abs(rule - truth) / sigma);
                table_error = std::max(table_error, std::abs(tabulated - truth) / sigma);
                versus_rule = std::max(versus_rule, std::abs(tabulated - rule) / sigma);
                // Away from the end knots' kinks the table follows the rule closely.
                if (std::abs(std::abs(z) - 3) > 4 * s + 0.1) inner = std::max(inner, std::abs(tabulated - rule) / sigma);
            }
        std::printf("channel %d: max error vs the true expectation: rule %.3g sigma, table %.3g sigma; "
                    "table vs rule %.3g sigma (%.3g away from the end knots)\n",
                    c, rule_error, table_error, versus_rule, inner);
        EXPECT_LE(table_error, rule_error + 1e-4) << "channel " << c;
        EXPECT_LT(versus_rule, 1.5e-2) << "channel " << c;
        EXPECT_LT(inner, 1e-3) << "channel " << c;
    }
    EXPECT_GT(mapped, 0);
}

TEST(TabulatedColourMapping, ChangesAFilteredRenderByLittle)
{
    // What tabulation changed in the tiling colour output: a 3.5× minified render (the
    // fingerprints' "tiling 2D scale 3.5") against the same moments mapped by the exact rule,
    // in units of each RGB channel's σ over the render: measured max 4.6e-3 σ, RMS 1.2e-4 σ.
    const TextureDescription d = tiling_colour();
    const TilingTexture texture(d);
    const ColourMapping exact(d, {1, 1, 1});
    const double upp = 3.5 / d.pixels_per_unit;
    const int n = 128;
    std::vector<Rgb> tabulated, reference;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Vec2 uv{(i + 0.5) * upp, (j + 0.5) * upp};
            const Moments m = texture.moments(uv, Footprint2D::square(upp));
            std::array<double, 3> spread{};
            for (int c = 0; c < 3; ++c) spread[c] = std::sqrt(std::max(0.0, m.moment(c, c)));
            tabulated.push_back(texture.eval(uv, Footprint2D::square(upp)));
            reference.push_back(exact.to_rgb({m.mean[0], m.mean[1], m.mean[2]}, spread));
        }
    for (int c = 0; c < 3; ++c) {
        double sum = 0, sum2 = 0, worst = 0, square = 0;
        for (std::size_t k = 0; k < reference.size(); ++k) {
            sum += reference[k][c], sum2 += double(reference[k][c]) * reference[k][c];
            const double difference = double(tabulated[k][c]) - reference[k][c];
            worst = std::max(worst, std::abs(difference)), square += difference * difference;
        }
        const double mean = sum / reference.size(), sigma = std::sqrt(sum2 / reference.size() - mean * mean);
        std::printf("RGB channel %d: max |tabulated − exact| = %.3g sigma, RMS %.3g sigma (sigma %.4g)\n", c, worst / sigma,
                    std::sqrt(square / reference.size()) / sigma, sigma);
        EXPECT_LT(worst / sigma, 1e-2) << "channel " << c;
        EXPECT_LT(std::sqrt(square / reference.size()) / sigma, 5e-4) << "channel " << c;
    }
}

}  // namespace
}  // namespace stochtex
