#include "stex/stex_blocks.h"

#include <stochtex/error.h>
#include <stochtex/model.h>

#include "models/model.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

namespace stochtex {

namespace {

using json_fields::Field;
using json_fields::Json;

constexpr double orthonormal_tolerance = 1e-4;
constexpr std::size_t min_histogram_knots = 4;
constexpr std::size_t max_chroma_knots = 64;
constexpr std::int64_t int_max = std::numeric_limits<int>::max();

void check_positive(double value, const std::string& path, const std::string& source)
{
    check_float_finite(value, path, source);
    if (!(value > 0)) json_fields::fail(source, path, "must be positive, got " + number_text(value));
}

// ---- scale ----------------------------------------------------------------------------------------

ParameterSchema<TextureDescription> make_scale_block()
{
    ParameterSchema<TextureDescription> s;
    auto positive = [&s](const char* key, double TextureDescription::*member, const char* unit, const char* doc) {
        s.custom({key, "number", "> 0", "", unit, doc, {}, false},
                 [member](const Field& f, TextureDescription& d, const ReadContext&) { d.*member = f.number(); },
                 [member](const TextureDescription& d) { return Json(d.*member); },
                 [member](const TextureDescription& d, const std::string& path, const std::string& source) {
                     check_positive(d.*member, path, source);
                 });
    };
    positive("pixels_per_unit", &TextureDescription::pixels_per_unit, "exemplar pixels per texture unit",
             "A render with units_per_pixel = 1 / pixels_per_unit shows the texture at the photo's own pixel scale.");
    positive("unit_size_m", &TextureDescription::unit_size_m, "metres",
             "Physical size of one texture unit, for scenes; informational for the core.");
    return s;
}

// ---- colour -------------------------------------------------------------------------------------

void validate_basis(const TextureDescription& description, const std::string& path, const std::string& source)
{
    const auto& basis = description.basis;
    for (std::size_t row = 0; row < 3; ++row)
        for (std::size_t col = 0; col < 3; ++col) check_float_finite(basis[row][col], json_path(json_path(path, row), col), source);

    if (description.colour_mode != ColourMode::pca) {
        // The RGB modes synthesise R, G and B directly: there is no rotation to store.
        for (std::size_t row = 0; row < 3; ++row)
            for (std::size_t col = 0; col < 3; ++col)
                if (basis[row][col] != (row == col ? 1.0 : 0.0))
                    json_fields::fail(source, path,
                                      std::string("must be the identity in colour mode '") + to_string(description.colour_mode) + "'");
        return;
    }
    for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t b = a; b < 3; ++b) {
            double dot = 0;
            for (std::size_t row = 0; row < 3; ++row) dot += basis[row][a] * basis[row][b];
            if (std::fabs(dot - (a == b ? 1.0 : 0.0)) > orthonormal_tolerance)
                json_fields::fail(source, path,
                                  "columns are not orthonormal (column " + std::to_string(a) + " · column " + std::to_string(b) +
                                      " = " + number_text(dot) + ", tolerance " + number_text(orthonormal_tolerance) + ")");
        }
    }
    // A reflection would be as good a basis mathematically; requiring a rotation makes the basis
    // of a given photo unique up to the signs of pairs of columns.
    const double det = basis[0][0] * (basis[1][1] * basis[2][2] - basis[1][2] * basis[2][1]) -
                       basis[0][1] * (basis[1][0] * basis[2][2] - basis[1][2] * basis[2][0]) +
                       basis[0][2] * (basis[1][0] * basis[2][1] - basis[1][1] * basis[2][0]);
    if (!(det > 0)) json_fields::fail(source, path, "determinant is " + number_text(det) + ": must be positive (a rotation)");
}

void validate_chroma_given_brightness(const TextureDescription& description, const std::string& path, const std::string& source)
{
    const ChromaGivenBrightness& curves = description.chroma_given_brightness;
    if (description.colour_mode != ColourMode::pca)
        json_fields::fail(source, path, "needs colour mode pca (the chroma axes), got " + std::string(to_string(description.colour_mode)));
    if (!model_info(description.model).capabilities.joint_colour)
        json_fields::fail(source, path,
                          "model '" + description.model + "' has no joint colour (its colours are not decorrelated noise channels)");
    const std::vector<double>& z = curves.z;
    if (z.size() < 2 || z.size() > max_chroma_knots)
        json_fields::fail(source, path + ".z",
                          "expected 2 to " + std::to_string(max_chroma_knots) + " knots, got " + std::to_string(z.size()));
    for (std::size_t i = 0; i < z.size(); ++i) check_float_finite(z[i], json_path(path + ".z", i), source);
    // Uniform knots: evaluation (here and in shaders) finds the segment by one multiplication.
    const double step = (z.back() - z.front()) / double(z.size() - 1);
    if (!(step > 0)) json_fields::fail(source, path + ".z", "knots must be increasing");
    for (std::size_t i = 1; i < z.size(); ++i)
        if (!(std::abs(z[i] - z[i - 1] - step) <= 1e-9 * (1 + std::abs(step))))
            json_fields::fail(source, json_path(path + ".z", i), "knots must be uniformly spaced (step " + number_text(step) + ")");
    for (std::size_t c = 0; c < 2; ++c) {
        const std::string location = json_path(path + ".location", c), scale = json_path(path + ".scale", c);
        if (curves.location[c].size() != z.size())
            json_fields::fail(source, location,
                              "has " + std::to_string(curves.location[c].size()) + " values for " + std::to_string(z.size()) + " knots");
        if (curves.scale[c].size() != z.size())
            json_fields::fail(source, scale,
                              "has " + std::to_string(curves.scale[c].size()) + " values for " + std::to_string(z.size()) + " knots");
        for (std::size_t i = 0; i < z.size(); ++i) {
            check_float_finite(curves.location[c][i], json_path(location, i), source);
            check_float_finite(curves.scale[c][i], json_path(scale, i), source);
            if (!(curves.scale[c][i] > 0))
                json_fields::fail(source, json_path(scale, i), "must be positive, got " + number_text(curves.scale[c][i]));
        }
    }
}

/// The two chroma channels' curves, one array per channel.
void chroma_curves(ParameterSchema<ChromaGivenBrightness>& s, const char* key,
                   std::array<std::vector<double>, 2> ChromaGivenBrightness::*member, const char* doc)
{
    s.custom({key, "2 arrays of numbers", "", "", "", doc, {}, false},
             [member](const Field& f, ChromaGivenBrightness& curves, const ReadContext&) {
                 const std::vector<Field> channels = f.elements(2, "chroma channels");
                 for (std::size_t c = 0; c < 2; ++c) (curves.*member)[c] = channels[c].numbers();
             },
             [member](const ChromaGivenBrightness& curves) { return Json{(curves.*member)[0], (curves.*member)[1]}; });
}

/// `colour.chroma_given_brightness`: read and written by this declaration; checked as a field of
/// `colour` (validate_chroma_given_brightness: the checks need the colour mode and the model).
ParameterSchema<ChromaGivenBrightness> make_chroma_given_brightness_block()
{
    ParameterSchema<ChromaGivenBrightness> s;
    s.numbers("z", &ChromaGivenBrightness::z,
              {"", "", "Standard-normal units: 2 to 64 knots, uniformly spaced (to 1e-9), increasing."});
    chroma_curves(s, "location", &ChromaGivenBrightness::location, "Channels 1 and 2: as many entries as z, finite.");
    chroma_curves(s, "scale", &ChromaGivenBrightness::scale, "Channels 1 and 2: as many entries as z, each > 0.");
    return s;
}

const ParameterSchema<ChromaGivenBrightness>& chroma_given_brightness_block()
{
    static const ParameterSchema<ChromaGivenBrightness> block = make_chroma_given_brightness_block();
    return block;
}

void read_chroma_given_brightness(const Field& joint, TextureDescription& description, const ReadContext& context)
{
    description.chroma_given_brightness = chroma_given_brightness_block().read(joint, context);
    if (!description.chroma_given_brightness.enabled())
        joint.fail("independent channels are written without chroma_given_brightness, not with empty knots");
}

Json write_chroma_given_brightness(const TextureDescription& description)
{
    return chroma_given_brightness_block().write(description.chroma_given_brightness);
}

ParameterSchema<TextureDescription> make_colour_block()
{
    ParameterSchema<TextureDescription> s;
    s.text("space", &TextureDescription::colour_space, {"", "", "Always \"lin_rec709\" in this version."},
           [](const TextureDescription& d, const std::string& path, const std::string& source) {
               if (d.colour_space != "lin_rec709")
                   json_fields::fail(source, path, "unsupported colour space '" + d.colour_space + "' (this build reads lin_rec709)");
           });
    s.enumeration("mode", &TextureDescription::colour_mode, &to_string, &colour_mode_from_string,
                  {ColourMode::pca, ColourMode::rgb, ColourMode::rgb_shared},
                  {"", "",
                   "pca (decorrelated channels along the principal axes of the photo's colours), rgb (R, G and B synthesised "
                   "independently) or rgb-shared (R, G and B with the same noise: perfectly correlated)."});
    s.numbers("mean", &TextureDescription::mean, {}, {"", "", "The mean colour, R, G, B."});
    s.custom({"basis", "array of 3 rows of 3 numbers", "", "", "",
              "basis[row][column]: column c is the RGB direction of channel c. In pca mode it is orthonormal (every column "
              "dot product within 1e-4 of 0 or 1) with a positive determinant (a rotation, not a reflection), columns sorted "
              "by decreasing variance. In the rgb modes it is exactly the identity.",
              {}, false},
             [](const Field& f, TextureDescription& d, const ReadContext&) {
                 std::vector<Field> rows = f.elements(3, "rows");
                 for (std::size_t row = 0; row < 3; ++row) d.basis[row] = rows[row].numbers<3>();
             },
             [](const TextureDescription& d) { return Json(d.basis); }, validate_basis);
    ParameterInfo joint{"chroma_given_brightness", "object", "", "", "",
                        "Joint colour (stex analyze --joint-colour on): y[c] = location[c−1](z₀) + scale[c−1](z₀) · r_c for the "
                        "chroma channels c = 1, 2, z₀ channel 0's standard-normal variate. Only in pca mode and for models that "
                        "declare joint colour. Absent: the three channels are independent.",
                        chroma_given_brightness_block().infos(), false};
    s.optional_custom(
        joint, [](const TextureDescription& d) { return d.chroma_given_brightness.enabled(); }, read_chroma_given_brightness,
        write_chroma_given_brightness, validate_chroma_given_brightness);
    return s;
}

// ---- histograms ---------------------------------------------------------------------------------

void validate_histogram(const HistogramMap& histogram, const std::string& path, const std::string& source)
{
    const std::vector<double>& z = histogram.z;
    const std::vector<double>& value = histogram.value;
    if (z.size() != value.size())
        json_fields::fail(source, path, "z has " + std::to_string(z.size()) + " knots but value has " + std::to_string(value.size()));
    if (!histogram.enabled()) return;
    if (z.size() < min_histogram_knots)
        json_fields::fail(source, path,
                          "expected at least " + std::to_string(min_histogram_knots) + " knots, got " + std::to_string(z.size()));
    for (std::size_t i = 0; i < z.size(); ++i) {
        check_float_finite(z[i], json_path(path + ".z", i), source);
        check_float_finite(value[i], json_path(path + ".value", i), source);
        if (i > 0 && !(z[i] > z[i - 1]))
            json_fields::fail(source, json_path(path + ".z", i),
                              "knots must be strictly increasing (" + number_text(z[i]) + " after " + number_text(z[i - 1]) + ")");
        if (i > 0 && !(value[i] >= value[i - 1]))
            json_fields::fail(source, json_path(path + ".value", i),
                              "values must be non-decreasing (" + number_text(value[i]) + " after " + number_text(value[i - 1]) + ")");
    }
}

ParameterSchema<HistogramMap> make_histogram_block()
{
    ParameterSchema<HistogramMap> s;
    s.numbers("z", &HistogramMap::z,
              {"", "", "Knot positions in standard-normal units, symmetric about 0: at least 4, strictly increasing."});
    s.numbers("value", &HistogramMap::value, {"", "", "The channel value at each knot: as many entries as z, non-decreasing."});
    s.check(validate_histogram);
    return s;
}

// ---- provenance ---------------------------------------------------------------------------------

/// A metric of a candidate's render: a number, or null where the images were too small for it.
void metric(ParameterSchema<ModelScore>& s, const char* key, double ModelScore::*member, const char* doc)
{
    s.custom({key, "number or null", "", "", "", doc, {}, false},
             [member](const Field& f, ModelScore& score, const ReadContext&) {
                 score.*member = f.is_null() ? std::numeric_limits<double>::quiet_NaN() : f.number();
             },
             [member](const ModelScore& score) { return std::isnan(score.*member) ? Json() : Json(score.*member); });
}

ParameterSchema<ModelScore> make_model_score_block()
{
    ParameterSchema<ModelScore> s;
    s.text("model", &ModelScore::model, {"", "", "A registered model."},
           [](const ModelScore& score, const std::string& path, const std::string& source) {
               if (!find_model(score.model)) json_fields::fail(source, path, "unknown model '" + score.model + "'");
           });
    s.text("colour", &ModelScore::colour, {"", "", "The colour mode it was fitted with: pca, rgb or rgb-shared."},
           [](const ModelScore& score, const std::string& path, const std::string& source) {
               try {
                   colour_mode_from_string(score.colour);
               } catch (const Error& e) {
                   json_fields::fail(source, path, e.what());
               }
           });
    s.optional_custom({"joint_colour", "boolean", "true | false", "false", "", "true when the candidate was fitted with joint colour; absent otherwise.", {}, false},
                      [](const ModelScore& score) { return score.joint_colour; },
                      [](const Field& f, ModelScore& score, const ReadContext&) { score.joint_colour = f.boolean(); },
                      [](const ModelScore&) { return Json(true); });
    s.text("variant", &ModelScore::variant,
           {"", "", "A variant of the model's fit the choice also tried (--choice-structure), as the provenance options it "
                    "adds, \"name value\" joined by \", \" (\"blend_contrast 8\"); absent: the model's own fit."})
        .optional_when([](const ModelScore& score) { return !score.variant.empty(); });
    s.custom({"penalty", "number", "finite, ≥ 0", "", "",
              "The fidelity penalty: lower is closer to the photo (metrics.md, Fidelity penalty).", {}, false},
             [](const Field& f, ModelScore& score, const ReadContext&) { score.penalty = f.number(); },
             [](const ModelScore& score) { return Json(score.penalty); },
             [](const ModelScore& score, const std::string& path, const std::string& source) {
                 if (!(score.penalty >= 0) || !std::isfinite(score.penalty))
                     json_fields::fail(source, path, "must be a finite number ≥ 0, got " + number_text(score.penalty));
             });
    metric(s, "radial_log_psd_db", &ModelScore::radial_log_psd_db, "Radial log-PSD distance, dB (mean over RGB).");
    metric(s, "polar_log_psd_db", &ModelScore::polar_log_psd_db, "2D (oriented) log-PSD distance of luma, dB.");
    metric(s, "w1_sigma", &ModelScore::w1_sigma, "Histogram W1 distance over σ, the worst RGB channel.");
    metric(s, "false_colour_rate", &ModelScore::false_colour_rate, "Share of pixels with colours the photo does not have (a fraction).");
    metric(s, "gradient_orientation_degrees", &ModelScore::gradient_orientation_degrees, "Gradient orientation W1, degrees.");
    metric(s, "gradient_magnitude_w1", &ModelScore::gradient_magnitude_w1, "Gradient magnitude W1.");
    // Absent where the choice did not score it (the default, and every earlier file).
    metric(s, "structure_distance", &ModelScore::structure_distance, "The structure distance (metrics.md, Structure), where the choice scored it.");
    s.optional_when([](const ModelScore& score) { return !std::isnan(score.structure_distance); });
    s.integer("bytes", &ModelScore::bytes, 0, std::numeric_limits<long long>::max(),
              {"", "bytes", "The size of that candidate's .stex.", "≥ 0"},
              [](const ModelScore& score, const std::string& path, const std::string& source) {
                  if (score.bytes < 0) json_fields::fail(source, path, "must not be negative");
              });
    return s;
}

ParameterSchema<Provenance> make_provenance_block()
{
    ParameterSchema<Provenance> s;
    s.text("source", &Provenance::source, {"", "", "File name of the photo, without directories."});
    s.custom({"source_size", "array of 2 integers", "each ≥ 0", "", "pixels", "Width and height of the photo.", {}, false},
             [](const Field& f, Provenance& p, const ReadContext&) {
                 std::vector<Field> size = f.elements(2, "numbers");
                 p.source_width = static_cast<int>(size[0].integer(0, int_max));
                 p.source_height = static_cast<int>(size[1].integer(0, int_max));
             },
             [](const Provenance& p) { return Json{p.source_width, p.source_height}; },
             [](const Provenance& p, const std::string& path, const std::string& source) {
                 if (p.source_width < 0 || p.source_height < 0)
                     json_fields::fail(source, path,
                                       "sizes must not be negative, got " + std::to_string(p.source_width) + " x " +
                                           std::to_string(p.source_height));
             });
    s.text("input_colour_space", &Provenance::input_colour_space, {"", "", "The colour space the photo was decoded from."});
    s.text("tool", &Provenance::tool, {"", "", "\"stochtex <version>\" of the program that wrote the file."});
    s.custom({"options", "object of strings", "", "", "",
              "The analysis options, name → value as text, in the order they were stored. Names are unique.", {}, false},
             [](const Field& f, Provenance& p, const ReadContext&) {
                 for (const auto& [name, value] : f.members()) p.options.emplace_back(name, value.string());
             },
             [](const Provenance& p) {
                 Json options = Json::object();
                 for (const auto& [name, value] : p.options) options[name] = value;
                 return options;
             },
             [](const Provenance& p, const std::string& path, const std::string& source) {
                 // Options become the keys of a JSON object: a repeated name could not be read back.
                 std::set<std::string> names;
                 for (const auto& option : p.options)
                     if (!names.insert(option.first).second) json_fields::fail(source, path + "." + option.first, "duplicate option");
             });
    s.list("model_choice", &Provenance::model_choice, make_model_score_block(),
           {"", "",
            "Present when the analysis chose the model (--model auto; options.model is then \"auto\"): one entry per "
            "candidate, in the order they were tried, with its fidelity penalty and the metrics of its render against the "
            "photo."})
        .optional_when([](const Provenance& p) { return !p.model_choice.empty(); });
    return s;
}

// ---- image --------------------------------------------------------------------------------------

/// Also the check of layouts a host overrides at open time (validate_image_layout()).
void check_image_layout(const ImageLayout& image, const std::string& path, const std::string& source)
{
    // 2^20 pixels a side keeps every MIP level's pixel count within 64-bit and OIIO's int
    // coordinates; tiles must be at least 8 and powers of two (what texture caches expect).
    constexpr int max_side = 1 << 20;
    const std::string width_path = json_path(path, "width"), height_path = json_path(path, "height");
    auto check_side = [&](int side, const std::string& at) {
        if (side < 1 || side > max_side)
            json_fields::fail(source, at, "must be in [1, " + std::to_string(max_side) + "], got " + std::to_string(side));
    };
    check_side(image.width, width_path);
    check_side(image.height, height_path);
    // A host that reads the image whole (oiiotool -o, maketx, an ImageBuf) holds
    // width × height × channels × 4 bytes of level 0, 4/3 of that with every level: 2^30 pixels
    // (32768², the largest `stex bake` writes) is 12 GiB in RGB, 16 GiB in RGBA. Sides alone
    // allowed 2^40 pixels (12 TiB), which oiiotool tried to fill until it was killed.
    constexpr std::int64_t max_pixels = std::int64_t(1) << 30;
    if (std::int64_t(image.width) * image.height > max_pixels)
        json_fields::fail(source, path,
                          std::to_string(image.width) + " x " + std::to_string(image.height) +
                              " pixels is too large (width × height at most " + std::to_string(max_pixels) + " = 2^30)");
    // Memory of a tile read: the host allocates a whole tile, tile_width × tile_height × channels
    // × 4 bytes (256 MiB for 4096² RGBA), for every tile it reads, and the plugin as much again
    // for a tile that hangs over the level's edge (and 12 bytes a texel more for Y and RGBA).
    // Every MIP level, however small, costs a whole tile: 4096² tiles on a 64² image held
    // 7 levels × 192 MiB for 64² × 12 bytes of texels. A tile side is therefore at most the
    // image side's next power of two (one tile then covers less than twice the image along that
    // axis), or the default 64 where that is larger, so that every image keeps the default tile.
    auto check_tile = [&](int side, int image_side, const std::string& at, const std::string& image_at) {
        if (side < 8 || side > 4096 || (side & (side - 1)))
            json_fields::fail(source, at, "must be a power of two in [8, 4096], got " + std::to_string(side));
        int largest = 64;
        while (largest < image_side) largest *= 2;
        if (side > largest)
            json_fields::fail(source, at,
                              "must be at most " + std::to_string(largest) + " for " + image_at + " " + std::to_string(image_side) +
                                  " (its next power of two, or 64), got " + std::to_string(side));
    };
    check_tile(image.tile_width, image.width, json_path(path, "tile_width"), width_path);
    check_tile(image.tile_height, image.height, json_path(path, "tile_height"), height_path);
    check_positive(image.scale, json_path(path, "scale"), source);
    const std::string channels_problem = image_layout_field_problem(image, "channels");
    if (!channels_problem.empty()) json_fields::fail(source, json_path(path, "channels"), channels_problem);
}

ParameterSchema<ImageLayout> make_image_block()
{
    // Every key may be absent (it keeps its default) and every key is written: a file states the
    // layout it was given, whatever the defaults become. The checks relate the fields (tiles
    // against sides, the pixel count), so they are one check of the whole block.
    const auto always = [](const ImageLayout&) { return true; };
    ParameterSchema<ImageLayout> s;
    auto side = [&](const char* key, int ImageLayout::*member, FieldDoc doc) {
        s.optional_custom({key, "integer", doc.range, doc.default_value, doc.unit, doc.doc, {}, false}, always,
                          [member](const Field& f, ImageLayout& layout, const ReadContext&) {
                              layout.*member = int(f.integer(0, int_max));
                          },
                          [member](const ImageLayout& layout) { return Json(layout.*member); });
    };
    const ImageLayout defaults;
    const char* size_doc = "Level-0 size, with width × height ≤ 2^30 (limits.md).";
    const char* tile_doc = "Tile size: a power of two, at most the side's next power of two or 64, whichever is larger.";
    side("width", &ImageLayout::width, {std::to_string(defaults.width), "pixels", size_doc, "[1, 1048576]"});
    side("height", &ImageLayout::height, {std::to_string(defaults.height), "pixels", size_doc, "[1, 1048576]"});
    side("tile_width", &ImageLayout::tile_width, {std::to_string(defaults.tile_width), "pixels", tile_doc, "[8, 4096]"});
    side("tile_height", &ImageLayout::tile_height, {std::to_string(defaults.tile_height), "pixels", tile_doc, "[8, 4096]"});
    s.optional_custom({"scale", "number", "> 0", number_text(defaults.scale), "exemplar pixels per pixel",
                       "Exemplar (photo) pixels per level-0 pixel.", {}, false},
                      always, [](const Field& f, ImageLayout& layout, const ReadContext&) { layout.scale = f.number(); },
                      [](const ImageLayout& layout) { return Json(layout.scale); });
    s.optional_custom({"channels", "string", "RGB | RGBA | Y", defaults.channels, "",
                       "RGB, RGBA (alpha 1) or Y (Rec.709 luminance).", {}, false},
                      always, [](const Field& f, ImageLayout& layout, const ReadContext&) { layout.channels = f.string(); },
                      [](const ImageLayout& layout) { return Json(layout.channels); });
    s.check(check_image_layout);
    return s;
}

}  // namespace

const ParameterSchema<TextureDescription>& scale_block()
{
    static const ParameterSchema<TextureDescription> block = make_scale_block();
    return block;
}

const ParameterSchema<TextureDescription>& colour_block()
{
    static const ParameterSchema<TextureDescription> block = make_colour_block();
    return block;
}

const ParameterSchema<HistogramMap>& histogram_block()
{
    static const ParameterSchema<HistogramMap> block = make_histogram_block();
    return block;
}

const ParameterSchema<Provenance>& provenance_block()
{
    static const ParameterSchema<Provenance> block = make_provenance_block();
    return block;
}

const ParameterSchema<ImageLayout>& image_block()
{
    static const ParameterSchema<ImageLayout> block = make_image_block();
    return block;
}

std::vector<StexBlockInfo> shared_stex_blocks()
{
    return {{"scale", scale_block().infos()},
            {"colour", colour_block().infos()},
            {"histograms[c]", histogram_block().infos()},
            {"provenance", provenance_block().infos()},
            {"image", image_block().infos()}};
}

const std::vector<ParameterInfo>& image_layout_fields()
{
    static const std::vector<ParameterInfo> fields = image_block().infos();
    return fields;
}

void set_image_layout_field(ImageLayout& layout, const std::string& key, const ImageLayoutValue& value, const std::string& source)
{
    // Through the block's own reader, so that a value is read exactly as the file's would be.
    Json block = Json::object();
    std::visit([&](const auto& v) { block[key] = v; }, value);
    image_block().read_into(Field(block, source), layout);
}

std::string image_layout_field_problem(const ImageLayout& layout, const std::string& key)
{
    if (key != "channels" || layout.channels == "RGB" || layout.channels == "RGBA" || layout.channels == "Y") return {};
    return "expected \"RGB\", \"RGBA\" or \"Y\", got \"" + layout.channels + "\"";
}

}  // namespace stochtex
