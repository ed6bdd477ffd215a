// The OSL-in-C++ shim of the OSL shader tests (osl_*_test.cpp): the names osl/stochtex_*.h use
// that OSL provides, so that each header compiles as C++ and its maths can be compared with the
// core on machines without oslc, and the parsing of a generated shader's parameter block.
//
// texture() is OIIO's closest-texel lookup with periodic wrap (what the shaders ask for): texel
// floor(s·width), floor(t·height) of the image file the generated shader names, channel
// "firstchannel", rows top-down as OIIO runs them — or, while a test sets mirroring_host() (a
// host such as Cycles 5.2, whose rows run bottom-up), row height − 1 − that: the row probe
// (osl/stochtex_subset.h) must then make the shader read the same texels. The images are read
// with OIIO from the very files `stex osl` writes, so the test covers the generator, the images
// and the transcription together. What it cannot check is OSL's own syntax and runtime (float
// literals are double in C++, so a few constant expressions round less than in OSL): the
// oslc/testshade tests do, where OSL is installed.
#pragma once

#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>

#include "test_support.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace osl_shim {

using string = const char*;
using std::abs;
using std::cos;
using std::exp;
using std::floor;
using std::hypot;
using std::log;
using std::log2;
using std::pow;
using std::round;
using std::sin;
using std::sqrt;

// OSL's min/max/clamp for any mix of int and float arguments (one template: no ambiguity
// between overloads when a literal is double).
template <class A, class B>
std::common_type_t<A, B> max(A a, B b)
{
    using T = std::common_type_t<A, B>;
    return T(a) > T(b) ? T(a) : T(b);
}
template <class A, class B>
std::common_type_t<A, B> min(A a, B b)
{
    using T = std::common_type_t<A, B>;
    return T(a) < T(b) ? T(a) : T(b);
}
template <class X, class A, class B>
float clamp(X x, A lo, B hi)
{
    return float(min(max(x, lo), hi));
}

struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<float> texels;
};
inline std::map<std::string, Image>& images()
{
    static std::map<std::string, Image> loaded;
    return loaded;
}

inline Image read_image(const std::string& path)
{
    auto input = OIIO::ImageInput::open(path);
    if (!input) throw stochtex::Error(path + ": " + OIIO::geterror());
    Image image;
    image.width = input->spec().width;
    image.height = input->spec().height;
    image.channels = input->spec().nchannels;
    image.texels.resize(std::size_t(image.width) * image.height * image.channels);
    if (!input->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.texels.data()))
        throw stochtex::Error(path + ": " + input->geterror());
    return image;
}

/// Loads the file a shader parameter names (again: a test may rewrite it for another texture).
inline void load_image(const std::string& path) { images()[path] = read_image(path); }

/// Whether texture() runs rows bottom-up, as Cycles 5.2 does (false: top-down, as OIIO).
inline bool& mirroring_host()
{
    static bool bottom_up = false;
    return bottom_up;
}

/// texture() runs rows bottom-up while one of these lives (so a failed assertion resets it too).
struct MirroringHost {
    MirroringHost() { mirroring_host() = true; }
    ~MirroringHost() { mirroring_host() = false; }
    MirroringHost(const MirroringHost&) = delete;
    MirroringHost& operator=(const MirroringHost&) = delete;
};

inline int first_channel_of() { return 0; }
template <class V, class... Rest>
int first_channel_of(const char* key, V value, Rest... rest)
{
    if constexpr (std::is_integral_v<V>)
        if (std::strcmp(key, "firstchannel") == 0) return int(value);
    return first_channel_of(rest...);
}

template <class... Options>
float texture(string name, float s, float t, Options... options)
{
    const Image& image = images().at(name);
    const int x = int(std::floor(s * image.width)), y = int(std::floor(t * image.height));
    const int wx = ((x % image.width) + image.width) % image.width, wy = ((y % image.height) + image.height) % image.height;
    const int row = mirroring_host() ? image.height - 1 - wy : wy;
    const int channel = first_channel_of(options...);
    return image.texels[(std::size_t(row) * image.width + wx) * image.channels + std::size_t(channel)];
}

}  // namespace osl_shim

#define STOCHTEX_OUT(type) type&
#define STOCHTEX_OUT_ARRAY(type) type

// The row probe's reader (stochtex_rows_bottom_up) and stochtex_row_t, over the texture() above.
namespace osl_shim {
#include "../osl/stochtex_subset.h"
}  // namespace osl_shim

namespace osl_test {

/// The parameters of a generated shader, read back from its text.
struct ShaderParameters {
    std::map<std::string, std::vector<float>> arrays;
    std::map<std::string, std::vector<int>> int_arrays;
    std::map<std::string, std::string> strings;
    std::map<std::string, float> scalars;

    float* a(const std::string& name) { return arrays.at(name).data(); }
    int* i(const std::string& name) { return int_arrays.at(name).data(); }
    const char* s(const std::string& name) const { return strings.at(name).c_str(); }
    float f(const std::string& name) const { return scalars.at(name); }
    int n(const std::string& name) const { return int(scalars.at(name)); }
};

inline ShaderParameters parse_parameters(const std::string& shader)
{
    // The shader's parameter list only (the inlined headers declare local arrays too).
    const std::size_t start = shader.rfind("\nshader ");
    if (start == std::string::npos) throw stochtex::Error("generated shader: no 'shader' declaration");
    const std::string text = shader.substr(start);
    ShaderParameters result;
    const std::regex array_re(R"((float|int) (\w+)\[\d+\] = \{([^}]*)\})");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), array_re); it != std::sregex_iterator(); ++it) {
        std::string body = (*it)[3];
        std::replace(body.begin(), body.end(), ',', ' ');
        std::istringstream in(body);
        std::vector<float> values;
        std::vector<int> ints;
        for (std::string word; in >> word;) {
            values.push_back(std::stof(word));
            if ((*it)[1] == "int") ints.push_back(std::stoi(word));
        }
        result.arrays[(*it)[2]] = values;
        if ((*it)[1] == "int") result.int_arrays[(*it)[2]] = ints;
    }
    const std::regex string_re(R"(string (\w+) = "([^"]*)\")");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), string_re); it != std::sregex_iterator(); ++it)
        result.strings[(*it)[1]] = (*it)[2];
    const std::regex scalar_re(R"((?:float|int) (\w+) = ([-+]?[0-9][0-9.eE+-]*))");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), scalar_re); it != std::sregex_iterator(); ++it)
        result.scalars[(*it)[1]] = std::stof((*it)[2]);
    return result;
}

/// Each RGB channel's standard deviation over 2000 point samples of the core in [−3, 3]²: the
/// unit the comparisons state their errors in.
inline std::array<double, 3> channel_sigmas(const stochtex::Texture& texture)
{
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> position(-3.0, 3.0);
    std::array<double, 3> sum{}, sum2{}, sigma{};
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
        const stochtex::Rgb v = texture.eval({position(rng), position(rng)}, stochtex::Footprint2D{});
        for (int c = 0; c < 3; ++c) sum[c] += v[c], sum2[c] += double(v[c]) * v[c];
    }
    for (int c = 0; c < 3; ++c) sigma[c] = std::sqrt(std::max(1e-30, sum2[c] / n - (sum[c] / n) * (sum[c] / n)));
    return sigma;
}

/// Compiles `shader_text` (shader stochtex_test) in `dir` and shades a size² grid with testshade
/// --center, P over [0, 1]² times `scale`; returns the core's render of the same region
/// (v ∈ [−scale, 0]) and testshade's image in `core`, `shaded`. False (with the output in
/// `log`) when oslc or testshade fails.
inline bool run_testshade(const std::string& shader_text, const stochtex::Texture& texture, const std::string& dir, int size,
                          double scale, stochtex::Image& core, stochtex::Image& shaded, std::string& log)
{
    std::ofstream(dir + "/generated.osl") << shader_text;
    const auto result = stochtex::test::run_command("cd " + stochtex::test::shell_quote(dir) + " && oslc generated.osl && testshade --center -g " +
                                          std::to_string(size) + " " + std::to_string(size) + " --param Scale " +
                                          std::to_string(scale) + " -od float -o Color osl.exr stochtex_test");
    log = result.output;
    if (result.status != 0) return false;
    shaded = stochtex::read_image_linear(dir + "/osl.exr");
    stochtex::RenderSettings settings;
    settings.width = settings.height = size;
    settings.units_per_pixel = scale / size;
    settings.origin_v = -scale;
    core = stochtex::render(texture, settings);
    return true;
}

/// testshade's image (rows top to bottom at v = 0 … −Scale, the shader's (u, v) = (x, −y)) against
/// the core's render of the same region (rows at v = −Scale … 0): the largest per-channel RMS
/// of their difference, in units of the core's channel σ.
inline double testshade_rms_sigma(const stochtex::Image& core, const stochtex::Image& shaded)
{
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
        double sum = 0, sum2 = 0, diff2 = 0;
        const double n = double(core.width) * core.height;
        for (int y = 0; y < core.height; ++y)
            for (int x = 0; x < core.width; ++x) {
                const double v = core.at(x, y, c), d = v - shaded.at(x, core.height - 1 - y, c);
                sum += v, sum2 += v * v, diff2 += d * d;
            }
        const double sigma = std::sqrt(std::max(1e-30, sum2 / n - (sum / n) * (sum / n)));
        worst = std::max(worst, std::sqrt(diff2 / n) / sigma);
    }
    return worst;
}

/// One point in a top-down host and in a mirroring one (Cycles 5.2): `shade(rows)` evaluates a
/// shader with its row flag read from its probe (rows < 0) or given. Fails unless the mirroring
/// host gives the top-down values bit for bit through the probe; returns, in units of `sigma`,
/// how far a shader that ignored the probe (flag 0) would be off there.
template <class Shade>
double mirroring_host_difference(Shade shade, const std::array<double, 3>& sigma, const std::string& where)
{
    const stochtex::Rgb top_down = shade(-1);
    osl_shim::MirroringHost mirroring;
    const stochtex::Rgb bottom_up = shade(-1), ignored = shade(0);
    double unprobed = 0;
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(bottom_up[c], top_down[c]) << where << ", channel " << c;
        unprobed = std::max(unprobed, std::abs(double(ignored[c]) - top_down[c]) / sigma[c]);
    }
    return unprobed;
}

/// A generated shader compiles on its own: headers inlined, renamed, parameters filled, ASCII.
inline void expect_self_contained(const std::string& text)
{
    EXPECT_EQ(text.find("#include"), std::string::npos) << "the headers must be inlined";
    EXPECT_NE(text.find("shader stochtex_test("), std::string::npos);
    EXPECT_EQ(text.find("@stochtex-parameters"), std::string::npos);
    // Cycles 5.2 ignores texture()'s "firstchannel": every lookup must read a single-channel image.
    EXPECT_EQ(text.find("\"firstchannel\""), std::string::npos) << "Cycles 5.2 reads channel 0 whatever is asked";
    for (char c : text) ASSERT_LT((unsigned char)c, 128) << "oslc reads ASCII safely; keep shaders ASCII";
}

/// run_testshade, then the pixel RMS in σ (printed with `model`); a failure of oslc or testshade
/// fails the test and returns infinity.
inline double testshade_rms(const char* model, const std::string& shader_text, const stochtex::Texture& texture,
                            const std::string& dir, int size, double scale)
{
    stochtex::Image core, shaded;
    std::string log;
    if (!run_testshade(shader_text, texture, dir, size, scale, core, shaded, log)) {
        ADD_FAILURE() << log;
        return HUGE_VAL;
    }
    const double rms = testshade_rms_sigma(core, shaded);
    std::printf("%s testshade vs stex render: rms %.2e sigma\n", model, rms);
    return rms;
}

}  // namespace osl_test
