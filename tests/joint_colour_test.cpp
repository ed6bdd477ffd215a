// Joint colour (colour/chroma_given_brightness.h): chroma channels conditioned on brightness.
// The photo here is made by the test: stones whose hue follows their brightness (dark ones
// grey-blue, bright ones yellow), the case where three independent channels make colours the
// photo never had.
#include <stochtex/analysis.h>
#include <stochtex/channel_map.h>
#include <stochtex/describe.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/morph.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>
#include <stochtex/models/shader_colour_data.h>

#include "analysis/colour_statistics.h"
#include "colour/chroma_given_brightness.h"
#include "colour/colour_mapping.h"
#include "colour/histogram_map.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace stochtex {
namespace {

/// 256² "gravel": a smooth random brightness field b; colour blends grey-blue (b < 0) into
/// yellow (b > 0), its level rising with b, plus a little noise.
Image two_hued_photo()
{
    constexpr int size = 256;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> phase(0, 2 * M_PI), direction(0, M_PI);
    struct Wave { double fx, fy, phase; };
    std::vector<Wave> waves;
    for (int k = 0; k < 40; ++k) {
        const double angle = direction(rng), frequency = 2 * M_PI * (6 + k % 10) / size;
        waves.push_back({frequency * std::cos(angle), frequency * std::sin(angle), phase(rng)});
    }
    std::normal_distribution<double> grain(0, 0.01);
    Image photo(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double b = 0;
            for (const Wave& w : waves) b += std::cos(w.fx * x + w.fy * y + w.phase);
            b /= std::sqrt(waves.size() / 2.0);
            const double t = 1 / (1 + std::exp(-3 * b)), level = 0.25 + 0.12 * b;
            const double blue_grey[3] = {0.30, 0.34, 0.42}, yellow[3] = {1.0, 0.75, 0.25};
            for (int c = 0; c < 3; ++c)
                photo.pixels[(std::size_t(y) * size + x) * 3 + c] =
                    float(std::max(0.0, level * ((1 - t) * blue_grey[c] + t * yellow[c]) + grain(rng)));
        }
    return photo;
}

TextureDescription analysed(const std::string& model, bool joint_colour)
{
    static const Image photo = two_hued_photo();
    AnalysisOptions options;
    options.model = model;
    options.joint_colour = joint_colour;
    return analyze(photo, options);
}

Image render_at_photo_scale(const TextureDescription& description)
{
    RenderSettings settings;
    settings.width = settings.height = 256;
    settings.units_per_pixel = 1.0 / description.pixels_per_unit;
    return render(*make_texture(description), settings);
}

using stochtex::test::error_of;

TEST(JointColour, KeepsTheColoursThePhotoHas)
{
    const Image photo = two_hued_photo();
    for (const std::string model : {"wavelet", "gabor", "lrp"}) {
        const double independent = false_colour_rate(photo, render_at_photo_scale(analysed(model, false)));
        const double joint = false_colour_rate(photo, render_at_photo_scale(analysed(model, true)));
        // Measured: wavelet 3.72 % → 0.25 %, gabor 3.40 % → 0.24 %.
        EXPECT_GT(independent, 0.02) << model << ": the test photo should show false colour without joint colour";
        EXPECT_LT(joint, 0.01) << model;
        EXPECT_LT(joint, independent / 4) << model;
    }
}

TEST(JointColour, OnlyWhereItApplies)
{
    EXPECT_TRUE(analysed("wavelet", true).chroma_given_brightness.enabled());
    EXPECT_FALSE(analysed("wavelet", false).chroma_given_brightness.enabled());
    EXPECT_TRUE(analysed("lrp", true).chroma_given_brightness.enabled());
    // Tiling keeps the photo's own colours.
    EXPECT_FALSE(analysed("tiling", true).chroma_given_brightness.enabled());
    AnalysisOptions rgb;
    rgb.joint_colour = true;
    rgb.colour_mode = ColourMode::rgb;
    EXPECT_FALSE(analyze(two_hued_photo(), rgb).chroma_given_brightness.enabled());
    // A grey photo has no chroma to condition.
    Image grey = two_hued_photo();
    for (std::size_t i = 0; i < grey.pixel_count(); ++i) grey.pixels[i * 3 + 1] = grey.pixels[i * 3 + 2] = grey.pixels[i * 3];
    AnalysisOptions options;
    options.joint_colour = true;
    EXPECT_FALSE(analyze(grey, options).chroma_given_brightness.enabled());
}

TEST(JointColour, RasterEqualsPointEvaluationAndMinificationConvergesToTheMean)
{
    for (const std::string model : {"wavelet", "gabor", "lrp"}) {
        const TextureDescription description = analysed(model, true);
        const auto texture = make_texture(description);
        RasterRegion region;
        const double pixel = 1.0 / description.pixels_per_unit;
        region.origin_u = -0.31, region.origin_v = 0.17;
        region.du = 0.7 * pixel, region.dv = 1.3 * pixel;
        region.width = 13, region.height = 7;
        region.footprint = {region.du, 0, 0, region.dv};
        EXPECT_EQ(test::raster_point_difference(*texture, region), "") << model;
        // Filtered away entirely, the texture is its mean (the curves' Gauss–Hermite expectation).
        const Rgb mean = texture->mean(), far = texture->eval({0.3, 0.7}, Footprint2D::square(1e4));
        const Image image = render_at_photo_scale(description);
        const std::array<double, 3> rendered = channel_means(image);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(far[c], mean[c], 1e-4) << model;
            // The mean of a render at the photo's scale agrees with it (spatial average ≈ expectation).
            EXPECT_NEAR(rendered[c], mean[c], 0.02) << model << " channel " << c;
        }
    }
}

TEST(JointColour, StexFilesRoundTripAndAreValidated)
{
    const TextureDescription description = analysed("wavelet", true);
    const std::string dir = test::temp_dir("JointColourStex");
    const std::string path = dir + "/joint.stex";
    write_stex(path, description);
    const TextureDescription read = read_stex(path);
    // Numbers keep 7 significant digits in the file: its text is the round trip's exact measure.
    EXPECT_EQ(read.chroma_given_brightness.z, description.chroma_given_brightness.z);
    for (int c = 0; c < 2; ++c)
        for (std::size_t k = 0; k < description.chroma_given_brightness.z.size(); ++k) {
            EXPECT_NEAR(read.chroma_given_brightness.location[c][k], description.chroma_given_brightness.location[c][k],
                        1e-6 * std::abs(description.chroma_given_brightness.location[c][k]));
            EXPECT_NEAR(read.chroma_given_brightness.scale[c][k], description.chroma_given_brightness.scale[c][k],
                        1e-6 * description.chroma_given_brightness.scale[c][k]);
        }
    EXPECT_EQ(format_stex(read), format_stex(description));
    EXPECT_NE(describe(read).find("joint colour chroma given brightness, 49 knots"), std::string::npos) << describe(read);

    TextureDescription bad = description;
    bad.chroma_given_brightness.scale[1][3] = 0;
    EXPECT_NE(error_of([&] { validate(bad, "t.stex"); }).find("colour.chroma_given_brightness.scale[1][3]: must be positive"),
              std::string::npos);
    bad = description;
    bad.chroma_given_brightness.z[2] += 0.01;
    EXPECT_NE(error_of([&] { validate(bad, "t.stex"); }).find("uniformly spaced"), std::string::npos);
    bad = description;
    bad.chroma_given_brightness.location[0].pop_back();
    EXPECT_NE(error_of([&] { validate(bad, "t.stex"); }).find("location[0]: has"), std::string::npos);
    bad = description;
    bad.colour_mode = ColourMode::rgb;
    bad.basis = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    EXPECT_NE(error_of([&] { validate(bad, "t.stex"); }).find("needs colour mode pca"), std::string::npos);
}

TEST(JointColour, OutputsThatCannotExpressItSaySo)
{
    // POV-Ray's channel colour maps colour one pattern each: chroma = location + scale · residual
    // is a product of two, which they cannot form.
    const TextureDescription description = analysed("wavelet", true);
    const std::string message = error_of([&] { channel_value_polyline(description, 1, -4, 4, 0.002, 256); });
    EXPECT_NE(message.find("--joint-colour off"), std::string::npos) << message;
    // The OSL shaders carry the curves (their maths: osl_shader_test, osl_gabor_test).
    const ShaderColourData data = shader_colour_data(description);
    EXPECT_EQ(data.chroma_given_brightness.z, description.chroma_given_brightness.z);
    EXPECT_EQ(data.chroma_given_brightness.location[1], description.chroma_given_brightness.location[1]);
    EXPECT_EQ(data.chroma_given_brightness.scale[0], description.chroma_given_brightness.scale[0]);
}

/// Largest |a − b| over two renders, in units of a's per-channel standard deviation.
double max_difference_sigma(const Image& a, const Image& b)
{
    const ComparisonReport report = compare_images(a, b);
    double worst = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        worst = std::max(worst, std::abs(double(a.pixels[i]) - b.pixels[i]) / report.stddev_reference[i % 3]);
    return worst;
}

/// The texture with its curves changed (still valid): another joint-colour texture on the same knots.
TextureDescription with_other_curves(TextureDescription description)
{
    ChromaGivenBrightness& curves = description.chroma_given_brightness;
    for (int c = 0; c < 2; ++c)
        for (std::size_t k = 0; k < curves.z.size(); ++k) {
            curves.location[c][k] = -0.5 * curves.location[c][k] + 0.01 * curves.z[k];
            curves.scale[c][k] *= 1.5 + 0.1 * std::tanh(curves.z[k]);
        }
    return description;
}

TEST(JointColour, MorphInterpolatesTheCurvesKnotByKnot)
{
    const TextureDescription a = analysed("wavelet", true), b = with_other_curves(a);
    const TextureDescription half = morph(a, b, 0.5);
    const ChromaGivenBrightness &ca = a.chroma_given_brightness, &cb = b.chroma_given_brightness,
                                &ch = half.chroma_given_brightness;
    ASSERT_EQ(ch.z, ca.z);
    for (int c = 0; c < 2; ++c)
        for (std::size_t k = 0; k < ca.z.size(); ++k) {
            EXPECT_DOUBLE_EQ(ch.location[c][k], ca.location[c][k] + (cb.location[c][k] - ca.location[c][k]) * 0.5);
            EXPECT_DOUBLE_EQ(ch.scale[c][k], ca.scale[c][k] + (cb.scale[c][k] - ca.scale[c][k]) * 0.5);
        }
    validate(half, "t=0.5");
    // The endpoints are the inputs, renders and all.
    EXPECT_EQ(render_at_photo_scale(morph(a, b, 0)).pixels, render_at_photo_scale(a).pixels);
    EXPECT_EQ(render_at_photo_scale(morph(a, b, 1)).pixels, render_at_photo_scale(b).pixels);
    // Through the interpolation itself (not the endpoints' shortcut): a texture morphed with itself
    // is itself. Measured: 1.6e-12 σ.
    const double itself = max_difference_sigma(render_at_photo_scale(a), render_at_photo_scale(morph(a, a, 0.5)));
    std::printf("morph(a, a, 0.5) vs a: max %.2e sigma\n", itself);
    EXPECT_LT(itself, 1e-5);
    // And continuous at the ends: t = 1e-6 is a within 1e-3 σ (measured 1.7e-6 σ).
    const double near_a = max_difference_sigma(render_at_photo_scale(a), render_at_photo_scale(morph(a, b, 1e-6)));
    std::printf("morph(a, b, 1e-6) vs a: max %.2e sigma\n", near_a);
    EXPECT_LT(near_a, 1e-3);
}

TEST(JointColour, MorphRefusesOneTextureWithAndOneWithout)
{
    // Location 0, scale 1 would express the independent texture, but interpolating its chroma
    // values with the other's unit-spread residuals (and the scales apart) puts the midpoint's
    // chroma spread far above either's (concrete: 8×). So: a clear error, at every t.
    const TextureDescription joint = analysed("wavelet", true), independent = analysed("wavelet", false);
    for (const double t : {0.0, 0.5, 1.0}) {
        const std::string first = error_of([&] { morph(joint, independent, t); });
        const std::string second = error_of([&] { morph(independent, joint, t); });
        EXPECT_NE(first.find("only the first texture has joint colour"), std::string::npos) << first;
        EXPECT_NE(second.find("only the second texture has joint colour"), std::string::npos) << second;
        EXPECT_NE(first.find("same --joint-colour"), std::string::npos) << first;
    }
}

TEST(JointColour, FlippingAnAxisKeepsTheColourStage)
{
    // morph aligns b's axes with a's by negating some: the curves must follow (brightness: read
    // from the other end; a chroma axis: location negated), so that the colour at noise z equals
    // the flipped texture's colour at the flipped noise. (Without flipping the curves, 1705 of
    // these 1800 channel values were off by more than 1e-5.)
    const TextureDescription original = analysed("wavelet", true);
    const std::array<double, 3> sigma_m{1, 1, 1};
    const ColourMapping before(original, sigma_m);
    for (int axis = 0; axis < 3; ++axis) {
        TextureDescription flipped = original;
        for (int r = 0; r < 3; ++r) flipped.basis[r][axis] = -flipped.basis[r][axis];
        if (flipped.histograms[axis].enabled()) flipped.histograms[axis] = mirrored(flipped.histograms[axis]);
        flip_joint_colour_axis(flipped.chroma_given_brightness, axis);
        const ColourMapping after(flipped, sigma_m);
        std::mt19937 rng(axis);
        std::normal_distribution<double> noise;
        for (int i = 0; i < 200; ++i) {
            std::array<double, 3> z{noise(rng), noise(rng), noise(rng)};
            const std::array<double, 3> dropped{i % 2 * 0.3, 0.1, 0};
            const Rgb expected = before.to_rgb(z, dropped);
            z[axis] = -z[axis];
            const Rgb got = after.to_rgb(z, dropped);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5) << "axis " << axis;
        }
    }
}

}  // namespace
}  // namespace stochtex
