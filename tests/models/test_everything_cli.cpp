// The `stex` command of the test suite's model with every capability (test_everything_model.cpp):
// `stex test-everything T.stex` prints its parameters. It registers itself as the ptm and tiling
// models' commands do (core/src/models/<name>/front_ends/<name>_cli.cpp).
#include "command_registry.h"
#include "models/test_everything_parameters.h"

#include <stochtex/error.h>
#include <stochtex/stex_file.h>

#include <cstdio>

namespace stex_cli {

namespace {

struct TestEverythingCommand {
    std::string texture;
    void add_options(CLI::App& command) { command.add_option("texture", texture, ".stex file")->required(); }
    int run() const
    {
        const stochtex::TextureDescription description = stochtex::read_stex(texture);
        if (description.model != "test_everything")
            throw stochtex::Error(texture + ": a " + description.model + " texture, not a test_everything one");
        const auto& p = description.parameters.get<stochtex::test::TestEverythingParameters>();
        std::printf("test_everything: frequency %g, amplitude %g\n", p.frequency, p.amplitude);
        return 0;
    }
};

const CommandRegistration registration = register_options_command<TestEverythingCommand>(
    HelpPosition::model_command, "test-everything", "Print a test_everything texture's parameters (test suite only)");

}  // namespace

}  // namespace stex_cli
