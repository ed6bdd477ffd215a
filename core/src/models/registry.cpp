#include "models/model.h"

#include <stochtex/error.h>

#include "numerics/random.h"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <sstream>

namespace stochtex {

// ---- The built-in models: one line each (docs/architecture.md, "How to add a model") ----------
const Model& wavelet_model();
const Model& gabor_model();
const Model& tiling_model();
const Model& lrp_model();
const Model& ptm_model();

namespace {

std::vector<const Model*>& registry()
{
    // Built in first, in this order (it is the order of every list users see).
    static std::vector<const Model*> models{&wavelet_model(), &gabor_model(), &tiling_model(), &lrp_model(), &ptm_model()};
    return models;
}

std::vector<std::string>& names()
{
    static std::vector<std::string> list;
    return list;
}

std::string joined(const std::vector<std::string>& items, const char* separator = ", ")
{
    std::string result;
    for (const std::string& item : items) result += (result.empty() ? "" : separator) + item;
    return result;
}

/// The text a number had in provenance records before options were declared (ostream's
/// default formatting), so that files analysed today are byte-identical to earlier ones.
std::string stream_text(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

bool parse_number(const std::string& text, double& value)
{
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return !text.empty() && end == text.c_str() + text.size();
}

}  // namespace

void ModelParameters::wrong_type() { throw Error("texture description: parameters: not the parameters of this model"); }

// ---- Model defaults: capabilities a model does not have ----------------------------------------

void Model::unsupported(const std::string& what) const
{
    throw Error("model '" + name() + "' " + what);
}

ModelParameters Model::fit(const FitInput&, Provenance&) const { unsupported("cannot analyse photos"); }
ModelParameters Model::morph(const TextureDescription&, const TextureDescription&, double) const
{
    unsupported("cannot be morphed");
}
double Model::channel_sigma(const TextureDescription&, int) const { unsupported("has no Gaussian channels"); }
Vec3 Model::light(const TextureDescription&) const { unsupported("does not depend on a light direction"); }
void Model::set_light(TextureDescription&, const Vec3&) const { unsupported("does not depend on a light direction"); }

TextureDescription Model::example() const
{
    if (!info_.capabilities.analysis) unsupported("has no example description");
    // A 96² photo of correlated, coloured, non-Gaussian noise with some orientation: every
    // analysing model has something to fit, in milliseconds.
    constexpr int size = 96;
    Image photo(size, size, 3);
    SplitMix64 random(12345);
    std::vector<double> noise(std::size_t(size) * size);
    for (double& n : noise) n = random.uniform();
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double sum = 0;  // a 5 × 3 box (periodic): wider along x than along y
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -2; dx <= 2; ++dx) sum += noise[std::size_t((y + dy + size) % size) * size + (x + dx + size) % size];
            const double v = sum / 15, w = v * v;
            photo.at(x, y, 0) = float(0.2 + 0.5 * w);
            photo.at(x, y, 1) = float(0.15 + 0.4 * w + 0.05 * noise[std::size_t(y) * size + x]);
            photo.at(x, y, 2) = float(0.1 + 0.3 * v);
        }
    AnalysisOptions options;
    options.model = name();
    options.source_name = "example";
    return analyze(photo, options);
}

void Model::declare_analysis_options(std::vector<AnalysisOption> options)
{
    info_.analysis_options = option_infos(options);
    analysis_options_ = std::move(options);
}

// ---- The registry ---------------------------------------------------------------------------

const std::vector<const Model*>& registered_models() { return registry(); }

const Model* find_model(const std::string& name)
{
    for (const Model* model : registry())
        if (model->name() == name) return model;
    return nullptr;
}

const Model& model_named(const std::string& name, std::string_view source, std::string_view path)
{
    if (const Model* model = find_model(name)) return *model;
    json_fields::fail(std::string(source), std::string(path), "unknown model '" + name + "' (known models: " + joined(known_models()) + ")");
}

ModelRegistration::ModelRegistration(const Model& model)
{
    if (find_model(model.name())) throw Error("model registry: a model named '" + model.name() + "' is registered twice");
    registry().push_back(&model);
    names().clear();  // rebuilt on the next known_models()
}

const std::vector<std::string>& known_models()
{
    // Error messages list the models, and the plugin opens files from many threads at once.
    static std::mutex mutex;
    const std::lock_guard<std::mutex> lock(mutex);
    std::vector<std::string>& list = names();
    if (list.size() != registry().size()) {
        list.clear();
        for (const Model* model : registry()) list.push_back(model->name());
    }
    return list;
}

const ModelInfo& model_info(const std::string& name) { return model_named(name, "stochtex", "model").info(); }

std::vector<const ModelInfo*> registered_model_infos()
{
    std::vector<const ModelInfo*> result;
    for (const Model* model : registry()) result.push_back(&model->info());
    return result;
}

// ---- Machine-readable and documentation forms ------------------------------------------------

namespace {

json_fields::Json parameter_json(const ParameterInfo& p)
{
    json_fields::Json json = json_fields::Json::object();
    json["key"] = p.key;
    json["type"] = p.type;
    json["range"] = p.range;
    json["default"] = p.default_value;
    json["unit"] = p.unit;
    json["doc"] = p.doc;
    if (p.optional) json["optional"] = true;
    if (!p.fields.empty()) {
        json["fields"] = json_fields::Json::array();
        for (const ParameterInfo& field : p.fields) json["fields"].push_back(parameter_json(field));
    }
    return json;
}

/// Table rows for `p` and its fields (keys as JSON paths below `parent`).
void table_rows(const ParameterInfo& p, const std::string& parent, std::string& out)
{
    const std::string key = parent.empty() ? p.key : parent + "." + p.key;
    // Markdown cells: "|" would end the cell.
    auto cell = [](const std::string& text) {
        if (text.empty()) return std::string("—");
        std::string escaped;
        for (char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
        return escaped;
    };
    out += "| `" + key + "`" + (p.optional ? " (optional)" : "") + " | " + cell(p.type) + " | " + cell(p.range) + " | " +
           cell(p.default_value) + " | " + cell(p.unit) + " | " + cell(p.doc) + " |\n";
    for (const ParameterInfo& field : p.fields) table_rows(field, key, out);
}

}  // namespace

std::string models_json()
{
    json_fields::Json root = json_fields::Json::object();
    root["models"] = json_fields::Json::array();
    for (const Model* model : registry()) {
        const ModelInfo& info = model->info();
        json_fields::Json json = json_fields::Json::object();
        json["name"] = info.name;
        json["summary"] = info.summary;
        json["doc"] = info.doc;
        const ModelCapabilities& c = info.capabilities;
        json["capabilities"] = {{"analysis", c.analysis},         {"solid", c.solid},
                                {"morph", c.morph},               {"pov_procedural", c.pov_procedural},
                                {"osl", c.osl},                   {"light_direction", c.light_direction},
                                {"gaussian_channels", c.gaussian_channels}, {"joint_colour", c.joint_colour}};
        json["parameters"] = json_fields::Json::array();
        for (const ParameterInfo& p : info.parameters) json["parameters"].push_back(parameter_json(p));
        json["analysis_options"] = json_fields::Json::array();
        for (const ParameterInfo& p : info.analysis_options) json["analysis_options"].push_back(parameter_json(p));
        root["models"].push_back(json);
    }
    return root.dump(2) + "\n";
}

std::string parameter_table_markdown(const ModelInfo& model) { return parameter_table_markdown(model.parameters, "parameters"); }

std::string parameter_table_markdown(const std::vector<ParameterInfo>& fields, const std::string& parent)
{
    std::string out = "| key | type | range | default | unit | meaning |\n|---|---|---|---|---|---|\n";
    for (const ParameterInfo& p : fields) table_rows(p, parent, out);
    return out;
}

// ---- Analysis options ----------------------------------------------------------------------------

AnalysisOption number_option(const char* key, double min, double max, FieldDoc doc, std::string word, bool max_open)
{
    const std::string range = "[" + stream_text(min) + ", " + stream_text(max) + (max_open ? ")" : "]");
    AnalysisOption option;
    option.info = {key, "number", word.empty() ? range : word + " or " + range, doc.default_value, doc.unit, doc.doc, {}};
    option.canonical = [=](const std::string& text) {
        if (!word.empty() && text == word) return word;
        double value = 0;
        if (!parse_number(text, value) || !(value >= min && (max_open ? value < max : value <= max)))
            throw Error("must be " + (word.empty() ? "" : word + " or ") + "a number in " + range + ", got '" + text + "'");
        return text;  // exact: the fit reads the value the user gave
    };
    return option;
}

AnalysisOption integer_option(const char* key, long min, long max, FieldDoc doc, std::string word)
{
    const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
    AnalysisOption option;
    option.info = {key, "integer", word.empty() ? range : word + " or " + range, doc.default_value, doc.unit, doc.doc, {}};
    option.canonical = [=](const std::string& text) {
        if (!word.empty() && text == word) return word;
        char* end = nullptr;
        const long value = std::strtol(text.c_str(), &end, 10);
        if (text.empty() || end != text.c_str() + text.size() || value < min || value > max)
            throw Error("must be " + (word.empty() ? "" : word + " or ") + "an integer in " + range + ", got '" + text + "'");
        return std::to_string(value);  // (an integer's text is exact)
    };
    return option;
}

AnalysisOption choice_option(const char* key, std::vector<std::string> choices, FieldDoc doc)
{
    AnalysisOption option;
    option.info = {key, "string", joined(choices, " | "), doc.default_value, doc.unit, doc.doc, {}};
    option.canonical = [choices](const std::string& text) {
        if (std::find(choices.begin(), choices.end(), text) == choices.end())
            throw Error("expected one of " + joined(choices) + ", got '" + text + "'");
        return text;
    };
    return option;
}

std::string recorded_option(const std::map<std::string, std::string>& options, const std::string& key)
{
    const std::string& text = options.at(key);
    double value = 0;
    return parse_number(text, value) ? stream_text(value) : text;
}

std::vector<ParameterInfo> option_infos(const std::vector<AnalysisOption>& options)
{
    std::vector<ParameterInfo> result;
    for (const AnalysisOption& option : options) result.push_back(option.info);
    return result;
}

std::map<std::string, std::string> parse_model_options(const Model& model,
                                                      const std::vector<std::pair<std::string, std::string>>& given)
{
    const std::vector<AnalysisOption>& declared = model.analysis_options();
    std::map<std::string, std::string> result;
    for (const AnalysisOption& option : declared) result[option.info.key] = option.canonical(option.info.default_value);
    for (const auto& [key, text] : given) {
        auto option = std::find_if(declared.begin(), declared.end(),
                                   [&, &key = key](const AnalysisOption& o) { return o.info.key == key; });
        if (option == declared.end()) {
            std::vector<std::string> keys;
            for (const AnalysisOption& o : declared) keys.push_back(o.info.key);
            throw Error(model.name() + ": unknown analysis option --" + key + " (" +
                        (keys.empty() ? std::string("this model has none") : "its options: --" + joined(keys, ", --")) + ")");
        }
        try {
            result[key] = option->canonical(text);
        } catch (const Error& e) {
            throw Error(model.name() + ": --" + key + ": " + e.what());
        }
    }
    return result;
}

}  // namespace stochtex
