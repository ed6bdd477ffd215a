#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/stex_file.h>

#include "models/model.h"
#include "schema/json_fields.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>

namespace stochtex {

namespace {

using json_fields::Field;
using json_fields::Json;

constexpr double orthonormal_tolerance = 1e-4;
constexpr std::size_t min_histogram_knots = 4;
constexpr std::size_t max_chroma_knots = 64;

// ---- Checks shared by the reader and validate() ------------------------------------------------

void check_version(int version, const std::string& source)
{
    if (version != TextureDescription::current_version)
        json_fields::fail(source, "version",
                          "unsupported version " + std::to_string(version) + " (this build reads version " +
                              std::to_string(TextureDescription::current_version) + ")");
}

void check_positive(double value, const std::string& path, const std::string& source)
{
    check_float_finite(value, path, source);
    if (!(value > 0)) json_fields::fail(source, path, "must be positive, got " + number_text(value));
}

void validate_basis(const TextureDescription& description, const std::string& source)
{
    const auto& basis = description.basis;
    for (std::size_t row = 0; row < 3; ++row)
        for (std::size_t col = 0; col < 3; ++col)
            check_float_finite(basis[row][col], json_path(json_path("colour.basis", row), col), source);

    if (description.colour_mode != ColourMode::pca) {
        // The RGB modes synthesise R, G and B directly: there is no rotation to store.
        for (std::size_t row = 0; row < 3; ++row)
            for (std::size_t col = 0; col < 3; ++col)
                if (basis[row][col] != (row == col ? 1.0 : 0.0))
                    json_fields::fail(source, "colour.basis",
                                      std::string("must be the identity in colour mode '") +
                                          to_string(description.colour_mode) + "'");
        return;
    }
    for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t b = a; b < 3; ++b) {
            double dot = 0;
            for (std::size_t row = 0; row < 3; ++row) dot += basis[row][a] * basis[row][b];
            if (std::fabs(dot - (a == b ? 1.0 : 0.0)) > orthonormal_tolerance)
                json_fields::fail(source, "colour.basis",
                                  "columns are not orthonormal (column " + std::to_string(a) + " · column " +
                                      std::to_string(b) + " = " + number_text(dot) + ", tolerance " +
                                      number_text(orthonormal_tolerance) + ")");
        }
    }
    // A reflection would be as good a basis mathematically; requiring a rotation makes the basis
    // of a given photo unique up to the signs of pairs of columns.
    const double det = basis[0][0] * (basis[1][1] * basis[2][2] - basis[1][2] * basis[2][1]) -
                       basis[0][1] * (basis[1][0] * basis[2][2] - basis[1][2] * basis[2][0]) +
                       basis[0][2] * (basis[1][0] * basis[2][1] - basis[1][1] * basis[2][0]);
    if (!(det > 0))
        json_fields::fail(source, "colour.basis", "determinant is " + number_text(det) + ": must be positive (a rotation)");
}

void validate_histogram(const HistogramMap& histogram, const std::string& path, const std::string& source)
{
    const std::vector<double>& z = histogram.z;
    const std::vector<double>& value = histogram.value;
    if (z.size() != value.size())
        json_fields::fail(source, path,
                          "z has " + std::to_string(z.size()) + " knots but value has " + std::to_string(value.size()));
    if (!histogram.enabled()) return;
    if (z.size() < min_histogram_knots)
        json_fields::fail(source, path,
                          "expected at least " + std::to_string(min_histogram_knots) + " knots, got " +
                              std::to_string(z.size()));
    for (std::size_t i = 0; i < z.size(); ++i) {
        check_float_finite(z[i], json_path(path + ".z", i), source);
        check_float_finite(value[i], json_path(path + ".value", i), source);
        if (i > 0 && !(z[i] > z[i - 1]))
            json_fields::fail(source, json_path(path + ".z", i),
                              "knots must be strictly increasing (" + number_text(z[i]) + " after " + number_text(z[i - 1]) + ")");
        if (i > 0 && !(value[i] >= value[i - 1]))
            json_fields::fail(source, json_path(path + ".value", i),
                              "values must be non-decreasing (" + number_text(value[i]) + " after " + number_text(value[i - 1]) +
                                  ")");
    }
}

void validate_chroma_given_brightness(const TextureDescription& description, const std::string& source)
{
    const ChromaGivenBrightness& curves = description.chroma_given_brightness;
    const std::string path = "colour.chroma_given_brightness";
    if (!curves.enabled()) return;
    if (description.colour_mode != ColourMode::pca)
        json_fields::fail(source, path, "needs colour mode pca (the chroma axes), got " + std::string(to_string(description.colour_mode)));
    if (!model_info(description.model).capabilities.joint_colour)
        json_fields::fail(source, path, "model '" + description.model + "' has no joint colour (its colours are not decorrelated noise channels)");
    const std::vector<double>& z = curves.z;
    if (z.size() < 2 || z.size() > max_chroma_knots)
        json_fields::fail(source, path + ".z",
                          "expected 2 to " + std::to_string(max_chroma_knots) + " knots, got " + std::to_string(z.size()));
    for (std::size_t i = 0; i < z.size(); ++i) check_float_finite(z[i], json_path(path + ".z", i), source);
    // Uniform knots: evaluation (here and in shaders) finds the segment by one multiplication.
    const double step = (z.back() - z.front()) / double(z.size() - 1);
    if (!(step > 0))
        json_fields::fail(source, path + ".z", "knots must be increasing");
    for (std::size_t i = 1; i < z.size(); ++i)
        if (!(std::abs(z[i] - z[i - 1] - step) <= 1e-9 * (1 + std::abs(step))))
            json_fields::fail(source, json_path(path + ".z", i), "knots must be uniformly spaced (step " + number_text(step) + ")");
    for (std::size_t c = 0; c < 2; ++c) {
        const std::string location = json_path(path + ".location", c), scale = json_path(path + ".scale", c);
        if (curves.location[c].size() != z.size())
            json_fields::fail(source, location, "has " + std::to_string(curves.location[c].size()) + " values for " +
                                                    std::to_string(z.size()) + " knots");
        if (curves.scale[c].size() != z.size())
            json_fields::fail(source, scale, "has " + std::to_string(curves.scale[c].size()) + " values for " +
                                                 std::to_string(z.size()) + " knots");
        for (std::size_t i = 0; i < z.size(); ++i) {
            check_float_finite(curves.location[c][i], json_path(location, i), source);
            check_float_finite(curves.scale[c][i], json_path(scale, i), source);
            if (!(curves.scale[c][i] > 0))
                json_fields::fail(source, json_path(scale, i), "must be positive, got " + number_text(curves.scale[c][i]));
        }
    }
}

/// Also used for the plugin's open-time hints, hence public through validate_image_layout().
void check_image_layout(const ImageLayout& image, const std::string& source)
{
    // 2^20 pixels a side keeps every MIP level's pixel count within 64-bit and OIIO's int
    // coordinates; tiles must be at least 8 and powers of two (what texture caches expect).
    constexpr int max_side = 1 << 20;
    auto check_side = [&](int side, const char* path) {
        if (side < 1 || side > max_side)
            json_fields::fail(source, path, "must be in [1, " + std::to_string(max_side) + "], got " + std::to_string(side));
    };
    check_side(image.width, "image.width");
    check_side(image.height, "image.height");
    // A host that reads the image whole (oiiotool -o, maketx, an ImageBuf) holds
    // width × height × channels × 4 bytes of level 0, 4/3 of that with every level: 2^30 pixels
    // (32768², the largest `stex bake` writes) is 12 GiB in RGB, 16 GiB in RGBA. Sides alone
    // allowed 2^40 pixels (12 TiB), which oiiotool tried to fill until it was killed.
    constexpr std::int64_t max_pixels = std::int64_t(1) << 30;
    if (std::int64_t(image.width) * image.height > max_pixels)
        json_fields::fail(source, "image",
                          std::to_string(image.width) + " x " + std::to_string(image.height) +
                              " pixels is too large (width × height at most " + std::to_string(max_pixels) +
                              " = 2^30)");
    // Memory of a tile read: the host allocates a whole tile, tile_width × tile_height × channels
    // × 4 bytes (256 MiB for 4096² RGBA), for every tile it reads, and the plugin as much again
    // for a tile that hangs over the level's edge (and 12 bytes a texel more for Y and RGBA).
    // Every MIP level, however small, costs a whole tile: 4096² tiles on a 64² image held
    // 7 levels × 192 MiB for 64² × 12 bytes of texels. A tile side is therefore at most the
    // image side's next power of two (one tile then covers less than twice the image along that
    // axis), or the default 64 where that is larger, so that every image keeps the default tile.
    auto check_tile = [&](int side, int image_side, const char* path, const char* image_path) {
        if (side < 8 || side > 4096 || (side & (side - 1)))
            json_fields::fail(source, path, "must be a power of two in [8, 4096], got " + std::to_string(side));
        int largest = 64;
        while (largest < image_side) largest *= 2;
        if (side > largest)
            json_fields::fail(source, path,
                              "must be at most " + std::to_string(largest) + " for " + image_path + " " +
                                  std::to_string(image_side) + " (its next power of two, or 64), got " +
                                  std::to_string(side));
    };
    check_tile(image.tile_width, image.width, "image.tile_width", "image.width");
    check_tile(image.tile_height, image.height, "image.tile_height", "image.height");
    check_positive(image.scale, "image.scale", source);
    const std::string channels_problem = image_channels_problem(image.channels);
    if (!channels_problem.empty()) json_fields::fail(source, "image.channels", channels_problem);
}

// ---- Reading ------------------------------------------------------------------------------------

ImageLayout read_image_layout(const Field& image)
{
    image.expect_keys({}, {"width", "height", "tile_width", "tile_height", "scale", "channels"});
    ImageLayout layout;
    constexpr std::int64_t int_max = std::numeric_limits<int>::max();
    if (image.contains("width")) layout.width = int(image["width"].integer(0, int_max));
    if (image.contains("height")) layout.height = int(image["height"].integer(0, int_max));
    if (image.contains("tile_width")) layout.tile_width = int(image["tile_width"].integer(0, int_max));
    if (image.contains("tile_height")) layout.tile_height = int(image["tile_height"].integer(0, int_max));
    if (image.contains("scale")) layout.scale = image["scale"].number();
    if (image.contains("channels")) layout.channels = image["channels"].string();
    return layout;
}

void read_colour(const Field& colour, TextureDescription& description)
{
    colour.expect_keys({"space", "mode", "mean", "basis"}, {"chroma_given_brightness"});
    description.colour_space = colour["space"].string();
    const Field mode = colour["mode"];
    try {
        description.colour_mode = colour_mode_from_string(mode.string());
    } catch (const Error& e) {
        mode.fail(e.what());
    }
    description.mean = colour["mean"].numbers<3>();
    std::vector<Field> rows = colour["basis"].elements(3, "rows");
    for (std::size_t row = 0; row < 3; ++row) description.basis[row] = rows[row].numbers<3>();
    if (!colour.contains("chroma_given_brightness")) return;
    const Field joint = colour["chroma_given_brightness"];
    joint.expect_keys({"z", "location", "scale"});
    ChromaGivenBrightness& curves = description.chroma_given_brightness;
    curves.z = joint["z"].numbers();
    const std::vector<Field> location = joint["location"].elements(2, "chroma channels");
    const std::vector<Field> scale = joint["scale"].elements(2, "chroma channels");
    for (std::size_t c = 0; c < 2; ++c) curves.location[c] = location[c].numbers(), curves.scale[c] = scale[c].numbers();
    if (!curves.enabled()) joint.fail("independent channels are written without chroma_given_brightness, not with empty knots");
}

void read_histograms(const Field& histograms, TextureDescription& description)
{
    std::vector<Field> channels = histograms.elements(3, "histograms");
    for (std::size_t channel = 0; channel < 3; ++channel) {
        const Field& histogram = channels[channel];
        if (histogram.is_null()) continue;  // disabled: the channel stays Gaussian
        histogram.expect_keys({"z", "value"});
        HistogramMap& map = description.histograms[channel];
        map.z = histogram["z"].numbers();
        map.value = histogram["value"].numbers();
        // One spelling per description keeps files canonical.
        if (!map.enabled()) histogram.fail("a disabled histogram is written as null, not as empty arrays");
    }
}

void read_provenance(const Field& provenance, Provenance& result)
{
    provenance.expect_keys({"source", "source_size", "input_colour_space", "tool", "options"}, {"model_choice"});
    result.source = provenance["source"].string();
    std::vector<Field> size = provenance["source_size"].elements(2, "numbers");
    result.source_width = static_cast<int>(size[0].integer(0, std::numeric_limits<int>::max()));
    result.source_height = static_cast<int>(size[1].integer(0, std::numeric_limits<int>::max()));
    result.input_colour_space = provenance["input_colour_space"].string();
    result.tool = provenance["tool"].string();
    for (const auto& [name, value] : provenance["options"].members()) result.options.emplace_back(name, value.string());
    if (!provenance.contains("model_choice")) return;
    for (const Field& entry : provenance["model_choice"].elements(-1, "candidates")) {
        entry.expect_keys({"model", "colour", "penalty", "radial_log_psd_db", "polar_log_psd_db", "w1_sigma", "false_colour_rate",
                           "gradient_orientation_degrees", "gradient_magnitude_w1", "bytes"},
                          {"joint_colour", "variant", "structure_distance"});
        // A metric the images were too small for is written as null.
        const auto metric = [&](const char* key) {
            const Field field = entry[key];
            return field.is_null() ? std::numeric_limits<double>::quiet_NaN() : field.number();
        };
        ModelScore& score = result.model_choice.emplace_back();
        score.model = entry["model"].string();
        score.colour = entry["colour"].string();
        score.joint_colour = entry.contains("joint_colour") && entry["joint_colour"].boolean();
        if (entry.contains("variant")) score.variant = entry["variant"].string();
        score.penalty = entry["penalty"].number();
        score.radial_log_psd_db = metric("radial_log_psd_db");
        score.polar_log_psd_db = metric("polar_log_psd_db");
        score.w1_sigma = metric("w1_sigma");
        score.false_colour_rate = metric("false_colour_rate");
        score.gradient_orientation_degrees = metric("gradient_orientation_degrees");
        score.gradient_magnitude_w1 = metric("gradient_magnitude_w1");
        if (entry.contains("structure_distance")) score.structure_distance = metric("structure_distance");
        score.bytes = entry["bytes"].integer(0, std::numeric_limits<long long>::max());
    }
}

// ---- Writing ------------------------------------------------------------------------------------

Json to_json(const TextureDescription& description)
{
    Json root = Json::object();  // ordered: keys appear in the order they are set
    root["format"] = "stex";
    root["version"] = description.version;
    root["model"] = description.model;
    root["seed"] = description.seed;

    root["scale"]["pixels_per_unit"] = description.pixels_per_unit;
    root["scale"]["unit_size_m"] = description.unit_size_m;

    Json& colour = root["colour"];
    colour["space"] = description.colour_space;
    colour["mode"] = to_string(description.colour_mode);
    colour["mean"] = description.mean;
    colour["basis"] = description.basis;
    if (const ChromaGivenBrightness& curves = description.chroma_given_brightness; curves.enabled()) {
        Json& joint = colour["chroma_given_brightness"];
        joint["z"] = curves.z;
        joint["location"] = {curves.location[0], curves.location[1]};
        joint["scale"] = {curves.scale[0], curves.scale[1]};
    }

    Json& histograms = root["histograms"] = Json::array();
    for (const HistogramMap& map : description.histograms) {
        Json histogram;  // null when disabled
        if (map.enabled()) {
            histogram["z"] = map.z;
            histogram["value"] = map.value;
        }
        histograms.push_back(histogram);
    }

    root["parameters"] = model_of(description).write_parameters(description);

    const Provenance& provenance = description.provenance;
    Json& source = root["provenance"];
    source["source"] = provenance.source;
    source["source_size"] = {provenance.source_width, provenance.source_height};
    source["input_colour_space"] = provenance.input_colour_space;
    source["tool"] = provenance.tool;
    source["options"] = Json::object();
    for (const auto& [name, value] : provenance.options) source["options"][name] = value;
    if (!provenance.model_choice.empty()) {
        Json& candidates = source["model_choice"] = Json::array();
        const auto metric = [](double value) { return std::isnan(value) ? Json() : Json(value); };
        for (const ModelScore& score : provenance.model_choice) {
            Json entry = Json::object();
            entry["model"] = score.model;
            entry["colour"] = score.colour;
            if (score.joint_colour) entry["joint_colour"] = true;  // absent: independent channels
            if (!score.variant.empty()) entry["variant"] = score.variant;  // absent: the model's own fit
            entry["penalty"] = score.penalty;
            entry["radial_log_psd_db"] = metric(score.radial_log_psd_db);
            entry["polar_log_psd_db"] = metric(score.polar_log_psd_db);
            entry["w1_sigma"] = metric(score.w1_sigma);
            entry["false_colour_rate"] = metric(score.false_colour_rate);
            entry["gradient_orientation_degrees"] = metric(score.gradient_orientation_degrees);
            entry["gradient_magnitude_w1"] = metric(score.gradient_magnitude_w1);
            // Absent where the choice did not score it (the default, and every earlier file).
            if (!std::isnan(score.structure_distance)) entry["structure_distance"] = score.structure_distance;
            entry["bytes"] = score.bytes;
            candidates.push_back(std::move(entry));
        }
    }

    if (description.image) {
        // Written in full: a file states the layout it was given, whatever the defaults become.
        Json& image = root["image"];
        image["width"] = description.image->width;
        image["height"] = description.image->height;
        image["tile_width"] = description.image->tile_width;
        image["tile_height"] = description.image->tile_height;
        image["scale"] = description.image->scale;
        image["channels"] = description.image->channels;
    }
    return root;
}

}  // namespace

void validate(const TextureDescription& description, const std::string& source)
{
    check_version(description.version, source);
    const Model& model = model_named(description.model, source);
    // Exactly the parameters of the named model are set; the first model (in registry order)
    // that disagrees names the problem.
    for (const Model* each : registered_models()) {
        const bool holds = each->holds(description.parameters), named = each == &model;
        if (holds != named)
            json_fields::fail(source, "parameters",
                              holds ? each->name() + " parameters given for model '" + description.model + "'"
                                    : "missing for model '" + each->name() + "'");
    }
    model.validate(description, source);

    check_positive(description.pixels_per_unit, "scale.pixels_per_unit", source);
    check_positive(description.unit_size_m, "scale.unit_size_m", source);

    if (description.colour_space != "lin_rec709")
        json_fields::fail(source, "colour.space",
                          "unsupported colour space '" + description.colour_space + "' (this build reads lin_rec709)");
    for (std::size_t c = 0; c < 3; ++c) check_float_finite(description.mean[c], json_path("colour.mean", c), source);
    validate_basis(description, source);
    for (std::size_t c = 0; c < 3; ++c)
        validate_histogram(description.histograms[c], json_path("histograms", c), source);
    validate_chroma_given_brightness(description, source);

    const Provenance& provenance = description.provenance;
    if (provenance.source_width < 0 || provenance.source_height < 0)
        json_fields::fail(source, "provenance.source_size",
                          "sizes must not be negative, got " + std::to_string(provenance.source_width) + " x " +
                              std::to_string(provenance.source_height));
    // Options become the keys of a JSON object: a repeated name could not be read back.
    std::set<std::string> option_names;
    for (const auto& option : provenance.options)
        if (!option_names.insert(option.first).second)
            json_fields::fail(source, "provenance.options." + option.first, "duplicate option");
    for (std::size_t i = 0; i < provenance.model_choice.size(); ++i) {
        const ModelScore& score = provenance.model_choice[i];
        const std::string path = json_path("provenance.model_choice", i);
        if (!find_model(score.model)) json_fields::fail(source, path + ".model", "unknown model '" + score.model + "'");
        try {
            colour_mode_from_string(score.colour);
        } catch (const Error& e) {
            json_fields::fail(source, path + ".colour", e.what());
        }
        if (!(score.penalty >= 0) || !std::isfinite(score.penalty))
            json_fields::fail(source, path + ".penalty", "must be a finite number ≥ 0, got " + number_text(score.penalty));
        if (score.bytes < 0) json_fields::fail(source, path + ".bytes", "must not be negative");
    }
    if (description.image) check_image_layout(*description.image, source);
}

void validate_image_layout(const ImageLayout& image, const std::string& source) { check_image_layout(image, source); }

std::string image_channels_problem(const std::string& channels)
{
    if (channels == "RGB" || channels == "RGBA" || channels == "Y") return {};
    return "expected \"RGB\", \"RGBA\" or \"Y\", got \"" + channels + "\"";
}

TextureDescription parse_stex(const std::string& text, const std::string& source_name)
{
    const Json json = json_fields::parse(text, source_name);
    const Field root(json, source_name);

    // Format and version first: in a file of another kind or version any other field may differ.
    const Field format = root["format"];
    if (format.string() != "stex") format.fail("expected \"stex\", got \"" + format.string() + "\"");
    TextureDescription description;
    description.version = static_cast<int>(
        root["version"].integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
    check_version(description.version, source_name);

    root.expect_keys({"format", "version", "model", "seed", "scale", "colour", "histograms", "parameters", "provenance"},
                     {"image"});
    description.model = root["model"].string();
    const Model& model = model_named(description.model, source_name);
    description.seed = static_cast<std::uint32_t>(root["seed"].integer(0, std::numeric_limits<std::uint32_t>::max()));

    const Field scale = root["scale"];
    scale.expect_keys({"pixels_per_unit", "unit_size_m"});
    description.pixels_per_unit = scale["pixels_per_unit"].number();
    description.unit_size_m = scale["unit_size_m"].number();

    read_colour(root["colour"], description);
    read_histograms(root["histograms"], description);
    // The model reads its own block (files it keeps beside the .stex are found from source_name).
    description.parameters = model.read_parameters(root["parameters"], source_name);
    read_provenance(root["provenance"], description.provenance);
    if (root.contains("image")) description.image = read_image_layout(root["image"]);

    validate(description, source_name);
    return description;
}

TextureDescription read_stex(const std::string& path)
{
    // An ifstream opens a directory without complaint and then reads nothing.
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored)) throw Error(path + ": cannot read: is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw Error(path + ": cannot read: " + std::strerror(errno));
    return parse_stex(text, path);
}

std::string format_stex(const TextureDescription& description)
{
    validate(description, "texture description");
    return json_fields::format(to_json(description));
}

void write_stex(const std::string& path, const TextureDescription& description)
{
    validate(description, path);
    // Files the model keeps beside the .stex go first, named after it.
    const std::string text = json_fields::format(to_json(model_of(description, path).write_beside(path, description)));
    // Beside the target, then renamed (atomic_write.h): readers never see a half-written file,
    // and a failed write leaves an existing file intact.
    write_file_atomically(path, text);
}

}  // namespace stochtex
