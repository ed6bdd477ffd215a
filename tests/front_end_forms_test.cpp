// The front-ends' registries from the outside: a model's OSL form, procedural POV-Ray form and
// `stex` commands are found through registrations, never through its name. Two programs:
// `stex` itself, in which every built-in model that claims a form has one linked (the forms
// register themselves from object files nothing references by name, which a linker drops from a
// static library), and stex_with_test_models, the same tool holding the test suite's models
// (tests/models/), whose model with every capability (test_everything_model.cpp and its forms
// beside it) gets all of them with no edit outside its own files.
#include "models/model.h"
#include "test_support.h"

#include <stochtex/model.h>
#include <stochtex/stex_file.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using stochtex::test::contains;
using stochtex::test::ProgramResult;

ProgramResult run(const char* program, const std::vector<std::string>& args, const fs::path& dir)
{
    std::vector<std::string> argv{program};
    argv.insert(argv.end(), args.begin(), args.end());
    return stochtex::test::run_program(argv, dir.string());
}
ProgramResult stex(const std::vector<std::string>& args, const fs::path& dir) { return run(STOCHTEX_CLI, args, dir); }
ProgramResult stex_with_test_models(const std::vector<std::string>& args, const fs::path& dir)
{
    return run(STOCHTEX_CLI_WITH_TEST_MODELS, args, dir);
}

std::string read_file(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FrontEndForms : public ::testing::Test {
protected:
    void SetUp() override { dir_ = stochtex::test::temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
    fs::path dir_;

    /// A test_everything texture fitted from the repository's exemplar by `stex analyze`.
    fs::path analysed_test_everything()
    {
        const fs::path texture = dir_ / "t.stex";
        const ProgramResult r = stex_with_test_models(
            {"analyze", stochtex::test::repo_exemplar("concrete_512.png"), "--model", "test_everything", "-o", texture.string()},
            dir_);
        EXPECT_TRUE(r.succeeded()) << r;
        return texture;
    }
};

TEST_F(FrontEndForms, EveryBuiltInFormIsLinkedIntoStex)
{
    // Each model claiming an OSL or procedural POV-Ray form: its example, through `stex`.
    for (const stochtex::ModelInfo* info : stochtex::registered_model_infos()) {
        if (!info->capabilities.osl && !info->capabilities.pov_procedural) continue;
        stochtex::TextureDescription example = stochtex::find_model(info->name)->example();
        example.chroma_given_brightness = {};  // POV-Ray's procedural form cannot express joint colour
        const fs::path texture = dir_ / (info->name + ".stex");
        stochtex::write_stex(texture.string(), example);
        if (info->capabilities.osl) {
            const ProgramResult r = stex({"osl", texture.string(), "-o", (dir_ / (info->name + ".osl")).string()}, dir_);
            EXPECT_TRUE(r.succeeded()) << info->name << "\n" << r;
            EXPECT_TRUE(contains(read_file(dir_ / (info->name + ".osl")), "the " + info->name + " model")) << info->name;
        }
        if (info->capabilities.pov_procedural) {
            const ProgramResult r =
                stex({"pov", texture.string(), "--mode", "procedural", "-o", (dir_ / (info->name + ".inc")).string()}, dir_);
            EXPECT_TRUE(r.succeeded()) << info->name << "\n" << r;
        }
    }
}

TEST_F(FrontEndForms, TheTestModelsAreOnlyInTheTestsStex)
{
    const ProgramResult tool = stex({"models", "--json"}, dir_), with = stex_with_test_models({"models", "--json"}, dir_);
    ASSERT_TRUE(tool.succeeded()) << tool;
    ASSERT_TRUE(with.succeeded()) << with;
    EXPECT_FALSE(contains(tool.out, "\"test_everything\""));
    EXPECT_TRUE(contains(with.out, "\"test_everything\""));
    EXPECT_TRUE(contains(with.out, "\"test_noise\""));
    EXPECT_FALSE(contains(stex({"--help"}, dir_).out, "test-everything"));
}

TEST_F(FrontEndForms, TheModelWithEveryCapabilityDeclaresThem)
{
    const ProgramResult r = stex_with_test_models({"models", "--json"}, dir_);
    ASSERT_TRUE(r.succeeded()) << r;
    const nlohmann::json models = nlohmann::json::parse(r.out)["models"];
    const auto found = std::find_if(models.begin(), models.end(), [](const nlohmann::json& m) { return m["name"] == "test_everything"; });
    ASSERT_NE(found, models.end()) << r.out;
    for (const char* capability : {"analysis", "solid", "morph", "pov_procedural", "osl"})
        EXPECT_TRUE((*found)["capabilities"][capability].get<bool>()) << capability;
}

TEST_F(FrontEndForms, ItsCommandIsInTheHelpAndRuns)
{
    const ProgramResult help = stex_with_test_models({"--help"}, dir_);
    EXPECT_TRUE(contains(help.out, "test-everything")) << help;
    EXPECT_TRUE(contains(help.out, "Print a test_everything texture's parameters")) << help;
    // The list of commands a bare `stex` prints comes from the same registry.
    const ProgramResult bare = stex_with_test_models({}, dir_);
    EXPECT_EQ(bare.code, 1) << bare;
    EXPECT_TRUE(contains(bare.err, "test-everything")) << bare;

    const fs::path texture = analysed_test_everything();
    const ProgramResult r = stex_with_test_models({"test-everything", texture.string()}, dir_);
    EXPECT_TRUE(r.succeeded()) << r;
    EXPECT_TRUE(contains(r.out, "test_everything: frequency ")) << r;
}

TEST_F(FrontEndForms, ItsTextureIsReadWrittenMorphedAndRendered)
{
    // Written by analyze, read by info, morph (which writes it again) and render; the byte-for-byte
    // round trip of its .stex is the conformance suite's (model_conformance_test.cpp), which holds it.
    const fs::path texture = analysed_test_everything();
    const ProgramResult info = stex_with_test_models({"info", texture.string()}, dir_);
    EXPECT_TRUE(info.succeeded()) << info;
    EXPECT_TRUE(contains(info.out, "test everything")) << info;
    const fs::path morphed = dir_ / "m.stex";
    const ProgramResult morph =
        stex_with_test_models({"morph", texture.string(), texture.string(), "--t", "0.5", "-o", morphed.string()}, dir_);
    EXPECT_TRUE(morph.succeeded()) << morph;
    const ProgramResult again = stex_with_test_models({"info", morphed.string()}, dir_);
    EXPECT_TRUE(again.succeeded()) << again;
    EXPECT_TRUE(contains(again.out, "test everything")) << again;
    const ProgramResult solid = stex_with_test_models(
        {"render", morphed.string(), "--solid", "--z", "0.5", "--size", "16x16", "-o", (dir_ / "s.exr").string()}, dir_);
    EXPECT_TRUE(solid.succeeded()) << solid;
}

TEST_F(FrontEndForms, OslAndPovFindItsForms)
{
    const fs::path texture = analysed_test_everything();
    const ProgramResult osl = stex_with_test_models({"osl", texture.string(), "-o", (dir_ / "t.osl").string()}, dir_);
    ASSERT_TRUE(osl.succeeded()) << osl;
    const std::string shader = read_file(dir_ / "t.osl");
    EXPECT_TRUE(contains(shader, "shader stochtex_t(")) << shader;
    EXPECT_TRUE(contains(shader, "float mean[3] = {")) << shader;
    EXPECT_TRUE(contains(shader, "the test_everything model")) << shader;
    EXPECT_TRUE(fs::exists(dir_ / "stochtex_rows.exr"));  // the row probe every shader reads

    // Procedural is the default where the model has the form.
    const ProgramResult pov = stex_with_test_models({"pov", texture.string(), "-o", (dir_ / "T.inc").string()}, dir_);
    ASSERT_TRUE(pov.succeeded()) << pov;
    EXPECT_TRUE(contains(pov.out, "procedural mode")) << pov;
    const std::string include = read_file(dir_ / "T.inc");
    EXPECT_TRUE(contains(include, "The test_everything model: its mean colour.")) << include;
    EXPECT_TRUE(contains(include, "#declare T = texture { pigment { T_Pigment } }")) << include;
}

}  // namespace
