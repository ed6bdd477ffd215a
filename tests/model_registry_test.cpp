// The model registry as users and documentation see it (the built-in models only: this program
// links no test model): the docs' parameter tables are the declarations', every declared
// analysis option accepts its own default, option errors name the model and the option, and
// `stex models --json` is the registry.
#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/model.h>
#include <stochtex/stex_file.h>

#include "models/model.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>

namespace stochtex {
namespace {

std::string read_text(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ModelRegistry, DocsParameterTablesAreTheDeclarations)
{
    const std::string path = std::string(STOCHTEX_SOURCE_DIR) + "/docs/stex-format.md";
    const std::string document = read_text(path);
    ASSERT_FALSE(document.empty()) << path;
    for (const ModelInfo* model : registered_model_infos()) {
        const std::string begin = "<!-- parameters " + model->name + ": ", end = "<!-- end parameters " + model->name + " -->";
        const std::size_t start = document.find(begin), stop = document.find(end);
        ASSERT_NE(start, std::string::npos) << path << " has no parameter table for model " << model->name;
        ASSERT_NE(stop, std::string::npos) << path << " has no end marker for model " << model->name;
        const std::size_t table = document.find('\n', start) + 1;
        EXPECT_EQ(document.substr(table, stop - table), parameter_table_markdown(*model))
            << path << ": the table of model " << model->name
            << " differs from its declaration; run scripts/update-parameter-tables.py build-dev/cli/stex";
    }
}

// The blocks every file shares are declared once too (core/src/stex/stex_blocks.cpp): the
// document's tables of scale, colour, histograms, provenance and image are those declarations.
TEST(ModelRegistry, DocsSharedBlockTablesAreTheDeclarations)
{
    const std::string path = std::string(STOCHTEX_SOURCE_DIR) + "/docs/stex-format.md";
    const std::string document = read_text(path);
    ASSERT_FALSE(document.empty()) << path;
    const std::vector<StexBlockInfo> blocks = shared_stex_blocks();
    ASSERT_EQ(blocks.size(), 5u);
    for (const StexBlockInfo& block : blocks) {
        EXPECT_FALSE(block.fields.empty()) << block.path;
        for (const ParameterInfo& field : block.fields) EXPECT_FALSE(field.doc.empty()) << block.path << "." << field.key;
        const std::string begin = "<!-- block " + block.path + ": ", end = "<!-- end block " + block.path + " -->";
        const std::size_t start = document.find(begin), stop = document.find(end);
        ASSERT_NE(start, std::string::npos) << path << " has no table for the block " << block.path;
        ASSERT_NE(stop, std::string::npos) << path << " has no end marker for the block " << block.path;
        const std::size_t table = document.find('\n', start) + 1;
        EXPECT_EQ(document.substr(table, stop - table), parameter_table_markdown(block.fields, block.path))
            << path << ": the table of " << block.path << " differs from its declaration; run scripts/update-parameter-tables.py";
    }
}

TEST(ModelRegistry, EveryModelDeclaresItsParametersAndDocumentsThem)
{
    for (const ModelInfo* model : registered_model_infos()) {
        EXPECT_FALSE(model->summary.empty()) << model->name;
        EXPECT_FALSE(model->parameters.empty()) << model->name;
        EXPECT_TRUE(std::ifstream(std::string(STOCHTEX_SOURCE_DIR) + "/" + model->doc).good()) << model->name << ": " << model->doc;
        for (const ParameterInfo& p : model->parameters) {
            EXPECT_FALSE(p.doc.empty()) << model->name << "." << p.key;
            EXPECT_FALSE(p.type.empty()) << model->name << "." << p.key;
        }
        // Analysis options only for models that analyse, each with a doc line and a default.
        if (!model->capabilities.analysis) EXPECT_TRUE(model->analysis_options.empty()) << model->name;
        for (const ParameterInfo& option : model->analysis_options) {
            EXPECT_FALSE(option.doc.empty()) << model->name << " --" << option.key;
            EXPECT_FALSE(option.default_value.empty()) << model->name << " --" << option.key;
        }
    }
}

TEST(ModelRegistry, AnalysisOptionsAcceptTheirDefaultsAndNameWhatIsWrong)
{
    for (const Model* model : registered_models()) {
        if (!model->info().capabilities.analysis) continue;
        EXPECT_NO_THROW(parse_model_options(*model, {})) << model->name();
        std::vector<std::pair<std::string, std::string>> defaults;
        for (const ParameterInfo& option : model->info().analysis_options) defaults.emplace_back(option.key, option.default_value);
        EXPECT_NO_THROW(parse_model_options(*model, defaults)) << model->name();
        try {
            parse_model_options(*model, {{"no-such-option", "1"}});
            ADD_FAILURE() << model->name() << " accepted an undeclared option";
        } catch (const Error& e) {
            EXPECT_TRUE(test::contains(e.what(), model->name() + ": unknown analysis option --no-such-option")) << e.what();
        }
    }
    // A value out of its declared range names the model and the option.
    try {
        parse_model_options(*find_model("lrp"), {{"L", "99"}});
        ADD_FAILURE() << "--L 99 accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "lrp: --L: must be an integer in [1, 16], got '99'");
    }
    // The analysis rejects another model's option instead of ignoring it.
    AnalysisOptions options;
    options.model = "wavelet";
    options.model_options = {{"impulses", "8"}};
    EXPECT_THROW(analyze(Image(64, 64, 3), options), Error);
}

TEST(ModelRegistry, CapabilitiesDecideTheFrontEnds)
{
    for (const ModelInfo* model : registered_model_infos()) {
        const ModelCapabilities& can = model->capabilities;
        // Morphing interpolates Gaussian channels' weights; relighting needs a light.
        if (can.morph) EXPECT_TRUE(can.gaussian_channels) << model->name;
        if (can.light_direction) EXPECT_FALSE(can.morph) << model->name;
    }
    EXPECT_THROW(model_info("perlin"), Error);
}

TEST(ModelRegistry, StexModelsJsonIsTheRegistry)
{
    const test::ProgramResult result = test::run_program({STOCHTEX_CLI, "models", "--json"}, test::temp_dir("models_json"));
    ASSERT_TRUE(result.succeeded()) << result;
    EXPECT_EQ(result.out, models_json());
    const nlohmann::json json = nlohmann::json::parse(result.out);
    std::vector<std::string> names;
    for (const auto& model : json["models"]) names.push_back(model["name"]);
    EXPECT_EQ(names, known_models());
    const test::ProgramResult table = test::run_program({STOCHTEX_CLI, "models"}, test::temp_dir("models_table"));
    ASSERT_TRUE(table.succeeded()) << table;
    for (const std::string& name : known_models()) EXPECT_TRUE(test::contains(table.out, name)) << table;
}

}  // namespace
}  // namespace stochtex
