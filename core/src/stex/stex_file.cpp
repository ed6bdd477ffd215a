#include <stochtex/atomic_write.h>
#include <stochtex/error.h>
#include <stochtex/stex_file.h>

#include "models/model.h"
#include "schema/json_fields.h"
#include "stex/stex_blocks.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

namespace stochtex {

namespace {

using json_fields::Field;
using json_fields::Json;

// ---- Checks shared by the reader and validate() ------------------------------------------------

void check_version(int version, const std::string& source)
{
    if (version != TextureDescription::current_version)
        json_fields::fail(source, "version",
                          "unsupported version " + std::to_string(version) + " (this build reads version " +
                              std::to_string(TextureDescription::current_version) + ")");
}

// ---- Reading ------------------------------------------------------------------------------------

void read_histograms(const Field& histograms, TextureDescription& description)
{
    std::vector<Field> channels = histograms.elements(3, "histograms");
    for (std::size_t channel = 0; channel < 3; ++channel) {
        const Field& histogram = channels[channel];
        if (histogram.is_null()) continue;  // disabled: the channel stays Gaussian
        HistogramMap& map = description.histograms[channel] = histogram_block().read(histogram);
        // One spelling per description keeps files canonical.
        if (!map.enabled()) histogram.fail("a disabled histogram is written as null, not as empty arrays");
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
    root["scale"] = scale_block().write(description);
    root["colour"] = colour_block().write(description);
    Json& histograms = root["histograms"] = Json::array();
    for (const HistogramMap& map : description.histograms)
        histograms.push_back(map.enabled() ? histogram_block().write(map) : Json());  // null when disabled
    root["parameters"] = model_of(description).write_parameters(description);
    root["provenance"] = provenance_block().write(description.provenance);
    if (description.image) root["image"] = image_block().write(*description.image);
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

    scale_block().validate(description, "scale", source);
    colour_block().validate(description, "colour", source);
    for (std::size_t c = 0; c < 3; ++c) histogram_block().validate(description.histograms[c], json_path("histograms", c), source);
    provenance_block().validate(description.provenance, "provenance", source);
    if (description.image) image_block().validate(*description.image, "image", source);
}

void validate_image_layout(const ImageLayout& image, const std::string& source) { image_block().validate(image, "image", source); }

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

    scale_block().read_into(root["scale"], description);
    colour_block().read_into(root["colour"], description);
    read_histograms(root["histograms"], description);
    // The model reads its own block (files it keeps beside the .stex are found from source_name).
    description.parameters = model.read_parameters(root["parameters"], source_name);
    description.provenance = provenance_block().read(root["provenance"]);
    if (root.contains("image")) description.image = image_block().read(root["image"]);

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
