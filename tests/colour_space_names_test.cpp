// Gamma-encoded colour spaces by OIIO 2.x's names ("Gamma2.2") and OIIO 3.x's ("g22_rec709",
// "g22_rec709_scene"), whichever OIIO stochtex is built with (issue 31): a photo that OIIO 2.4
// tagged "Gamma2.2" (the committed exemplar) must read under OIIO 3.1, and every gamma decodes to
// the plain power it is.
#include "image/colour_space_names.h"
#include "test_support.h"

#include <stochtex/image.h>

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

using namespace stochtex;

TEST(ColourSpaceNames, GammaFromEitherMajorsName)
{
    EXPECT_DOUBLE_EQ(encoding_gamma("Gamma2.2"), 2.2);
    EXPECT_DOUBLE_EQ(encoding_gamma("Gamma1.8"), 1.8);
    EXPECT_DOUBLE_EQ(encoding_gamma("g22_rec709"), 2.2);
    EXPECT_DOUBLE_EQ(encoding_gamma("g22_rec709_scene"), 2.2);
    EXPECT_DOUBLE_EQ(encoding_gamma("g26_rec709_scene"), 2.6);
    for (const char* other : {"sRGB", "linear", "lin_rec709_scene", "Gamma", "GammaX", "Gamma2.2x", "g_rec709",
                              "g2x_rec709", "srgb_rec709_scene", "Gamma-1"})
        EXPECT_EQ(encoding_gamma(other), 0) << other;
}

TEST(ColourSpaceNames, NamesTheLinkedOiioKnows)
{
    EXPECT_EQ(oiio_colour_space_name("sRGB"), "sRGB");
#if OIIO_VERSION_MAJOR >= 3
    EXPECT_EQ(oiio_colour_space_name("Gamma2.2"), "g22_rec709");
    EXPECT_EQ(oiio_colour_space_name("g18_rec709_scene"), "g18_rec709");
    EXPECT_EQ(oiio_colour_space_name("Gamma2.4"), "");  // no name: a plain power, applied by stochtex
#else
    EXPECT_EQ(oiio_colour_space_name("Gamma2.2"), "Gamma2.2");
    EXPECT_EQ(oiio_colour_space_name("g22_rec709_scene"), "Gamma2.2");
    EXPECT_EQ(oiio_colour_space_name("g24_rec709"), "Gamma2.4");
#endif
}

TEST(ColourSpaceNames, EveryGammaDecodesToItsPower)
{
    for (const char* name : {"Gamma2.2", "g22_rec709", "g22_rec709_scene", "Gamma1.8", "Gamma2.4", "g24_rec709_scene",
                             "Gamma2.6"}) {
        const double gamma = encoding_gamma(name);
        Image image(4, 4, 3);
        for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) / float(image.pixels.size());
        const std::vector<float> encoded = image.pixels;
        convert_colour_space(image, name, "linear");
        for (std::size_t i = 0; i < encoded.size(); ++i)
            ASSERT_NEAR(image.pixels[i], std::pow(encoded[i], gamma), 2e-5) << name << " at " << encoded[i];
        convert_colour_space(image, "linear", name);
        for (std::size_t i = 0; i < encoded.size(); ++i) ASSERT_NEAR(image.pixels[i], encoded[i], 2e-5) << name;
    }
}

TEST(ColourSpaceNames, ExemplarTaggedGamma22ByOiio24Reads)
{
    // data/exemplars/concrete_512.png has a gAMA chunk and the tEXt oiio:ColorSpace "Gamma2.2".
    const std::string path = test::repo_exemplar("concrete_512.png");
    const Image linear = read_image_linear(path);
    auto input = OIIO::ImageInput::open(path);
    ASSERT_TRUE(input) << OIIO::geterror();
    std::vector<float> encoded(std::size_t(512) * 512 * 3);
    ASSERT_TRUE(input->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, encoded.data())) << input->geterror();
    for (std::size_t i = 0; i < encoded.size(); i += 97) ASSERT_NEAR(linear.pixels[i], std::pow(encoded[i], 2.2), 2e-5) << i;
}

}  // namespace
