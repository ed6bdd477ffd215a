// .stex reading, writing and validation: canonical round trips, and an Error naming the file and
// the field (as a JSON path) for every kind of bad input.
#include <stochtex/error.h>
#include <stochtex/model.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/wavelet_parameters.h>

#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>

namespace fs = std::filesystem;
using stochtex::Error;
using stochtex::TextureDescription;
using Json = nlohmann::ordered_json;

namespace {

/// A description using every field, with numbers that are not exact floats (0.1, 1/3), tiny and
/// huge ones, negatives, a seed above 2^31 and options out of alphabetical order.
TextureDescription sample()
{
    TextureDescription d;
    d.model = "wavelet";
    d.seed = 4000000000u;
    d.pixels_per_unit = 512;
    d.unit_size_m = 0.35;
    d.colour_mode = stochtex::ColourMode::pca;
    d.mean = {0.1, -0.25, 1e-7};
    // A rotation: about z by 30°, then about x by 40°.
    const double degree = std::acos(-1.0) / 180, a = 30 * degree, b = 40 * degree;
    const double rz[3][3] = {{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}};
    const double rx[3][3] = {{1, 0, 0}, {0, std::cos(b), -std::sin(b)}, {0, std::sin(b), std::cos(b)}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            d.basis[i][j] = 0;
            for (int k = 0; k < 3; ++k) d.basis[i][j] += rx[i][k] * rz[k][j];
        }
    // 0x1.5c87fap-84 is the one positive float whose shortest text reads back (as a double,
    // then rounded to float) as its neighbour: the writer must handle it.
    d.histograms[0] = {{-3, -1.5, -0.5, 0, 0.5, 1.5, 3},
                       {-0.5, static_cast<double>(0x1.5c87fap-84f), 0.1, 0.1, 1.0 / 3.0, 0.7, 12.5}};
    d.histograms[2] = {{-2, -1, 1, 2}, {1e-7, 2e-7, 3e-7, 1e10}};
    d.parameters = stochtex::WaveletParameters{
        {{{1, 0.5, 0.25, 0.1, 0}, {0.3, 1e-7, 2, 0.01, 0.5}, {1.0 / 3.0, 2.0 / 3.0, 1, 0, 0}}}};
    d.provenance.source = "brick \"wall\" é.jpg";
    d.provenance.source_width = 1024;
    d.provenance.source_height = 768;
    d.provenance.input_colour_space = "sRGB";
    d.provenance.tool = "stochtex 0.1.0";
    d.provenance.options = {{"model", "wavelet"}, {"bands", "5"}, {"alpha", "0.5"}};
    return d;
}

std::string read_bytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The message of the Error that `action` throws ("" and a test failure if it throws none).
std::string error_of(const std::function<void()>& action)
{
    try {
        action();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no stochtex::Error thrown";
    return "";
}

std::string parse_error(const std::string& text)
{
    return error_of([&] { stochtex::parse_stex(text, "t.stex"); });
}

std::string validate_error(const TextureDescription& description)
{
    return error_of([&] { stochtex::validate(description, "t.stex"); });
}

/// The sample's text with one edit applied to its JSON.
std::string edited(const std::function<void(Json&)>& edit)
{
    Json json = Json::parse(stochtex::format_stex(sample()));
    edit(json);
    return json.dump(2);
}

/// The sample's text with `from` replaced by `to` (for edits JSON values cannot express).
std::string replaced(const std::string& from, const std::string& to)
{
    std::string text = stochtex::format_stex(sample());
    std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

bool starts_with(const std::string& text, const std::string& prefix)
{
    return text.compare(0, prefix.size(), prefix) == 0;
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

}  // namespace

// ---- Writing and round trips --------------------------------------------------------------------

TEST(StexFile, RoundTripIsByteIdentical)
{
    const std::string dir = stochtex::test::temp_dir("stex_round_trip");
    const std::string first = dir + "/first.stex", second = dir + "/second.stex";
    stochtex::write_stex(first, sample());
    const TextureDescription read = stochtex::read_stex(first);
    stochtex::write_stex(second, read);

    const std::string text = read_bytes(first);
    EXPECT_EQ(text, stochtex::format_stex(sample()));
    EXPECT_EQ(read_bytes(second), text);
    EXPECT_EQ(stochtex::format_stex(stochtex::parse_stex(text, "again")), text);
    // Only the two files: the temporary files were renamed.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

// Optional blocks and lists are written only where the description has them: a file of a named
// model (no model choice) and without an image layout has neither key, and reads back so.
TEST(StexFile, AbsentOptionalFieldsAreNotWritten)
{
    TextureDescription plain = sample();
    plain.provenance.model_choice.clear();
    plain.image.reset();
    const std::string text = stochtex::format_stex(plain);
    EXPECT_FALSE(contains(text, "model_choice")) << text;
    EXPECT_FALSE(contains(text, "\"image\"")) << text;
    EXPECT_TRUE(stochtex::parse_stex(text, "plain").provenance.model_choice.empty());

    TextureDescription chosen = plain;
    stochtex::ModelScore score;
    score.model = plain.model;
    score.penalty = 0.5;
    chosen.provenance.model_choice.push_back(score);
    const std::string chosen_text = stochtex::format_stex(chosen);
    EXPECT_TRUE(contains(chosen_text, "\"model_choice\"")) << chosen_text;
    EXPECT_EQ(stochtex::format_stex(stochtex::parse_stex(chosen_text, "chosen")), chosen_text);
}

TEST(StexFile, RoundTripKeepsValuesToFloatPrecision)
{
    const TextureDescription original = sample();
    const TextureDescription read = stochtex::parse_stex(stochtex::format_stex(original), "t.stex");
    auto same_float = [](double a, double b) { return static_cast<float>(a) == static_cast<float>(b); };

    EXPECT_EQ(read.seed, 4000000000u);  // integers do not go through float
    EXPECT_EQ(read.model, "wavelet");
    EXPECT_EQ(read.colour_mode, stochtex::ColourMode::pca);
    EXPECT_TRUE(same_float(read.pixels_per_unit, 512));
    EXPECT_TRUE(same_float(read.unit_size_m, 0.35));
    for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(same_float(read.mean[c], original.mean[c])) << c;
        for (int r = 0; r < 3; ++r) EXPECT_TRUE(same_float(read.basis[r][c], original.basis[r][c])) << r << c;
        ASSERT_EQ(read.histograms[c].value.size(), original.histograms[c].value.size());
        for (std::size_t i = 0; i < read.histograms[c].value.size(); ++i) {
            EXPECT_TRUE(same_float(read.histograms[c].z[i], original.histograms[c].z[i]));
            EXPECT_TRUE(same_float(read.histograms[c].value[i], original.histograms[c].value[i]));
        }
        ASSERT_EQ(read.parameters.get<stochtex::WaveletParameters>().band_weights[c].size(), 5u);
        for (std::size_t j = 0; j < 5; ++j)
            EXPECT_TRUE(same_float(read.parameters.get<stochtex::WaveletParameters>().band_weights[c][j], original.parameters.get<stochtex::WaveletParameters>().band_weights[c][j]));
    }
    EXPECT_FALSE(read.histograms[1].enabled());
    EXPECT_EQ(read.provenance.source, "brick \"wall\" é.jpg");
    EXPECT_EQ(read.provenance.source_width, 1024);
    EXPECT_EQ(read.provenance.source_height, 768);
    EXPECT_EQ(read.provenance.input_colour_space, "sRGB");
    EXPECT_EQ(read.provenance.tool, "stochtex 0.1.0");
    EXPECT_EQ(read.provenance.options, original.provenance.options);  // order kept
}

TEST(StexFile, WritesShortReadableText)
{
    TextureDescription description = sample();
    description.mean[2] = -0.0;  // written as 0: "-0" would read back as the integer 0
    const std::string text = stochtex::format_stex(description);

    EXPECT_TRUE(starts_with(text, "{\n  \"format\": \"stex\",\n  \"version\": 1,\n  \"model\": \"wavelet\",\n"
                                  "  \"seed\": 4000000000,\n  \"scale\": {\n    \"pixels_per_unit\": 512,\n"))
        << text;
    EXPECT_TRUE(contains(text, "\"mean\": [0.1, -0.25, 0]")) << text;
    EXPECT_TRUE(contains(text, "\"z\": [-3, -1.5, -0.5, 0, 0.5, 1.5, 3]")) << text;
    EXPECT_TRUE(contains(text, "[0.3, 1e-07, 2, 0.01, 0.5]")) << text;
    EXPECT_TRUE(contains(text, "\"basis\": [\n      [")) << text;
    EXPECT_TRUE(contains(text, "\"histograms\": [\n    {")) << text;
    EXPECT_TRUE(contains(text, "},\n    null,\n    {")) << text;
    EXPECT_TRUE(contains(text, "\"source_size\": [1024, 768]")) << text;
    EXPECT_TRUE(contains(text, "\"options\": {\n      \"model\": \"wavelet\",\n      \"bands\": \"5\",")) << text;
    EXPECT_EQ(text.back(), '\n');

    std::size_t previous = 0;
    for (const char* key : {"\"format\"", "\"version\"", "\"model\"", "\"seed\"", "\"scale\"", "\"colour\"",
                            "\"histograms\"", "\"parameters\"", "\"provenance\""}) {
        std::size_t at = text.find(std::string("\n  ") + key);
        ASSERT_NE(at, std::string::npos) << key;
        EXPECT_GT(at, previous) << key;
        previous = at;
    }
}

TEST(StexFile, DoublesEqualAsFloatsWriteTheSameText)
{
    TextureDescription a = sample(), b = sample();
    b.mean = {static_cast<double>(0.1f), static_cast<double>(-0.25f), static_cast<double>(1e-7f)};
    EXPECT_EQ(stochtex::format_stex(a), stochtex::format_stex(b));
}

TEST(StexFile, WriteFailureNamesThePath)
{
    const std::string path = stochtex::test::temp_dir("stex_write_failure") + "/missing-dir/t.stex";
    const std::string message = error_of([&] { stochtex::write_stex(path, sample()); });
    EXPECT_TRUE(starts_with(message, path + ": cannot write")) << message;
}

TEST(StexFile, WriteRefusesAnInvalidDescription)
{
    TextureDescription description = sample();
    description.parameters.get<stochtex::WaveletParameters>().band_weights[0][0] = -1;
    const std::string path = stochtex::test::temp_dir("stex_write_invalid") + "/t.stex";
    const std::string message = error_of([&] { stochtex::write_stex(path, description); });
    EXPECT_TRUE(starts_with(message, path + ": parameters.band_weights[0][0]: ")) << message;
    EXPECT_FALSE(fs::exists(path));
}

// ---- Reading errors -----------------------------------------------------------------------------

TEST(StexFileErrors, MissingOrUnreadableFile)
{
    const std::string dir = stochtex::test::temp_dir("stex_missing");
    const std::string missing = dir + "/nope.stex";
    std::string message = error_of([&] { stochtex::read_stex(missing); });
    EXPECT_TRUE(starts_with(message, missing + ": cannot open: ")) << message;

    message = error_of([&] { stochtex::read_stex(dir); });
    EXPECT_TRUE(starts_with(message, dir + ": cannot read: ")) << message;
}

TEST(StexFileErrors, FileErrorsStartWithThePath)
{
    const std::string path = stochtex::test::temp_dir("stex_bad_file") + "/bad.stex";
    std::ofstream(path) << replaced("\"version\": 1", "\"version\": 2");
    const std::string message = error_of([&] { stochtex::read_stex(path); });
    EXPECT_EQ(message, path + ": version: unsupported version 2 (this build reads version 1)");
}

TEST(StexFileErrors, MalformedJsonGivesTheParserPosition)
{
    std::string message = parse_error("");
    EXPECT_TRUE(starts_with(message, "t.stex: invalid JSON: ")) << message;
    EXPECT_TRUE(contains(message, "line 1, column 1")) << message;

    message = parse_error("{\n  \"format\": \"stex\",\n  garbage\n}");
    EXPECT_TRUE(starts_with(message, "t.stex: invalid JSON: ")) << message;
    EXPECT_TRUE(contains(message, "line 3, column 3")) << message;

    const std::string text = stochtex::format_stex(sample());
    message = parse_error(text.substr(0, text.size() / 2));
    EXPECT_TRUE(starts_with(message, "t.stex: invalid JSON: ")) << message;
    EXPECT_TRUE(contains(message, "unexpected end of input")) << message;

    EXPECT_EQ(parse_error("[1, 2]"), "t.stex: (top level): expected an object, got an array");
}

TEST(StexFileErrors, FormatAndVersion)
{
    EXPECT_EQ(parse_error(edited([](Json& j) { j["format"] = "png"; })),
              "t.stex: format: expected \"stex\", got \"png\"");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["version"] = 2; })),
              "t.stex: version: unsupported version 2 (this build reads version 1)");
    // The version is checked before the rest: a future file's new fields are not the problem.
    EXPECT_EQ(parse_error(edited([](Json& j) {
                  j["version"] = 3;
                  j["new_field"] = 1;
              })),
              "t.stex: version: unsupported version 3 (this build reads version 1)");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["version"] = 1.0; })),
              "t.stex: version: expected an integer, got 1.0");
}

TEST(StexFileErrors, UnknownAndMissingKeys)
{
    std::string message = parse_error(edited([](Json& j) { j["extra"] = 1; }));
    EXPECT_TRUE(starts_with(message, "t.stex: extra: unknown field (expected one of: format, version, ")) << message;

    EXPECT_EQ(parse_error(edited([](Json& j) { j["colour"]["gamma"] = 2.2; })),
              "t.stex: colour.gamma: unknown field (expected one of: space, mode, mean, basis, chroma_given_brightness (optional))");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["histograms"][2]["knots"] = 4; })),
              "t.stex: histograms[2].knots: unknown field (expected one of: z, value)");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["scale"].erase("unit_size_m"); })),
              "t.stex: scale.unit_size_m: missing required field");
    EXPECT_EQ(parse_error(edited([](Json& j) { j.erase("provenance"); })),
              "t.stex: provenance: missing required field");
}

TEST(StexFileErrors, DuplicateKeys)
{
    EXPECT_EQ(parse_error(replaced("\"seed\": 4000000000,", "\"seed\": 4000000000, \"seed\": 1,")),
              "t.stex: seed: duplicate key");
    // Inside the third histogram: the path follows arrays past an object and a null.
    EXPECT_EQ(parse_error(replaced("\"z\": [-2,", "\"z\": [], \"z\": [-2,")), "t.stex: histograms[2].z: duplicate key");
}

TEST(StexFileErrors, WrongTypes)
{
    EXPECT_EQ(parse_error(edited([](Json& j) { j["parameters"]["band_weights"][1] = "loud"; })),
              "t.stex: parameters.band_weights[1]: expected an array of numbers, got a string");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["parameters"]["band_weights"][1][3] = "0.5"; })),
              "t.stex: parameters.band_weights[1][3]: expected a number, got a string");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["scale"]["pixels_per_unit"] = "512"; })),
              "t.stex: scale.pixels_per_unit: expected a number, got a string");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["seed"] = true; })), "t.stex: seed: expected an integer, got a boolean");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["seed"] = -1; })),
              "t.stex: seed: expected an integer in [0, 4294967295], got -1");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["seed"] = 4294967296; })),
              "t.stex: seed: expected an integer in [0, 4294967295], got 4294967296");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["model"] = 3; })), "t.stex: model: expected a string, got a number");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["histograms"][0] = Json::array(); })),
              "t.stex: histograms[0]: expected an object, got an array");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["provenance"]["options"]["bands"] = 5; })),
              "t.stex: provenance.options.bands: expected a string, got a number");
}

TEST(StexFileErrors, WrongArraySizes)
{
    EXPECT_EQ(parse_error(edited([](Json& j) { j["colour"]["mean"] = {0.1, 0.2}; })),
              "t.stex: colour.mean: expected 3 numbers, got 2");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["colour"]["basis"].erase(2); })),
              "t.stex: colour.basis: expected 3 rows, got 2");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["colour"]["basis"][1].push_back(0); })),
              "t.stex: colour.basis[1]: expected 3 numbers, got 4");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["histograms"].push_back(nullptr); })),
              "t.stex: histograms: expected 3 histograms, got 4");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["provenance"]["source_size"] = {1024}; })),
              "t.stex: provenance.source_size: expected 2 numbers, got 1");
}

TEST(StexFileErrors, NumbersOverflowingToInfinity)
{
    EXPECT_EQ(parse_error(replaced("\"unit_size_m\": 0.35", "\"unit_size_m\": 1e999")),
              "t.stex: scale.unit_size_m: number overflow parsing '1e999'");
    EXPECT_EQ(parse_error(replaced("[1, 0.5, 0.25, 0.1, 0]", "[1, -1e999, 0.25, 0.1, 0]")),
              "t.stex: parameters.band_weights[0][1]: number overflow parsing '-1e999'");
    // Finite as a double but not as a float, which is how numbers are stored.
    EXPECT_EQ(parse_error(replaced("\"unit_size_m\": 0.35", "\"unit_size_m\": 1e300")),
              "t.stex: scale.unit_size_m: expected a finite number within float range, got 1e+300");
}

TEST(StexFileErrors, ModelsAndTheirParameters)
{
    EXPECT_EQ(parse_error(edited([](Json& j) { j["model"] = "perlin"; })),
              "t.stex: model: unknown model 'perlin' (known models: wavelet, gabor, tiling, lrp, ptm)");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["parameters"] = {{"orientation", 1}}; })),
              "t.stex: parameters.orientation: unknown field (expected one of: band_weights)");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["parameters"] = Json::object(); })),
              "t.stex: parameters.band_weights: missing required field");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["colour"]["mode"] = "hsv"; })),
              "t.stex: colour.mode: unknown colour mode 'hsv' (valid: pca, rgb, rgb-shared)");
}

TEST(StexFileErrors, ReaderValidatesValues)
{
    EXPECT_EQ(parse_error(edited([](Json& j) { j["histograms"][2]["value"][2] = 0; })),
              "t.stex: histograms[2].value[2]: values must be non-decreasing (0 after 2e-07)");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["histograms"][0] = {{"z", Json::array()}, {"value", Json::array()}}; })),
              "t.stex: histograms[0]: a disabled histogram is written as null, not as empty arrays");
    EXPECT_EQ(parse_error(edited([](Json& j) { j["colour"]["space"] = "acescg"; })),
              "t.stex: colour.space: unsupported colour space 'acescg' (this build reads lin_rec709)");
}

// ---- validate() ---------------------------------------------------------------------------------

TEST(StexValidate, AcceptsTheSample)
{
    EXPECT_NO_THROW(stochtex::validate(sample(), "t.stex"));
    TextureDescription rgb = sample();
    rgb.colour_mode = stochtex::ColourMode::rgb_shared;
    rgb.basis = TextureDescription().basis;
    EXPECT_NO_THROW(stochtex::validate(rgb, "t.stex"));
}

TEST(StexValidate, Basis)
{
    TextureDescription d = sample();
    d.basis[0][0] += 0.01;
    std::string message = validate_error(d);
    EXPECT_TRUE(starts_with(message, "t.stex: colour.basis: columns are not orthonormal (column 0 · column 0 = "))
        << message;

    d = sample();
    for (auto& row : d.basis) row[2] = -row[2];  // a reflection
    message = validate_error(d);
    EXPECT_TRUE(starts_with(message, "t.stex: colour.basis: determinant is -")) << message;
    EXPECT_TRUE(contains(message, ": must be positive (a rotation)")) << message;

    d = sample();
    d.basis[1][1] = std::nan("");
    EXPECT_EQ(validate_error(d), "t.stex: colour.basis[1][1]: expected a finite number within float range, got nan");

    d = sample();
    d.colour_mode = stochtex::ColourMode::rgb;
    EXPECT_EQ(validate_error(d), "t.stex: colour.basis: must be the identity in colour mode 'rgb'");
}

TEST(StexValidate, Histograms)
{
    TextureDescription d = sample();
    d.histograms[0].z[3] = -1;
    EXPECT_EQ(validate_error(d), "t.stex: histograms[0].z[3]: knots must be strictly increasing (-1 after -0.5)");

    d = sample();
    d.histograms[2].z[2] = d.histograms[2].z[1];
    EXPECT_EQ(validate_error(d), "t.stex: histograms[2].z[2]: knots must be strictly increasing (-1 after -1)");

    d = sample();
    d.histograms[0].value[6] = 0.5;
    EXPECT_EQ(validate_error(d), "t.stex: histograms[0].value[6]: values must be non-decreasing (0.5 after 0.7)");

    d = sample();
    d.histograms[2].value.pop_back();
    EXPECT_EQ(validate_error(d), "t.stex: histograms[2]: z has 4 knots but value has 3");

    d = sample();
    d.histograms[2] = {{-1, 0, 1}, {0, 1, 2}};
    EXPECT_EQ(validate_error(d), "t.stex: histograms[2]: expected at least 4 knots, got 3");
}

TEST(StexValidate, BandWeights)
{
    TextureDescription d = sample();
    d.parameters.get<stochtex::WaveletParameters>().band_weights[1][2] = -0.5;
    EXPECT_EQ(validate_error(d), "t.stex: parameters.band_weights[1][2]: weights must not be negative, got -0.5");

    d = sample();
    d.parameters.get<stochtex::WaveletParameters>().band_weights[2].pop_back();
    EXPECT_EQ(validate_error(d), "t.stex: parameters.band_weights[2]: has 4 bands but channel 0 has 5");

    d = sample();
    d.parameters.get<stochtex::WaveletParameters>().band_weights = {{{}, {}, {}}};
    EXPECT_EQ(validate_error(d), "t.stex: parameters.band_weights[0]: expected 1 to 24 bands, got 0");

    d = sample();
    for (auto& channel : d.parameters.get<stochtex::WaveletParameters>().band_weights) channel.assign(25, 1.0);
    EXPECT_EQ(validate_error(d), "t.stex: parameters.band_weights[0]: expected 1 to 24 bands, got 25");

    d = sample();
    d.parameters.get<stochtex::WaveletParameters>().band_weights[0][4] = std::numeric_limits<double>::infinity();
    EXPECT_EQ(validate_error(d),
              "t.stex: parameters.band_weights[0][4]: expected a finite number within float range, got inf");

    d = sample();
    d.parameters.reset();
    EXPECT_EQ(validate_error(d), "t.stex: parameters: missing for model 'wavelet'");
}

TEST(StexValidate, ScaleMeanModelVersionAndProvenance)
{
    TextureDescription d = sample();
    d.pixels_per_unit = 0;
    EXPECT_EQ(validate_error(d), "t.stex: scale.pixels_per_unit: must be positive, got 0");

    d = sample();
    d.unit_size_m = -1;
    EXPECT_EQ(validate_error(d), "t.stex: scale.unit_size_m: must be positive, got -1");

    d = sample();
    d.mean[1] = std::nan("");
    EXPECT_EQ(validate_error(d), "t.stex: colour.mean[1]: expected a finite number within float range, got nan");

    d = sample();
    d.model = "fractal";
    EXPECT_EQ(validate_error(d), "t.stex: model: unknown model 'fractal' (known models: wavelet, gabor, tiling, lrp, ptm)");

    d = sample();
    d.version = 0;
    EXPECT_EQ(validate_error(d), "t.stex: version: unsupported version 0 (this build reads version 1)");

    d = sample();
    d.provenance.options.emplace_back("bands", "6");
    EXPECT_EQ(validate_error(d), "t.stex: provenance.options.bands: duplicate option");

    d = sample();
    d.provenance.source_width = -1;
    EXPECT_EQ(validate_error(d), "t.stex: provenance.source_size: sizes must not be negative, got -1 x 768");
}

// ---- texture_description.h ----------------------------------------------------------------------

TEST(TextureDescription, ColourModeNames)
{
    for (auto mode : {stochtex::ColourMode::pca, stochtex::ColourMode::rgb, stochtex::ColourMode::rgb_shared})
        EXPECT_EQ(stochtex::colour_mode_from_string(stochtex::to_string(mode)), mode);
    EXPECT_STREQ(stochtex::to_string(stochtex::ColourMode::rgb_shared), "rgb-shared");
    EXPECT_EQ(error_of([] { stochtex::colour_mode_from_string("RGB"); }),
              "unknown colour mode 'RGB' (valid: pca, rgb, rgb-shared)");
}

TEST(TextureDescription, KnownModels)
{
    EXPECT_EQ(stochtex::known_models(), (std::vector<std::string>{"wavelet", "gabor", "tiling", "lrp", "ptm"}));
}

// ---- The optional "image" block (the OIIO plugin's virtual image) --------------------------------

TEST(StexImageLayout, OptionalBlockRoundTripsAndPartialBlocksTakeDefaults)
{
    TextureDescription d = sample();
    EXPECT_FALSE(stochtex::parse_stex(stochtex::format_stex(d), "t.stex").image.has_value());
    d.image = stochtex::ImageLayout{4096, 2048, 32, 128, 0.5, "Y"};
    const std::string text = stochtex::format_stex(d);
    const TextureDescription back = stochtex::parse_stex(text, "t.stex");
    ASSERT_TRUE(back.image.has_value());
    EXPECT_EQ(back.image->width, 4096);
    EXPECT_EQ(back.image->height, 2048);
    EXPECT_EQ(back.image->tile_width, 32);
    EXPECT_EQ(back.image->tile_height, 128);
    EXPECT_EQ(back.image->scale, 0.5);
    EXPECT_EQ(back.image->channels, "Y");
    EXPECT_EQ(stochtex::format_stex(back), text);

    const TextureDescription partial =
        stochtex::parse_stex(edited([](Json& j) { j["image"] = {{"width", 1000}}; }), "t.stex");
    ASSERT_TRUE(partial.image.has_value());
    EXPECT_EQ(partial.image->width, 1000);
    EXPECT_EQ(partial.image->height, stochtex::ImageLayout{}.height);
    EXPECT_EQ(partial.image->channels, "RGB");
}

TEST(StexImageLayout, BadValuesNameTheField)
{
    auto with_image = [](Json image) { return parse_error(edited([&](Json& j) { j["image"] = image; })); };
    EXPECT_EQ(with_image({{"width", 0}}), "t.stex: image.width: must be in [1, 1048576], got 0");
    EXPECT_EQ(with_image({{"tile_width", 100}}), "t.stex: image.tile_width: must be a power of two in [8, 4096], got 100");
    EXPECT_EQ(with_image({{"channels", "XYZ"}}), "t.stex: image.channels: expected \"RGB\", \"RGBA\" or \"Y\", got \"XYZ\"");
    EXPECT_EQ(with_image({{"scale", -1}}), "t.stex: image.scale: must be positive, got -1");
    EXPECT_EQ(with_image({{"height", 2.5}}).rfind("t.stex: image.height: ", 0), 0u);
    EXPECT_TRUE(starts_with(with_image({{"tiles", 64}}), "t.stex: image.tiles: unknown field (expected one of: width"));
    EXPECT_EQ(with_image(Json::array()).rfind("t.stex: image: expected an object", 0), 0u) << with_image(Json::array());
}
