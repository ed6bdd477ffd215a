// The built-in image codecs (core/src/image/image_codec.h) against OpenImageIO, which they
// replace on the common paths: the same pixels read, the same bytes or pixels and metadata
// written, and linear ↔ sRGB bit for bit as OIIO converts.
#include <stochtex/image.h>

#include "image/image_codec.h"
#include "image/png_memory.h"
#include "test_support.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

namespace {

using namespace stochtex;

std::string bytes_of(const std::string& path)
{
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

std::vector<float> random_values(std::size_t count, std::uint32_t seed, float lo = 0.0f, float hi = 1.0f)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> uniform(lo, hi);
    std::vector<float> values(count);
    for (float& v : values) v = uniform(random);
    return values;
}

void write_with_oiio(const std::string& path, const OIIO::ImageSpec& spec, const float* pixels)
{
    auto output = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(output);
    ASSERT_TRUE(output->open(path, spec) && output->write_image(OIIO::TypeDesc::FLOAT, pixels) && output->close())
        << output->geterror();
}

std::vector<float> read_with_oiio(const std::string& path, OIIO::ImageSpec* spec_out = nullptr, int level = 0)
{
    auto input = OIIO::ImageInput::open(path);
    EXPECT_TRUE(input) << OIIO::geterror();
    if (!input) return {};
    OIIO::ImageSpec spec;
    EXPECT_TRUE(input->seek_subimage(0, level));
    spec = input->spec();
    std::vector<float> pixels(spec.image_pixels() * spec.nchannels);
    EXPECT_TRUE(input->read_image(0, level, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) << input->geterror();
    if (spec_out) *spec_out = spec;
    return pixels;
}

std::vector<float> read_with_built_in(codec::ImageCodec& codec, const std::string& path, codec::ImageHeader* header_out)
{
    std::string error;
    auto reader = codec.open(path, false, error);
    EXPECT_TRUE(reader) << path << ": " << error;
    if (!reader) return {};
    const codec::ImageHeader& header = reader->header();
    std::vector<float> pixels(std::size_t(header.width) * header.height * header.channels);
    error = reader->read(header.channels, pixels.data());
    EXPECT_EQ(error, "");
    if (header_out) *header_out = header;
    return pixels;
}

/// Floats in [0, 1] (every 31st bit pattern: 35 million values, both sides of each curve's
/// threshold; run once over all 2^30 of them, also 0 differences) and a sample beyond 1, through
/// convert_colour_space and through OIIO's colorconvert: the same bits. Prints the largest
/// difference (0 when they agree).
TEST(ImageCodec, LinearSrgbConversionIsOiiosBitForBit)
{
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"linear", "sRGB"}, {"sRGB", "linear"}}) {
        std::size_t mismatches = 0;
        double largest = 0;
        const std::uint32_t one = 0x3f800000u, chunk = 3u << 20, step = 31;
        for (std::uint32_t first = 0; first <= one / step + 3 * 4096; first += chunk) {
            Image image(int(chunk / 3), 1, 3);
            for (std::uint32_t i = 0; i < chunk; ++i) {
                std::uint64_t bits = (std::uint64_t(first) + i) * step;
                // beyond 1: a sample up to ~1e7
                bits = bits <= one ? bits : one + (bits - one) / step * 4099u;
                const std::uint32_t pattern = std::uint32_t(bits);
                std::memcpy(&image.pixels[i], &pattern, 4);
            }
            std::vector<float> reference = image.pixels;
            OIIO::ImageBuf buffer(OIIO::ImageSpec(image.width, 1, 3, OIIO::TypeDesc::FLOAT), reference.data());
            ASSERT_TRUE(OIIO::ImageBufAlgo::colorconvert(buffer, buffer, from, to));
            convert_colour_space(image, from, to);
            for (std::size_t i = 0; i < reference.size(); ++i)
                if (std::memcmp(&reference[i], &image.pixels[i], 4) != 0) {
                    ++mismatches;
                    largest = std::max(largest, std::fabs(double(reference[i]) - image.pixels[i]));
                }
        }
        std::printf("%s -> %s: %zu values differ from OIIO, largest difference %g\n", from.c_str(), to.c_str(),
                    mismatches, largest);
        EXPECT_EQ(mismatches, 0u) << from << " -> " << to;
    }
}

TEST(ImageCodec, PngReadsTheSamePixelsAsOiio)
{
    const std::string dir = test::temp_dir("ImageCodec.PngRead");
    for (const OIIO::TypeDesc type : {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16})
        for (int channels : {1, 3}) {
            const std::string path = dir + "/p" + std::to_string(channels) + "_" + type.c_str() + ".png";
            const std::vector<float> values = random_values(std::size_t(37) * 29 * channels, 7u + channels);
            write_with_oiio(path, OIIO::ImageSpec(37, 29, channels, type), values.data());
            OIIO::ImageSpec spec;
            const std::vector<float> expected = read_with_oiio(path, &spec);
            codec::ImageHeader header;
            const std::vector<float> pixels = read_with_built_in(codec::png_codec(), path, &header);
            EXPECT_EQ(header.width, spec.width);
            EXPECT_EQ(header.height, spec.height);
            EXPECT_EQ(header.channels, spec.nchannels);
            EXPECT_EQ(header.attribute("oiio:ColorSpace"), spec.get_string_attribute("oiio:ColorSpace")) << path;
            ASSERT_EQ(pixels.size(), expected.size());
            EXPECT_EQ(std::memcmp(pixels.data(), expected.data(), 4 * pixels.size()), 0) << path;
        }
}

TEST(ImageCodec, PngDeclinesWhatOiioInterprets)
{
    const std::string dir = test::temp_dir("ImageCodec.PngDecline");
    const std::string alpha = dir + "/alpha.png";
    const std::vector<float> values = random_values(16 * 16 * 4, 3);
    OIIO::ImageSpec spec(16, 16, 4, OIIO::TypeDesc::UINT8);
    spec.alpha_channel = 3;
    write_with_oiio(alpha, spec, values.data());
    // Alpha (associated on reading), and a gAMA chunk (OIIO: "Gamma2.2"): left to OIIO.
    for (const std::string& path : {alpha, test::repo_exemplar("concrete_512.png")}) {
        std::string error;
        EXPECT_FALSE(codec::png_codec().open(path, false, error)) << path;
        EXPECT_EQ(error, "") << path;
    }
}

TEST(ImageCodec, PngWritesOiiosBytes)
{
    const std::string dir = test::temp_dir("ImageCodec.PngWrite");
    Image image(45, 31, 3);
    image.pixels = random_values(image.pixels.size(), 11, -0.1f, 1.3f);
    write_image(dir + "/built_in.png", image);
    Image encoded = image;
    convert_colour_space(encoded, "linear", "sRGB");
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("Software", "stochtex " STOCHTEX_VERSION);
    for (float& v : encoded.pixels) v = std::clamp(v, 0.0f, 1.0f);
    write_with_oiio(dir + "/oiio.png", spec, encoded.pixels.data());
    EXPECT_EQ(bytes_of(dir + "/built_in.png"), bytes_of(dir + "/oiio.png"));
}

TEST(ImageCodec, GreyPngInMemoryIsOiiosEncoding)
{
    for (int bits : {8, 16}) {
        const int width = 53, height = 71;
        std::vector<std::uint16_t> samples(std::size_t(width) * height);
        std::mt19937 random(bits);
        for (auto& s : samples) s = std::uint16_t(random() % (bits == 16 ? 65536 : 256));
        // The encoder stochtex used before (schema/quantised_image.cpp, then in stex/, through OIIO).
        const OIIO::TypeDesc type = bits == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
        std::vector<std::uint8_t> narrow(samples.begin(), samples.end());
        std::vector<unsigned char> expected;
        OIIO::Filesystem::IOVecOutput memory(expected);
        auto out = OIIO::ImageOutput::create("png");
        OIIO::ImageSpec spec(width, height, 1, type);
        spec.attribute("png:compressionLevel", 9);
        void* proxy = &memory;
        spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        ASSERT_TRUE(out->open("exemplar.png", spec) &&
                    out->write_image(type, bits == 16 ? static_cast<const void*>(samples.data()) : narrow.data()) &&
                    out->close());
        const std::vector<std::uint8_t> png = codec::encode_grey_png(width, height, bits, samples.data());
        EXPECT_EQ(png, std::vector<std::uint8_t>(expected.begin(), expected.end())) << bits << " bits";
        int w = 0, h = 0, channels = 0, stored = 0;
        std::vector<std::uint16_t> decoded;
        EXPECT_EQ(codec::decode_grey_png(png, w, h, channels, stored, &decoded), "");
        EXPECT_EQ(w, width);
        EXPECT_EQ(h, height);
        EXPECT_EQ(channels, 1);
        EXPECT_EQ(stored, bits);
        EXPECT_EQ(decoded, samples);
    }
}

TEST(ImageCodec, ExrReadsTheSamePixelsAndChannelsAsOiio)
{
    const std::string dir = test::temp_dir("ImageCodec.ExrRead");
    struct Case {
        std::vector<std::string> names;
        OIIO::TypeDesc type;
        int alpha;
    };
    const std::vector<Case> cases{{{"R", "G", "B"}, OIIO::TypeDesc::FLOAT, -1},
                                  {{"R", "G", "B", "A"}, OIIO::TypeDesc::HALF, 3},
                                  {{"c0", "c1", "c2", "c3", "c4"}, OIIO::TypeDesc::FLOAT, -1}};
    int n = 0;
    for (const Case& c : cases) {
        const std::string path = dir + "/e" + std::to_string(n++) + ".exr";
        OIIO::ImageSpec spec(23, 19, int(c.names.size()), c.type);
        spec.channelnames = c.names;
        spec.alpha_channel = c.alpha;
        const std::vector<float> values = random_values(spec.image_pixels() * c.names.size(), 5u + n, -2.0f, 40.0f);
        write_with_oiio(path, spec, values.data());
        OIIO::ImageSpec read_spec;
        const std::vector<float> expected = read_with_oiio(path, &read_spec);
        codec::ImageHeader header;
        const std::vector<float> pixels = read_with_built_in(codec::exr_codec(), path, &header);
        EXPECT_EQ(header.channel_names, read_spec.channelnames) << path;
        EXPECT_EQ(header.alpha_channel, read_spec.alpha_channel) << path;
        EXPECT_EQ(header.attribute("oiio:ColorSpace"), read_spec.get_string_attribute("oiio:ColorSpace")) << path;
        ASSERT_EQ(pixels.size(), expected.size());
        EXPECT_EQ(std::memcmp(pixels.data(), expected.data(), 4 * pixels.size()), 0) << path;
    }
}

/// Layered names (the ptm coefficient maps) are left to OIIO, unless the caller finds channels
/// by name: then every named channel holds OIIO's values.
TEST(ImageCodec, ExrReadsLayeredChannelsByName)
{
    const std::string path = test::temp_dir("ImageCodec.ExrByName") + "/layers.exr";
    OIIO::ImageSpec spec(11, 7, 5, OIIO::TypeDesc::HALF);
    spec.channelnames = {"Y.b0", "Y.b1", "chroma.R", "chroma.G", "chroma.B"};
    const std::vector<float> values = random_values(spec.image_pixels() * 5, 17, -3.0f, 3.0f);
    write_with_oiio(path, spec, values.data());
    std::string error;
    EXPECT_FALSE(codec::exr_codec().open(path, false, error));
    EXPECT_EQ(error, "");
    OIIO::ImageSpec read_spec;
    const std::vector<float> expected = read_with_oiio(path, &read_spec);
    auto reader = codec::exr_codec().open(path, true, error);
    ASSERT_TRUE(reader) << error;
    const codec::ImageHeader header = reader->header();
    ASSERT_EQ(header.channels, 5);
    std::vector<float> pixels(std::size_t(header.width) * header.height * 5);
    ASSERT_EQ(reader->read(5, pixels.data()), "");
    for (int c = 0; c < 5; ++c) {
        const int theirs = read_spec.channelindex(header.channel_names[c]);
        ASSERT_GE(theirs, 0) << header.channel_names[c];
        for (std::size_t i = 0; i < pixels.size() / 5; ++i)
            ASSERT_EQ(pixels[i * 5 + c], expected[i * 5 + theirs]) << header.channel_names[c] << " texel " << i;
    }
}

/// A scanline image and a tiled MIP-mapped one, written by the built-in codec and by OIIO's:
/// OIIO reads the same pixels, levels, tiles and metadata from both.
TEST(ImageCodec, ExrWritesWhatOiioWrote)
{
    const std::string dir = test::temp_dir("ImageCodec.ExrWrite");
    codec::ImageCodec& oiio = codec::oiio_codec("test");
    codec::ImageHeader header;
    header.width = 29, header.height = 17, header.channels = 4, header.alpha_channel = 3;
    header.set("compression", "zip");
    header.set("Software", "stochtex test");
    header.set("oiio:ColorSpace", "Linear");
    const std::vector<float> values = random_values(29 * 17 * 4, 13, -1.0f, 8.0f);
    codec::MipSource mip;
    mip.header.width = 64, mip.header.height = 32, mip.header.channels = 3, mip.header.tile_size = 16;
    mip.header.sample = codec::Sample::half;
    for (const char* name : {"compression", "Software", "oiio:ColorSpace"}) mip.header.set(name, header.attribute(name));
    mip.header.set("textureformat", "Plain Texture");
    mip.header.set("wrapmodes", "periodic,periodic");
    mip.header.set("stochtex:source", "test.png");
    mip.levels = 7;
    mip.level_size = [](int level) { return std::pair<int, int>(std::max(1, 64 >> level), std::max(1, 32 >> level)); };
    mip.fill = [](int level, int y0, int rows, float* strip) {
        const int width = std::max(1, 64 >> level);
        for (int y = 0; y < rows; ++y)
            for (int x = 0; x < width; ++x)
                for (int c = 0; c < 3; ++c) strip[(std::size_t(y) * width + x) * 3 + c] = float(level * 1000 + (y0 + y) * 64 + x) + 0.25f * c;
    };
    for (const bool tiled : {false, true}) {
        const std::string mine = dir + (tiled ? "/mine_mip.exr" : "/mine.exr");
        const std::string theirs = dir + (tiled ? "/oiio_mip.exr" : "/oiio.exr");
        if (tiled) {
            ASSERT_EQ(codec::exr_codec().write_mip(mine, mine, mip), "");
            ASSERT_EQ(oiio.write_mip(theirs, theirs, mip), "");
        } else {
            ASSERT_EQ(codec::exr_codec().write(mine, mine, header, values.data()), "");
            ASSERT_EQ(oiio.write(theirs, theirs, header, values.data()), "");
        }
        for (int level = 0; level < (tiled ? mip.levels : 1); ++level) {
            OIIO::ImageSpec a, b;
            EXPECT_EQ(read_with_oiio(mine, &a, level), read_with_oiio(theirs, &b, level)) << mine << " level " << level;
            EXPECT_EQ(a.channelnames, b.channelnames);
            EXPECT_EQ(a.alpha_channel, b.alpha_channel);
            EXPECT_EQ(a.format, b.format);
            EXPECT_EQ(a.tile_width, b.tile_width);
            EXPECT_EQ(a.tile_height, b.tile_height);
            // The same metadata, but for the time each file was written.
            OIIO::ParamValueList mine_attributes = a.extra_attribs, their_attributes = b.extra_attribs;
            mine_attributes.remove("DateTime");
            their_attributes.remove("DateTime");
            ASSERT_EQ(mine_attributes.size(), their_attributes.size()) << mine;
            for (const OIIO::ParamValue& p : their_attributes) {
                const OIIO::ParamValue* q = mine_attributes.find_pv(p.name());
                ASSERT_TRUE(q) << mine << " lacks " << p.name();
                EXPECT_EQ(q->get_string(), p.get_string()) << p.name();
            }
        }
    }
}

}  // namespace

namespace {

/// What `stex` needs at start-up: not OIIO. It renders PNG and EXR with the module out of
/// reach, and names the module when a format needs it.
TEST(ImageCodec, StexRendersPngAndExrWithoutTheOiioModule)
{
    const std::string dir = test::temp_dir("ImageCodec.NoModule");
    const std::string stex = "STOCHTEX_OIIO_MODULE=/nonexistent/stochtex_oiio.so " + test::shell_quote(STOCHTEX_CLI);
    const std::string texture = test::shell_quote(dir + "/phasor.stex");
    const test::CommandResult made = test::run_command(stex + " tiling phasor -o " + texture);
    ASSERT_EQ(made.status, 0) << made.output;
    for (const char* image : {"/a.exr", "/a.png"}) {
        const test::CommandResult r =
            test::run_command(stex + " render " + texture + " --size 8x8 -o " + test::shell_quote(dir + image));
        EXPECT_EQ(r.status, 0) << image << ": " << r.output;
    }
    const test::CommandResult tif =
        test::run_command(stex + " render " + texture + " --size 8x8 -o " + test::shell_quote(dir + "/a.tif"));
    EXPECT_NE(tif.status, 0);
    EXPECT_TRUE(test::contains(tif.output, "writing '.tif' files needs the OpenImageIO module /nonexistent/stochtex_oiio.so"))
        << tif.output;
    if (test::on_path("ldd")) {
        const test::CommandResult libraries = test::run_command("ldd " + test::shell_quote(STOCHTEX_CLI));
        EXPECT_FALSE(test::contains(libraries.output, "libOpenImageIO")) << libraries.output;
    }
}

}  // namespace
