// The ptm model's mathematics (docs/models/ptm.md): the Legendre re-parameterisation (exact
// matrices, ψ distances are function distances), the fit (exact for biquadratic data, the
// closed-form leave-one-out equals refitting), the light sidecars' strict parsing, the
// projection-kernel search (the same candidates as exhaustive search), quilting, the .stex
// block and its coefficient file, the texture's MIP levels and the light hook.
#include "models/ptm/legendre_basis.h"
#include "models/ptm/patch_search.h"
#include "models/ptm/ptm_functions.h"
#include "numerics/random.h"
#include "test_support.h"

#include <stochtex/error.h>
#include <stochtex/lighting.h>
#include <stochtex/mip_image.h>
#include <stochtex/models/ptm.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>
#include <stochtex/models/ptm_parameters.h>

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

namespace fs = std::filesystem;
using namespace stochtex;

namespace {

using legendre::Terms;

Terms random_terms(SplitMix64& random, double scale = 1)
{
    Terms t{};
    for (double& v : t) v = scale * random.gaussian();
    return t;
}

/// The 3-point Gauss–Legendre rule: exact on [−1, 1] for polynomials of degree ≤ 5, so exact
/// for products of two biquadratics in each variable (degree 4).
constexpr double gauss_nodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
constexpr double gauss_weights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};

/// ∫∫ over [−1, 1]² of (g1 − g2)², g given in the monomial basis, by a rule of n × n midpoints.
double midpoint_distance(const Terms& a1, const Terms& a2, int n)
{
    double sum = 0;
    const double h = 2.0 / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Terms m = legendre::monomials(-1 + (i + 0.5) * h, -1 + (j + 0.5) * h);
            const double d = legendre::dot(a1, m) - legendre::dot(a2, m);
            sum += d * d * h * h;
        }
    return sum;
}

void write_text(const fs::path& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
}

/// Maps whose every texel's functions are positive over the light disk (b0 dominates), so
/// relighting never clamps.
PtmMaps random_maps(PtmColour colour, int width, int height, std::uint64_t seed)
{
    SplitMix64 random(seed);
    PtmMaps maps;
    maps.colour = colour;
    maps.coefficients = Image(width, height, ptm_channel_count(colour));
    for (std::size_t i = 0; i < maps.coefficients.pixel_count(); ++i) {
        float* texel = &maps.coefficients.pixels[i * maps.coefficients.channels];
        const int functions = colour == PtmColour::lrgb ? 1 : 3;
        for (int f = 0; f < functions; ++f) {
            texel[f * 6] = float(1.0 + 0.2 * random.uniform());
            for (int k = 1; k < 6; ++k) texel[f * 6 + k] = float(0.08 * random.gaussian());
        }
        if (colour == PtmColour::lrgb)
            for (int c = 0; c < 3; ++c) texel[6 + c] = float(0.7 + 0.6 * random.uniform());
    }
    return maps;
}

std::vector<Image> photos_of(const PtmMaps& maps, const std::vector<Vec3>& lights, double noise, std::uint64_t seed)
{
    SplitMix64 random(seed);
    std::vector<Image> photos;
    for (const Vec3& l : lights) {
        photos.push_back(relight(maps, l));
        for (float& v : photos.back().pixels) v = float(std::max(0.0, v + noise * random.gaussian()));
    }
    return photos;
}

}  // namespace

// ---- Legendre basis --------------------------------------------------------------------------------

TEST(LegendreBasis, IsOrthonormalOnTheSquare)
{
    double worst = 0;
    for (int p = 0; p < 6; ++p)
        for (int q = 0; q < 6; ++q) {
            double integral = 0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) {
                    const Terms b = legendre::legendre(gauss_nodes[i], gauss_nodes[j]);
                    integral += gauss_weights[i] * gauss_weights[j] * b[p] * b[q];
                }
            worst = std::max(worst, std::fabs(integral - (p == q ? 1.0 : 0.0)));
        }
    EXPECT_LT(worst, 1e-14);
}

TEST(LegendreBasis, MatrixAndInverseAreExact)
{
    const auto& m = legendre::monomial_to_legendre();
    const auto& inverse = legendre::legendre_to_monomial();
    double worst = 0;
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) {
            double sum = 0, sum_other = 0;
            for (int k = 0; k < 6; ++k) sum += m[r][k] * inverse[k][c], sum_other += inverse[r][k] * m[k][c];
            worst = std::max({worst, std::fabs(sum - (r == c)), std::fabs(sum_other - (r == c))});
        }
    EXPECT_LT(worst, 1e-15);
    // b = M a describes the same function: compare values at random light projections.
    SplitMix64 random(3);
    for (int trial = 0; trial < 100; ++trial) {
        const Terms a = random_terms(random);
        const Terms b = legendre::to_legendre(a);
        const double lu = 2 * random.uniform() - 1, lv = 2 * random.uniform() - 1;
        EXPECT_NEAR(legendre::dot(a, legendre::monomials(lu, lv)), legendre::dot(b, legendre::legendre(lu, lv)), 1e-13);
    }
}

TEST(LegendreBasis, RoundTripOfStoredCoefficientsIsExact)
{
    // Maps store floats. a → b → a in double, rounded back to float, gives the same floats for
    // coefficients of PTM-like magnitudes (components within a factor 2^6 or so of each other).
    // a5 = b0/2 − √45/12 (b4 + b5) cancels, so in general the round trip is exact relative to
    // the whole vector: |Δ| ≤ a few ε·‖a‖.
    SplitMix64 random(11);
    long long differences = 0;
    double worst_relative = 0;
    for (int trial = 0; trial < 100000; ++trial) {
        const double scale = std::ldexp(1.0, int(random.uniform() * 40) - 20);
        Terms a{}, wide{};
        for (double& v : a) v = float(scale * random.gaussian());
        for (double& v : wide) v = float(std::ldexp(random.gaussian(), int(random.uniform() * 40) - 20));
        const Terms back = legendre::to_monomial(legendre::to_legendre(a));
        const Terms b = legendre::to_legendre(a);
        Terms stored_b{};
        for (int k = 0; k < 6; ++k) stored_b[k] = float(b[k]);
        const Terms forth = legendre::to_legendre(legendre::to_monomial(stored_b));
        for (int k = 0; k < 6; ++k) differences += (float(back[k]) != float(a[k])) + (float(forth[k]) != float(stored_b[k]));
        const Terms wide_back = legendre::to_monomial(legendre::to_legendre(wide));
        double norm = 0, error = 0;
        for (int k = 0; k < 6; ++k) norm = std::max(norm, std::fabs(wide[k])), error = std::max(error, std::fabs(wide_back[k] - wide[k]));
        worst_relative = std::max(worst_relative, error / norm);
    }
    EXPECT_EQ(differences, 0);
    EXPECT_LT(worst_relative, 4e-16);
}

TEST(LegendreBasis, CoefficientDistanceIsTheFunctionDistance)
{
    SplitMix64 random(5);
    double worst_exact = 0, worst_midpoint = 0, monomial_ratio_min = 1e9, monomial_ratio_max = 0;
    for (int trial = 0; trial < 20; ++trial) {
        const Terms a1 = random_terms(random), a2 = random_terms(random);
        const Terms b1 = legendre::to_legendre(a1), b2 = legendre::to_legendre(a2);
        double coefficient_distance = 0, monomial_distance = 0;
        for (int k = 0; k < 6; ++k)
            coefficient_distance += (b1[k] - b2[k]) * (b1[k] - b2[k]), monomial_distance += (a1[k] - a2[k]) * (a1[k] - a2[k]);
        double quadrature = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const Terms m = legendre::monomials(gauss_nodes[i], gauss_nodes[j]);
                const double d = legendre::dot(a1, m) - legendre::dot(a2, m);
                quadrature += gauss_weights[i] * gauss_weights[j] * d * d;
            }
        worst_exact = std::max(worst_exact, std::fabs(quadrature / coefficient_distance - 1));
        worst_midpoint = std::max(worst_midpoint, std::fabs(midpoint_distance(a1, a2, 200) / coefficient_distance - 1));
        monomial_ratio_min = std::min(monomial_ratio_min, monomial_distance / coefficient_distance);
        monomial_ratio_max = std::max(monomial_ratio_max, monomial_distance / coefficient_distance);
    }
    EXPECT_LT(worst_exact, 1e-12);
    EXPECT_LT(worst_midpoint, 1e-4);  // the midpoint rule's O(h²) error at 200 × 200
    // Why the paper re-parameterises: distances of monomial coefficients are not function
    // distances (their ratio varies from pair to pair).
    EXPECT_GT(monomial_ratio_max / monomial_ratio_min, 1.5);
}

// ---- Fitting -------------------------------------------------------------------------------------

TEST(PtmFit, RecoversBiquadraticDataExactly)
{
    const std::vector<Vec3> lights = spiral_light_directions(20, 20);
    for (PtmColour colour : {PtmColour::lrgb, PtmColour::rgb}) {
        const PtmMaps truth = random_maps(colour, 12, 10, 7);
        const PtmFit fit = fit_ptm(photos_of(truth, lights, 0, 1), lights, colour);
        EXPECT_LT(fit.rmse, 1e-6 * fit.data_rms) << to_string(colour);
        EXPECT_LT(fit.loo_rmse, 1e-6 * fit.data_rms) << to_string(colour);
        double worst = 0;
        for (std::size_t i = 0; i < truth.coefficients.pixel_count(); ++i) {
            const auto expected = texel_colour_functions(colour, &truth.coefficients.pixels[i * truth.coefficients.channels]);
            const auto fitted = texel_colour_functions(colour, &fit.maps.coefficients.pixels[i * fit.maps.coefficients.channels]);
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 6; ++k) worst = std::max(worst, std::fabs(expected[c][k] - fitted[c][k]));
        }
        EXPECT_LT(worst, 1e-5) << to_string(colour);
    }
}

TEST(PtmFit, ClosedFormLeaveOneOutEqualsRefitting)
{
    const std::vector<Vec3> lights = spiral_light_directions(14, 15, 30);
    for (PtmColour colour : {PtmColour::lrgb, PtmColour::rgb}) {
        const std::vector<Image> photos = photos_of(random_maps(colour, 9, 7, 21), lights, 0.05, 4);
        const PtmFit fit = fit_ptm(photos, lights, colour);
        ASSERT_EQ(fit.loo_rmse_per_light.size(), lights.size());
        double sum_squares = 0;
        for (std::size_t held_out = 0; held_out < lights.size(); ++held_out) {
            std::vector<Image> others;
            std::vector<Vec3> other_lights;
            for (std::size_t i = 0; i < lights.size(); ++i)
                if (i != held_out) others.push_back(photos[i]), other_lights.push_back(lights[i]);
            const Image predicted = relight(fit_ptm(others, other_lights, colour).maps, lights[held_out]);
            double sum = 0;
            for (std::size_t k = 0; k < predicted.pixels.size(); ++k)
                sum += std::pow(double(photos[held_out].pixels[k]) - predicted.pixels[k], 2);
            sum_squares += sum;
            const double refit = std::sqrt(sum / double(predicted.pixels.size()));
            EXPECT_NEAR(fit.loo_rmse_per_light[held_out], refit, 1e-5 * refit) << to_string(colour) << " light " << held_out;
        }
        EXPECT_NEAR(fit.loo_rmse, std::sqrt(sum_squares / (double(lights.size()) * photos[0].pixels.size())), 1e-5 * fit.loo_rmse);
        EXPECT_GT(fit.loo_rmse, fit.rmse);  // predicting an unseen light is harder than fitting it
    }
}

TEST(PtmFit, RejectsUnusableInput)
{
    const std::vector<Vec3> lights = spiral_light_directions(8, 20);
    const std::vector<Image> photos = photos_of(random_maps(PtmColour::rgb, 4, 4, 1), lights, 0, 1);
    auto message = [](const auto& call) {
        try {
            call();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_TRUE(test::contains(message([&] { fit_ptm({photos.begin(), photos.begin() + 5}, {lights.begin(), lights.begin() + 5}, PtmColour::rgb); }),
                               "at least 6 photos"));
    // All lights on one azimuth: l_v is always 0, so no biquadratic is determined.
    std::vector<Vec3> line;
    for (int i = 0; i < 8; ++i) line.push_back({std::cos(0.2 + 0.15 * i), 0, std::sin(0.2 + 0.15 * i)});
    EXPECT_TRUE(test::contains(message([&] { fit_ptm(photos, line, PtmColour::rgb); }), "do not determine a biquadratic"));
    std::vector<Image> mixed = photos;
    mixed[3] = Image(5, 4, 3);
    EXPECT_TRUE(test::contains(message([&] { fit_ptm(mixed, lights, PtmColour::rgb); }), "photo 3 is 5x4"));
}

// ---- Light sidecars ---------------------------------------------------------------------------------

TEST(LightSidecar, ReadsLpAndJson)
{
    const fs::path dir = test::temp_dir("ptm-sidecar");
    write_text(dir / "lights.lp", "3\nimg 0.png 0 0 1\n\nimg1.png 0.6 0 0.8\r\nsub/img2.png 0 -0.6 0.8\n");
    const LightSet lp = read_light_set((dir / "lights.lp").string());
    ASSERT_EQ(lp.images.size(), 3u);
    EXPECT_EQ(lp.images[0], (dir / "img 0.png").string());  // names may contain spaces
    EXPECT_EQ(lp.images[2], (dir / "sub/img2.png").string());
    EXPECT_DOUBLE_EQ(lp.directions[1][0], 0.6);
    write_text(dir / "lights.json",
               R"({"lights": [{"image": "a.exr", "direction": [0, 0, 1]}, {"image": "b.exr", "direction": [0.6, 0, 0.8]}]})");
    const LightSet json = read_light_set((dir / "lights.json").string());
    ASSERT_EQ(json.images.size(), 2u);
    EXPECT_EQ(json.images[1], (dir / "b.exr").string());
    // write → read gives the same set.
    write_light_set((dir / "again.lp").string(), lp);
    const LightSet again = read_light_set((dir / "again.lp").string());
    EXPECT_EQ(again.images, lp.images);
    for (std::size_t i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(again.directions[i][k], lp.directions[i][k], 1e-8);
}

TEST(LightSidecar, ErrorsNameTheFileAndTheLineOrField)
{
    const fs::path dir = test::temp_dir("ptm-sidecar-errors");
    const struct {
        const char* name;
        const char* text;
        const char* expected;
    } cases[] = {
        {"count.lp", "2\na.png 0 0 1\n", "count.lp: the first line announces 2 lights, the file lists 1"},
        {"header.lp", "a.png 0 0 1\n", "header.lp:1: expected the number of lights"},
        {"number.lp", "1\na.png 0 x 1\n", "number.lp:2: direction component y is not a number: 'x'"},
        {"unit.lp", "1\na.png 0 0 2\n", "unit.lp:2: direction: (0, 0, 2) is not a unit vector"},
        {"below.lp", "1\na.png 0.6 0 -0.8\n", "below.lp:2: direction: (0.6, 0, -0.8) points below the surface"},
        {"twice.lp", "2\na.png 0 0 1\na.png 0.6 0 0.8\n", "twice.lp:3: image 'a.png' is listed twice (first on line 2)"},
        {"extra.lp", "1\na.png 0 0 1\nb.png 0 0 1\n", "extra.lp:3: more lights than the 1 announced"},
        {"short.lp", "1\n0 0 1\n", "short.lp:2: expected 'image x y z'"},
        {"key.json", R"({"lights": [{"image": "a", "direction": [0, 0, 1], "power": 2}]})", "key.json: lights[0].power: unknown field"},
        {"size.json", R"({"lights": [{"image": "a", "direction": [0, 1]}]})", "size.json: lights[0].direction: expected 3 numbers"},
        {"unitj.json", R"({"lights": [{"image": "a", "direction": [0, 0, 3]}]})", "unitj.json: lights[0].direction: (0, 0, 3) is not a unit vector"},
        {"twice.json", R"({"lights": [{"image": "a", "direction": [0, 0, 1]}, {"image": "a", "direction": [0, 0, 1]}]})",
         "twice.json: lights[1].image: 'a' is listed twice"},
        {"syntax.json", "{\"lights\": [}", "syntax.json: invalid JSON"},
        {"lights.txt", "1\na 0 0 1\n", "unknown light sidecar type '.txt'"},
    };
    for (const auto& c : cases) {
        write_text(dir / c.name, c.text);
        std::string message = "no error";
        try {
            read_light_set((dir / c.name).string());
        } catch (const Error& e) {
            message = e.what();
        }
        EXPECT_TRUE(test::contains(message, c.expected)) << c.name << ": " << message;
    }
}

// ---- Projection-kernel search --------------------------------------------------------------------

namespace {

/// A smooth random field plus fine noise, `channels` channels: like coefficient maps.
Image random_field(int width, int height, int channels, std::uint64_t seed)
{
    SplitMix64 random(seed);
    Image image(width, height, channels);
    std::vector<double> phases(channels * 8);
    for (double& p : phases) p = 2 * M_PI * random.uniform();
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
                double v = 0;
                for (int k = 0; k < 4; ++k)
                    v += std::sin(0.05 * (k + 1) * x + phases[c * 8 + k]) * std::cos(0.07 * (k + 1) * y + phases[c * 8 + 4 + k]);
                image.at(x, y, c) = float(v / (c + 1) + 0.3 * random.gaussian());
            }
    return image;
}

}  // namespace

TEST(PatchSearch, ProjectionReturnsExactlyTheExhaustiveCandidates)
{
    constexpr int block = 16, overlap = 4, channels = 6;
    const Image source = random_field(72, 64, channels, 9);
    const PatchSearch search(source, block, channels);
    SplitMix64 random(17);
    const std::vector<std::vector<BlockRect>> shapes = {
        {{0, 0, overlap, block}},                                            // left
        {{0, 0, block, overlap}},                                            // top
        {{0, 0, block, overlap}, {0, overlap, overlap, block - overlap}},    // L
        {{0, 0, block, overlap}, {0, block - overlap, block, overlap}, {0, overlap, overlap, block - 2 * overlap},
         {block - overlap, overlap, overlap, block - 2 * overlap}},          // all four (tileable corner)
    };
    long long positions = 0, distances = 0;
    int queries = 0, mismatches = 0;
    double exhaustive_seconds = 0, projection_seconds = 0;
    for (int trial = 0; trial < 120; ++trial) {
        Neighbourhood neighbourhood;
        neighbourhood.rects = shapes[trial % shapes.size()];
        // Queries: an exemplar block (its exact continuation exists: d_min = 0), a perturbed
        // one, or pure noise.
        const int kind = trial / int(shapes.size()) % 3;
        const int qx = int(random.uniform() * (source.width - block)), qy = int(random.uniform() * (source.height - block));
        for (const BlockRect& r : neighbourhood.rects)
            for (int j = 0; j < r.height; ++j)
                for (int i = 0; i < r.width; ++i)
                    for (int c = 0; c < channels; ++c)
                        neighbourhood.values.push_back(kind == 2 ? float(random.gaussian())
                                                                 : float(source.at(qx + r.x + i, qy + r.y + j, c) +
                                                                         (kind == 1 ? 0.2 * random.gaussian() : 0.0)));
        Acceptance acceptance;
        acceptance.relative = trial % 2 ? 1.1 : 1.0;  // the best alone, or the near-best
        acceptance.absolute = trial % 4 == 3 ? 5.0 : 0.0;
        SearchStatistics exhaustive_statistics, projection_statistics;
        auto start = std::chrono::steady_clock::now();
        const auto expected = search.exhaustive(neighbourhood, acceptance, exhaustive_statistics);
        exhaustive_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        start = std::chrono::steady_clock::now();
        const auto found = search.projection(neighbourhood, acceptance, projection_statistics);
        projection_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ++queries;
        bool same = expected.size() == found.size();
        for (std::size_t i = 0; same && i < expected.size(); ++i)
            same = expected[i].x == found[i].x && expected[i].y == found[i].y && expected[i].distance == found[i].distance;
        mismatches += !same;
        if (kind == 0) EXPECT_EQ(std::min_element(found.begin(), found.end(), [](auto& a, auto& b) { return a.distance < b.distance; })->distance, 0.0);
        positions += projection_statistics.positions;
        distances += projection_statistics.exact_distances;
    }
    EXPECT_EQ(mismatches, 0) << "of " << queries << " queries";
    std::printf("[ search ] %d queries: identical candidates; %.2f %% of %lld positions needed a distance; "
                "exhaustive %.3f s, projection %.3f s (×%.1f)\n",
                queries, 100.0 * distances / positions, positions, exhaustive_seconds, projection_seconds,
                exhaustive_seconds / projection_seconds);
}

// ---- Quilting ------------------------------------------------------------------------------------

namespace {

PtmMaps field_maps(int width, int height, std::uint64_t seed)
{
    PtmMaps maps;
    maps.colour = PtmColour::lrgb;
    maps.coefficients = random_field(width, height, 9, seed);
    return maps;
}

}  // namespace

TEST(Quilting, ProjectionAndExhaustiveSearchSynthesiseTheSameMaps)
{
    const PtmMaps exemplar = field_maps(56, 56, 2);
    PtmSynthesisOptions options;
    options.width = options.height = 96;
    options.block = 16;
    options.overlap = 4;
    for (bool tileable : {false, true}) {
        options.tileable = tileable;
        PtmSynthesisReport projection, exhaustive;
        options.brute_force = false;
        const PtmMaps a = synthesize_ptm(exemplar, options, &projection);
        options.brute_force = true;
        const PtmMaps b = synthesize_ptm(exemplar, options, &exhaustive);
        EXPECT_TRUE(a.coefficients.pixels == b.coefficients.pixels) << "tileable " << tileable;
        std::printf("[ quilting ] %s %dx%d: search exhaustive %.3f s, projection %.3f s (×%.1f)\n",
                    tileable ? "tileable" : "plain", a.width(), a.height(), exhaustive.search_seconds,
                    projection.search_seconds, exhaustive.search_seconds / projection.search_seconds);
    }
}

TEST(Quilting, CutsCopyExemplarTexelsAndTheTileableOutputWraps)
{
    const PtmMaps exemplar = field_maps(60, 52, 3);
    std::set<std::vector<float>> exemplar_texels;
    const int channels = exemplar.coefficients.channels;
    for (std::size_t i = 0; i < exemplar.coefficients.pixel_count(); ++i)
        exemplar_texels.insert(std::vector<float>(&exemplar.coefficients.pixels[i * channels],
                                                  &exemplar.coefficients.pixels[(i + 1) * channels]));
    PtmSynthesisOptions options;
    options.block = 20;
    options.overlap = 5;
    options.width = 100, options.height = 70;
    PtmSynthesisReport report;
    const PtmMaps plain = synthesize_ptm(exemplar, options, &report);
    EXPECT_EQ(plain.width(), 100);
    EXPECT_EQ(plain.height(), 70);
    options.tileable = true;
    const PtmMaps tiled = synthesize_ptm(exemplar, options, &report);
    EXPECT_EQ(tiled.width(), 105);  // 7 whole steps of 15
    EXPECT_EQ(tiled.height(), 75);
    for (const PtmMaps* maps : {&plain, &tiled}) {
        long long foreign = 0;
        for (std::size_t i = 0; i < maps->coefficients.pixel_count(); ++i)
            foreign += !exemplar_texels.count(std::vector<float>(&maps->coefficients.pixels[i * channels],
                                                                 &maps->coefficients.pixels[(i + 1) * channels]));
        EXPECT_EQ(foreign, 0) << "min-cut seams copy texels, never mix them";
    }
    // Across the wrap the field is as continuous as inside: the mean ψ step between
    // neighbouring columns over the wrap equals the mean step elsewhere (within noise).
    auto column_step = [&](const Image& image, int x0, int x1) {
        double sum = 0;
        for (int y = 0; y < image.height; ++y)
            for (int c = 0; c < 6; ++c) sum += std::fabs(image.at(x0, y, c) - image.at(x1, y, c));
        return sum / (image.height * 6);
    };
    double inside = 0;
    for (int x = 0; x + 1 < tiled.width(); ++x) inside += column_step(tiled.coefficients, x, x + 1);
    inside /= tiled.width() - 1;
    const double across = column_step(tiled.coefficients, tiled.width() - 1, 0);
    EXPECT_LT(across, 1.5 * inside) << "across the wrap " << across << ", inside " << inside;
    // Blended seams: texels away from every overlap are the exemplar's own.
    options.tileable = false;
    options.seam = SeamMode::blend;
    const PtmMaps blended = synthesize_ptm(exemplar, options);
    const float* centre = &blended.coefficients.pixels[(std::size_t(10) * blended.width() + 10) * channels];
    EXPECT_TRUE(exemplar_texels.count(std::vector<float>(centre, centre + channels)));
}

TEST(Quilting, RejectsBadOptions)
{
    const PtmMaps exemplar = field_maps(32, 32, 4);
    PtmSynthesisOptions options;
    options.block = 40;
    EXPECT_THROW(synthesize_ptm(exemplar, options), Error);  // the block does not fit
    options.block = 16;
    options.overlap = 9;
    EXPECT_THROW(synthesize_ptm(exemplar, options), Error);  // overlap > block / 2
}

// ---- The .stex ptm model --------------------------------------------------------------------------

TEST(PtmStex, RoundTripsWithItsCoefficientFile)
{
    const fs::path dir = test::temp_dir("ptm-stex");
    const TextureDescription description = make_ptm_description(random_maps(PtmColour::lrgb, 24, 16, 5), {0.6, 0, 0.8});
    const std::string path = (dir / "rock.stex").string();
    write_stex(path, description);
    ASSERT_TRUE(fs::exists(dir / "rock.ptm.exr"));
    const TextureDescription read = read_stex(path);
    ASSERT_TRUE(read.parameters.holds<PtmParameters>());
    EXPECT_EQ(read.parameters.get<PtmParameters>().coefficient_file, "rock.ptm.exr");
    EXPECT_TRUE(read.parameters.get<PtmParameters>().maps->coefficients.pixels == description.parameters.get<PtmParameters>().maps->coefficients.pixels);
    EXPECT_EQ(format_stex(read), format_stex(read_stex(path)));
    // Written again elsewhere: byte-identical text, the maps named after the new file.
    const std::string copy = (dir / "copy.stex").string();
    write_stex(copy, read);
    const TextureDescription read_copy = read_stex(copy);
    EXPECT_EQ(read_copy.parameters.get<PtmParameters>().coefficient_file, "copy.ptm.exr");
    auto text = [](const std::string& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    std::string expected = text(path);
    expected.replace(expected.find("rock.ptm.exr"), 12, "copy.ptm.exr");
    EXPECT_EQ(text(copy), expected);
}

TEST(PtmStex, ReaderIsStrict)
{
    const fs::path dir = test::temp_dir("ptm-stex-strict");
    const std::string path = (dir / "t.stex").string();
    write_stex(path, make_ptm_description(random_maps(PtmColour::rgb, 8, 8, 6), {0, 0, 1}));
    auto original = [&] {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }();
    auto error_for = [&](const std::string& from, const std::string& to) {
        std::string text = original;
        const auto at = text.find(from);
        if (at == std::string::npos) return "pattern not found: " + from;
        text.replace(at, from.size(), to);
        try {
            parse_stex(text, path);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_TRUE(test::contains(error_for("\"t.ptm.exr\"", "\"../t.ptm.exr\""),
                               "parameters.coefficients.file: expected a file name beside the .stex"));
    EXPECT_TRUE(test::contains(error_for("\"t.ptm.exr\"", "\"missing.exr\""), "does not exist"));
    EXPECT_TRUE(test::contains(error_for("\"checksum\": \"fnv1a64:", "\"checksum\": \"fnv1a64:0"),
                               "parameters.coefficients.checksum"));
    EXPECT_TRUE(test::contains(error_for("\"width\": 8", "\"width\": 9"), "parameters.coefficients: the file says 9x8"));
    EXPECT_TRUE(test::contains(error_for("\"colour\": \"rgb\"", "\"colour\": \"lrgb\""), "has 18 channels, a lrgb PTM has 9"));
    EXPECT_TRUE(test::contains(error_for("\"colour\": \"rgb\"", "\"colour\": \"yuv\""), "parameters.colour: unknown PTM colour model"));
    EXPECT_TRUE(test::contains(error_for("\"light\": [0, 0, 1]", "\"light\": [0, 0, 2]"), "parameters.light: must be a unit vector"));
    EXPECT_TRUE(test::contains(error_for("\"mode\": \"rgb\"", "\"mode\": \"rgb-shared\""), "colour.mode: must be \"rgb\" for the ptm model"));
    EXPECT_TRUE(test::contains(error_for("\"checksum\"", "\"sum\""), "parameters.coefficients.sum: unknown field"));
}

TEST(PtmTexture, RendersTheRelitMapsAndFiltersThroughCoefficientMips)
{
    const PtmMaps maps = random_maps(PtmColour::lrgb, 32, 32, 8);
    const Vec3 light{0.48, -0.36, 0.8};
    const TextureDescription description = make_ptm_description(maps, light);
    const auto texture = make_texture(description);
    // At the maps' own scale a render is the relit maps.
    RenderSettings settings;
    settings.width = settings.height = 32;
    settings.units_per_pixel = 1.0 / description.pixels_per_unit;
    const Image rendered = render(*texture, settings);
    const Image lit = relight(maps, light);
    double worst = 0;
    for (std::size_t i = 0; i < lit.pixels.size(); ++i) worst = std::max(worst, double(std::fabs(lit.pixels[i] - rendered.pixels[i])));
    EXPECT_LT(worst, 1e-5);
    // The plugin's MIP levels: level l is the box average of the relit maps (these functions
    // never clamp), the 1 × 1 level the texture's mean.
    ImageLayout layout;
    layout.width = layout.height = 64;  // two repeats
    const MipImage mip(description, layout, "test");
    for (int level : {0, 1, 3}) {
        const int size = mip.level_width(level), span = 64 / size;
        std::vector<float> texels(std::size_t(size) * size * 3);
        mip.fill(level, 0, 0, size, size, texels.data());
        double level_worst = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                for (int c = 0; c < 3; ++c) {
                    double sum = 0;
                    for (int j = 0; j < span; ++j)
                        for (int i = 0; i < span; ++i) sum += lit.at((x * span + i) % 32, (y * span + j) % 32, c);
                    level_worst = std::max(level_worst, std::fabs(sum / (span * span) - texels[(std::size_t(y) * size + x) * 3 + c]));
                }
        EXPECT_LT(level_worst, 1e-5) << "level " << level;
    }
    float top[3];
    mip.fill(mip.level_count() - 1, 0, 0, 1, 1, top);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(top[c], texture->mean()[c], 1e-6);
}

TEST(Lighting, TheHookSetsTheLightOfModelsThatHaveOne)
{
    TextureDescription description = make_ptm_description(random_maps(PtmColour::rgb, 8, 8, 9), {0, 0, 1});
    EXPECT_TRUE(depends_on_light(description));
    set_light_direction(description, parse_light_direction("3, 0, 4"));
    EXPECT_NEAR(light_direction(description)[0], 0.6, 1e-12);
    EXPECT_NEAR(light_direction(description)[2], 0.8, 1e-12);
    EXPECT_THROW(parse_light_direction("1,0"), Error);
    EXPECT_THROW(parse_light_direction("1,0,-1"), Error);
    EXPECT_THROW(parse_light_direction("1,0,1,2"), Error);
    TextureDescription other;
    other.model = "wavelet";
    EXPECT_FALSE(depends_on_light(other));
    EXPECT_THROW(set_light_direction(other, {0, 0, 1}), Error);
}

TEST(PtmPlugin, TheLightHintRelightsThePluginImage)
{
    OIIO::attribute("plugin_searchpath", STOCHTEX_PLUGIN_DIR);
    const fs::path dir = test::temp_dir("ptm-plugin");
    const PtmMaps maps = random_maps(PtmColour::lrgb, 32, 32, 12);
    const std::string path = (dir / "t.stex").string();
    write_stex(path, make_ptm_description(maps, {0, 0, 1}));
    auto level0 = [&](const char* light, std::string& error) {
        OIIO::ImageSpec config;
        config.attribute("stex:width", 32);
        config.attribute("stex:height", 32);
        if (light) config.attribute("stex:light", light);
        auto input = OIIO::ImageInput::open(path, &config);
        std::vector<float> pixels;
        if (!input) {
            error = OIIO::geterror();
            return pixels;
        }
        pixels.resize(32 * 32 * 3);
        EXPECT_TRUE(input->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
        EXPECT_EQ(input->spec().get_string_attribute("stex:light"), light ? "0.6,0,0.8" : "0,0,1");
        return pixels;
    };
    // The texture holds lrgb texels as premultiplied float functions: equal to relight() up to
    // float rounding.
    auto difference = [](const std::vector<float>& a, const std::vector<float>& b) {
        double worst = a.size() == b.size() ? 0 : 1e9;
        for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, double(std::fabs(a[i] - b[i])));
        return worst;
    };
    std::string error;
    const std::vector<float> lit = level0("3,0,4", error);
    ASSERT_FALSE(lit.empty()) << error;
    EXPECT_LT(difference(lit, relight(maps, {0.6, 0, 0.8}).pixels), 1e-5);
    EXPECT_LT(difference(level0(nullptr, error), relight(maps, {0, 0, 1}).pixels), 1e-5);
    EXPECT_TRUE(level0("1,0,-1", error).empty());
    EXPECT_TRUE(test::contains(error, "stex:light: light direction: must point out of the surface")) << error;
}
