// Morphing (paper 000, Fig. 15): exact endpoints, U(t) a rotation, continuous statistics.
#include "test_support.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/morph.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/wavelet_parameters.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace stochtex {
namespace {

TextureDescription analyse_crop(const Image& photo, int x0, int y0, int size, double gain)
{
    Image crop(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) crop.at(x, y, c) = float(gain * photo.at(x0 + x, y0 + y, c) * (1 + 0.3 * c));
    AnalysisOptions options;
    options.histogram = HistogramMode::on;
    return analyze(crop, options);
}

}  // namespace

TEST(Morph, EndpointsAreExactAndBasisStaysARotation)
{
    const Image photo = read_image_linear(test::repo_exemplar("concrete_512.png"));
    const TextureDescription a = analyse_crop(photo, 0, 0, 256, 1.0);
    const TextureDescription b = analyse_crop(photo, 128, 200, 128, 0.5);  // fewer bands, darker
    EXPECT_EQ(format_stex(morph(a, b, 0)), format_stex(a));
    EXPECT_EQ(format_stex(morph(a, b, 1)), format_stex(b));
    for (double t : {0.1, 0.5, 0.9}) {
        const TextureDescription m = morph(a, b, t);
        Eigen::Matrix3d u;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) u(r, c) = m.basis[r][c];
        EXPECT_NEAR((u.transpose() * u - Eigen::Matrix3d::Identity()).norm(), 0, 1e-9) << "t = " << t;
        EXPECT_NEAR(u.determinant(), 1, 1e-9);
        EXPECT_EQ(m.parameters.get<WaveletParameters>().band_weights[0].size(), a.parameters.get<WaveletParameters>().band_weights[0].size());
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.mean[c], a.mean[c] + t * (b.mean[c] - a.mean[c]), 1e-12);
        EXPECT_NO_THROW(validate(m, "morph"));
    }
}

TEST(Morph, RenderedMeanVariesContinuously)
{
    const Image photo = read_image_linear(test::repo_exemplar("concrete_512.png"));
    const TextureDescription a = analyse_crop(photo, 0, 0, 256, 1.0);
    const TextureDescription b = analyse_crop(photo, 256, 256, 256, 0.4);
    RenderSettings settings;
    settings.width = settings.height = 64;
    settings.units_per_pixel = 1.0 / 256;
    double previous = -1;
    for (int i = 0; i <= 10; ++i) {
        const Image image = render(*make_texture(morph(a, b, i / 10.0)), settings);
        double mean = 0;
        for (float v : image.pixels) mean += v / image.pixels.size();
        if (previous >= 0) {
            EXPECT_LT(mean, previous + 1e-3) << "the morph darkens monotonically, step " << i;
            EXPECT_LT(previous - mean, 0.2 * previous) << "no jump at step " << i;
        }
        previous = mean;
    }
}

TEST(Morph, RejectsMismatchedInputs)
{
    const Image photo = read_image_linear(test::repo_exemplar("concrete_512.png"));
    const TextureDescription a = analyse_crop(photo, 0, 0, 128, 1.0);
    TextureDescription rgb = a;
    rgb.colour_mode = ColourMode::rgb;
    EXPECT_THROW(morph(a, rgb, 0.5), Error);
    EXPECT_THROW(morph(a, a, 1.5), Error);
    EXPECT_THROW(morph(a, a, std::nan("")), Error);
}

}  // namespace stochtex
