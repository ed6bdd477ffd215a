// The conformance suite: what every registered model must do, checked on each model's own
// example description (Model::example()). It iterates the registry, so a new model — the test
// suite's own test_noise (tests/models/) among them — is covered without a test of its own.
// Model-specific statistics stay in each model's test file.
#include <stochtex/bake.h>
#include <stochtex/describe.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/mip_image.h>
#include <stochtex/model.h>
#include <stochtex/morph.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/pov/pov_include.h>

#include "models/model.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>
#include <vector>

namespace stochtex {
namespace {

using Json = nlohmann::ordered_json;

std::string read_bytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

using stochtex::test::error_of;

bool starts_with(const std::string& text, const std::string& prefix) { return text.compare(0, prefix.size(), prefix) == 0; }

/// Each model's example, made once (analysis takes a few milliseconds per model).
const TextureDescription& example_of(const std::string& name)
{
    static std::map<std::string, TextureDescription> examples;
    auto found = examples.find(name);
    if (found == examples.end()) found = examples.emplace(name, find_model(name)->example()).first;
    return found->second;
}

/// Every MIP level's pixels of an image file, one after another (as floats).
std::vector<float> pixels_of_every_level(const std::string& path)
{
    std::vector<float> pixels;
    auto input = OIIO::ImageInput::open(path);
    if (!input) return pixels;
    for (int level = 0; input->seek_subimage(0, level); ++level) {
        const OIIO::ImageSpec& spec = input->spec();
        const std::size_t start = pixels.size();
        pixels.resize(start + spec.image_pixels() * spec.nchannels);
        if (!input->read_image(0, level, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data() + start)) return {};
    }
    return pixels;
}

/// Largest |a − b| over channels, relative to the texture's spread (its mean's magnitude + 1).
double difference(const Rgb& a, const Rgb& b)
{
    double d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, double(std::fabs(a[c] - b[c])));
    return d;
}

class ModelConformance : public ::testing::TestWithParam<std::string> {
protected:
    const std::string& name() const { return GetParam(); }
    const TextureDescription& example() const { return example_of(name()); }
    const ModelInfo& info() const { return model_info(name()); }
    /// One exemplar pixel, in texture units: the footprint of a render at the photo's scale.
    double pixel() const { return 1.0 / example().pixels_per_unit; }
};

TEST_P(ModelConformance, ExampleIsValidAndNamesItsModel)
{
    EXPECT_EQ(example().model, name());
    EXPECT_NO_THROW(validate(example(), "example"));
    EXPECT_TRUE(find_model(name())->holds(example().parameters));
}

TEST_P(ModelConformance, HugeFootprintConvergesToTheMean)
{
    const auto texture = make_texture(example());
    const Rgb mean = texture->mean();
    for (double huge : {1e3, 1e5})
        for (const Vec2& uv : {Vec2{0.1, 0.2}, Vec2{-3.7, 11.3}, Vec2{250.5, -80.25}}) {
            const Rgb value = texture->eval(uv, Footprint2D::square(huge));
            EXPECT_LT(difference(value, mean), 2e-3) << "footprint " << huge << " at (" << uv[0] << ", " << uv[1] << ")";
        }
}

TEST_P(ModelConformance, SolidFormConvergesToTheMeanToo)
{
    const auto texture = make_texture(example());
    SurfacePoint point;
    point.p = {0.3, -1.2, info().capabilities.solid ? 0.77 : 0.0};
    point.dpdx = {1e4, 0, 0};
    point.dpdy = {0, 1e4, 0};
    EXPECT_LT(difference(texture->eval_solid(point), texture->mean()), 2e-3);
    point.dpdx = point.dpdy = {0, 0, 0};
    for (float v : texture->eval_solid(point)) EXPECT_TRUE(std::isfinite(v));
}

TEST_P(ModelConformance, PeriodicFormTilesWithoutASeam)
{
    const Vec2 period{8, 4};  // texture units: a few hundred exemplar pixels
    const auto texture = make_periodic_texture(example(), period);
    const Footprint2D footprint = Footprint2D::square(pixel());
    double worst = 0;
    for (int i = 0; i < 40; ++i) {
        const Vec2 uv{0.37 * i - 3, 0.23 * i * i - 5};
        const Rgb here = texture->eval(uv, footprint);
        worst = std::max({worst, difference(here, texture->eval({uv[0] + period[0], uv[1]}, footprint)),
                          difference(here, texture->eval({uv[0], uv[1] - period[1]}, footprint)),
                          difference(here, texture->eval({uv[0] - 2 * period[0], uv[1] + 3 * period[1]}, footprint))});
    }
    EXPECT_LT(worst, 1e-4);
}

TEST_P(ModelConformance, RasterRegionEqualsPointEvaluation)
{
    for (const bool periodic : {false, true}) {
        const auto texture = periodic ? make_periodic_texture(example(), {8, 4}) : make_texture(example());
        RasterRegion region;
        region.origin_u = -0.31, region.origin_v = 0.17;
        region.du = 0.7 * pixel(), region.dv = 1.3 * pixel();
        region.x0 = 5, region.y0 = 3, region.width = 13, region.height = 7;
        region.footprint = {region.du, 0, 0, region.dv};
        EXPECT_EQ(test::raster_point_difference(*texture, region), "") << (periodic ? "periodic" : "plain");
    }
}

TEST_P(ModelConformance, BatchesEqualPointEvaluation)
{
    const auto texture = make_texture(example());
    // 2D points with footprints of their own, into planar output.
    std::vector<Vec2> uv;
    std::vector<Footprint2D> footprints;
    for (int k = 0; k < 23; ++k) {
        uv.push_back({0.13 * k - 1, 0.07 * k * k});
        footprints.push_back(Footprint2D{k * 0.3 * pixel(), 0.1 * pixel(), -0.2 * pixel(), (23 - k) * 0.2 * pixel()});
    }
    std::vector<float> planes(3 * uv.size());
    const std::size_t n = uv.size();
    texture->eval_points({uv.data(), footprints.data(), n}, RgbOutput::planar(planes.data(), planes.data() + n, planes.data() + 2 * n));
    for (std::size_t k = 0; k < n; ++k) {
        const Rgb point = texture->eval(uv[k], footprints[k]);
        for (int c = 0; c < 3; ++c) ASSERT_EQ(planes[c * n + k], point[c]) << "point " << k;
    }
    // A solid slice, interleaved.
    SolidRegion slice;
    slice.plane.origin_u = 0.4, slice.plane.origin_v = -0.9, slice.plane.du = 1.5 * pixel(), slice.plane.dv = pixel();
    slice.plane.x0 = 2, slice.plane.y0 = 1, slice.plane.width = 9, slice.plane.height = 4;
    slice.plane.footprint = {slice.plane.du, 0, 0, slice.plane.dv};
    slice.w = 0.61;
    std::vector<float> rgb(std::size_t(9 * 4 * 3));
    texture->eval_solid_region(slice, RgbOutput::interleaved(rgb.data()));
    std::vector<SurfacePoint> surface;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 9; ++i) {
            SurfacePoint point;
            point.p = {slice.plane.u(i), slice.plane.v(j), slice.w};
            point.dpdx = {slice.plane.du, 0, 0};
            point.dpdy = {0, slice.plane.dv, 0};
            const Rgb value = texture->eval_solid(point);
            for (int c = 0; c < 3; ++c) ASSERT_EQ(rgb[(std::size_t(j) * 9 + i) * 3 + c], value[c]) << i << ", " << j;
            point.n = {0.6, 0, 0.8};
            surface.push_back(point);
        }
    std::vector<float> tilted(3 * surface.size());
    texture->eval_solid_points({surface.data(), surface.size()}, RgbOutput::interleaved(tilted.data()));
    for (std::size_t k = 0; k < surface.size(); ++k) {
        const Rgb value = texture->eval_solid(surface[k]);
        for (int c = 0; c < 3; ++c) ASSERT_EQ(tilted[3 * k + c], value[c]) << "surface point " << k;
    }
}

TEST_P(ModelConformance, RendersAreTheSameForAnyThreadCountAndRun)
{
    const auto texture = make_texture(example());
    RenderSettings settings;
    settings.width = 40, settings.height = 33;
    settings.units_per_pixel = 1.7 * pixel();
    settings.threads = 1;
    const Image one = render(*texture, settings);
    settings.threads = 2;
    const Image two = render(*texture, settings);
    const Image again = render(*make_texture(example()), settings);
    EXPECT_EQ(one.pixels, two.pixels);
    EXPECT_EQ(two.pixels, again.pixels);
}

/// Every entry point that spreads work over threads gives the same bits for 1, 2 and many
/// threads (more than rows, than cores): render (2D filtered and point-sampled, periodic, solid
/// where the model has it), the MIP levels the plugin serves as tiles (filled in any order from
/// many threads), `stex bake` and the solid bake at a position map (the files, byte for byte),
/// and the POV-Ray include's baked image (all cores) against a one-thread render.
TEST_P(ModelConformance, EveryEntryPointIsTheSameForOneTwoAndManyThreads)
{
    const std::vector<int> thread_counts{1, 2, 7};
    const auto texture = make_texture(example());
    const auto periodic = make_periodic_texture(example(), {8, 4});
    for (int variant = 0; variant < 4; ++variant) {
        if (variant == 3 && !info().capabilities.solid) continue;
        RenderSettings settings;
        settings.width = 23, settings.height = 9;  // fewer rows than the 7 threads' bands
        settings.units_per_pixel = 2.3 * pixel();
        settings.origin_u = -1.25, settings.origin_v = 0.5;
        settings.filter = variant != 1;
        settings.solid = variant == 3;
        settings.z = 0.4;
        const Texture& subject = variant == 2 ? *periodic : *texture;
        std::vector<Image> images;
        for (int threads : thread_counts) {
            settings.threads = threads;
            images.push_back(render(subject, settings));
        }
        for (std::size_t i = 1; i < images.size(); ++i)
            EXPECT_EQ(images[0].pixels, images[i].pixels) << "render variant " << variant << ", " << thread_counts[i] << " threads";
    }

    // Plugin tiles: every level's 8² tiles, in order on one thread, then backwards from 7.
    ImageLayout layout;
    layout.width = 64, layout.height = 40, layout.tile_width = layout.tile_height = 8;  // lrp: periods ≥ 32 pixels
    const MipImage mip(example(), layout, "conformance");
    auto tiles = [&](int threads) {
        std::vector<std::vector<float>> result;
        std::vector<std::array<int, 3>> jobs;  // level, x0, y0
        for (int level = 0; level < mip.level_count(); ++level)
            for (int y = 0; y < mip.level_height(level); y += 8)
                for (int x = 0; x < mip.level_width(level); x += 8) jobs.push_back({level, x, y});
        result.resize(jobs.size());
        std::atomic<int> next{int(jobs.size()) - 1};
        auto work = [&] {
            for (int j; (j = next.fetch_sub(1)) >= 0;) {
                const auto [level, x, y] = jobs[j];
                const int w = std::min(8, mip.level_width(level) - x), h = std::min(8, mip.level_height(level) - y);
                result[j].resize(std::size_t(w) * h * mip.channel_count());
                mip.fill(level, x, y, w, h, result[j].data());
            }
        };
        std::vector<std::thread> pool;
        for (int t = 0; t < threads; ++t) pool.emplace_back(work);
        for (auto& thread : pool) thread.join();
        return result;
    };
    const auto sequential = tiles(1);
    EXPECT_EQ(sequential, tiles(2));
    EXPECT_EQ(sequential, tiles(7));

    // The bakes: every level's pixels (the headers hold the time of writing).
    const std::string dir = test::temp_dir("conformance-threads-" + name());
    const std::string positions = dir + "/positions.exr";
    {
        // A sheared ramp of positions, alpha 1 (covered) but for one texel.
        Image map(12, 10, 4);
        for (int y = 0; y < map.height; ++y)
            for (int x = 0; x < map.width; ++x)
                map.at(x, y, 0) = 0.1f * x, map.at(x, y, 1) = 0.07f * y + 0.02f * x, map.at(x, y, 2) = 0.05f * y,
                map.at(x, y, 3) = x == 3 && y == 4 ? 0.0f : 1.0f;
        auto output = OIIO::ImageOutput::create(positions);
        ASSERT_TRUE(output && output->open(positions, OIIO::ImageSpec(map.width, map.height, 4, OIIO::TypeDesc::FLOAT)) &&
                    output->write_image(OIIO::TypeDesc::FLOAT, map.pixels.data()) && output->close());
    }
    std::vector<std::vector<float>> bakes, solid_bakes;
    for (int threads : thread_counts) {
        BakeOptions options;
        options.width = options.height = 32;
        options.tile_size = 16;
        options.threads = threads;
        const std::string path = dir + "/bake-" + std::to_string(threads) + ".exr";
        bake_mip_image(example(), path, options);
        bakes.push_back(pixels_of_every_level(path));
        const std::string solid_path = dir + "/solid-" + std::to_string(threads) + ".exr";
        bake_solid_map(example(), positions, solid_path, 0.5, threads);
        solid_bakes.push_back(pixels_of_every_level(solid_path));
    }
    for (std::size_t i = 1; i < bakes.size(); ++i) {
        EXPECT_FALSE(bakes[0].empty());
        EXPECT_TRUE(bakes[0] == bakes[i]) << "bake, " << thread_counts[i] << " threads";
        EXPECT_TRUE(solid_bakes[0] == solid_bakes[i]) << "solid bake, " << thread_counts[i] << " threads";
    }

    // The POV-Ray include's baked image renders on all cores.
    pov::PovIncludeOptions pov_options;
    pov_options.name = "T";
    pov_options.mode = pov::PovMode::baked;
    pov_options.image_file_name = "t.exr";
    pov_options.bake_size = 64;  // lrp's fixed phases need a period of at least 32 exemplar pixels
    const Image baked = pov::make_pov_include(example(), pov_options).baked_image;
    const double period = 64 / example().pixels_per_unit;
    RenderSettings settings;
    settings.width = settings.height = 64;
    settings.units_per_pixel = period / 64;
    settings.threads = 1;
    EXPECT_EQ(baked.pixels, render(*make_periodic_texture(example(), {period, period}), settings).pixels);
}

TEST_P(ModelConformance, StexRoundTripIsByteIdentical)
{
    const std::string dir = test::temp_dir("conformance_" + name());
    const std::string first = dir + "/first.stex", second = dir + "/second.stex";
    write_stex(first, example());
    write_stex(second, read_stex(first));
    const std::string text = read_bytes(first);
    EXPECT_FALSE(text.empty());
    // (Files a model keeps beside the .stex are named after it: the texts differ only there.)
    std::string renamed = read_bytes(second);
    for (std::size_t at; (at = renamed.find("second.")) != std::string::npos;) renamed.replace(at, 7, "first.");
    EXPECT_EQ(renamed, text);
    EXPECT_EQ(format_stex(parse_stex(text, first)), text);
}

TEST_P(ModelConformance, EveryDeclaredParameterIsCheckedWithItsPath)
{
    const std::string dir = test::temp_dir("conformance_bad_" + name());
    const std::string path = dir + "/t.stex";
    write_stex(path, example());
    const Json original = Json::parse(read_bytes(path));
    auto error_for = [&](const std::function<void(Json&)>& edit) {
        Json json = original;
        edit(json["parameters"]);
        std::ofstream(path, std::ios::binary | std::ios::trunc) << json.dump(2);
        return error_of([&] { read_stex(path); });
    };
    ASSERT_FALSE(info().parameters.empty());
    for (const ParameterInfo& p : info().parameters) {
        const std::string at = path + ": parameters." + p.key;
        if (!p.optional)
            EXPECT_EQ(error_for([&](Json& block) { block.erase(p.key); }), at + ": missing required field");
        // A value of the wrong type: a string where anything else is expected, else a number.
        const Json wrong = p.type == "string" ? Json(7) : Json("seven");
        EXPECT_TRUE(starts_with(error_for([&](Json& block) { block[p.key] = wrong; }), at)) << p.key;
        // A number past its declared range.
        if ((p.type == "number" || p.type == "integer") && p.range.size() > 2 && p.range.front() == '[') {
            const double max = std::stod(p.range.substr(p.range.find(',') + 1));
            const Json past = p.type == "integer" ? Json(std::int64_t(max) + 1) : Json(2 * std::fabs(max) + 1);
            EXPECT_TRUE(starts_with(error_for([&](Json& block) { block[p.key] = past; }), at)) << p.key << " = " << past;
        }
    }
    const std::string unknown = error_for([](Json& block) { block["no_such_parameter"] = 1; });
    EXPECT_TRUE(starts_with(unknown, path + ": parameters.no_such_parameter: unknown field (expected one of: ")) << unknown;
}

TEST_P(ModelConformance, TheOtherModelsParametersAreRejected)
{
    for (const std::string& other : known_models()) {
        if (other == name()) continue;
        TextureDescription mixed = example();
        mixed.parameters = example_of(other).parameters;
        EXPECT_TRUE(starts_with(error_of([&] { validate(mixed, "t.stex"); }), "t.stex: parameters: ")) << other;
    }
    TextureDescription none = example();
    none.parameters.reset();
    EXPECT_EQ(error_of([&] { validate(none, "t.stex"); }), "t.stex: parameters: missing for model '" + name() + "'");
}

TEST_P(ModelConformance, InfoDescribesIt)
{
    const std::string text = describe(example());
    EXPECT_TRUE(starts_with(text, "model        " + name() + " (format version 1)\n")) << text;
    EXPECT_NE(text.find("texture mean"), std::string::npos) << text;
}

TEST_P(ModelConformance, CapabilitiesAreHonoured)
{
    const ModelCapabilities& can = info().capabilities;
    const Model& model = *find_model(name());
    TextureDescription d = example();
    if (can.morph) {
        EXPECT_EQ(format_stex(morph(d, d, 0.5)), format_stex(morph(d, d, 0.5)));
    } else {
        EXPECT_THROW(morph(d, d, 0.5), Error);
    }
    if (can.gaussian_channels) {
        EXPECT_GT(model.channel_sigma(d, 0), 0);
    } else {
        EXPECT_THROW(model.channel_sigma(d, 0), Error);
    }
    if (can.light_direction) {
        EXPECT_NO_THROW(model.set_light(d, {0, 0, 1}));
        EXPECT_EQ(model.light(d), (Vec3{0, 0, 1}));
    } else {
        EXPECT_THROW(model.light(d), Error);
    }
    if (!can.analysis) {
        AnalysisOptions options;
        options.model = name();
        EXPECT_THROW(analyze(Image(32, 32, 3), options), Error);
    }
}

INSTANTIATE_TEST_SUITE_P(EveryRegisteredModel, ModelConformance, ::testing::ValuesIn(known_models()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(ModelRegistry, TheTestSuitesOwnModelIsRegisteredAfterTheBuiltInOnes)
{
    // The built-in models, then the test suite's own (tests/models/: test_noise, test_everything,
    // …), in the order the linker runs their registrations.
    const std::vector<std::string> built_in{"wavelet", "gabor", "tiling", "lrp", "ptm"};
    const std::vector<std::string>& known = known_models();
    ASSERT_GT(known.size(), built_in.size());
    EXPECT_EQ(std::vector<std::string>(known.begin(), known.begin() + 5), built_in);
    EXPECT_NE(std::find(known.begin() + 5, known.end(), "test_noise"), known.end());
    EXPECT_NE(std::find(known.begin() + 5, known.end(), "test_everything"), known.end());
    EXPECT_EQ(model_info("test_noise").parameters.size(), 2u);
    // Its .stex errors come from its declaration, as every model's do.
    std::string text = format_stex(find_model("test_noise")->example());
    text.replace(text.find("\"amplitude\": 0.1"), 16, "\"amplitude\": 2");
    EXPECT_EQ(error_of([&] { parse_stex(text, "t.stex"); }), "t.stex: parameters.amplitude: must be in [0, 1], got 2");
    EXPECT_NE(models_json().find("\"test_noise\""), std::string::npos);
}

}  // namespace
}  // namespace stochtex
