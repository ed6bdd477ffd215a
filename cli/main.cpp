// stex — the stochtex command-line tool. See `stex --help` and README.md.
#include "command_registry.h"
#include "progress_bar.h"

#include <stochtex/atomic_write.h>
#include <stochtex/error.h>

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <vector>

namespace {

// Every output is written to a temporary and renamed into place (stochtex/atomic_write.h), so
// an interrupted run never leaves a half-written file under an output's name; this handler
// removes the temporaries too, then dies of the signal so that the caller sees the interruption.
extern "C" void remove_outputs_and_die(int signal_number)
{
    stochtex::remove_pending_outputs();
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

void install_signal_handlers()
{
    struct sigaction action {};
    action.sa_handler = remove_outputs_and_die;
    sigemptyset(&action.sa_mask);
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal_number, &action, nullptr);
    // Past a file-size limit (ulimit -f) the default action kills the process, leaving the
    // temporary behind; ignored, the write fails with EFBIG and is reported like any other.
    std::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace stex_cli;
    CLI::App app{"stex — procedural textures by example (stochtex " STOCHTEX_VERSION ")"};
    // At most one sub-command; "none" is reported below, so that an unknown word is named as
    // such instead of as a missing sub-command.
    app.require_subcommand(0, 1);
    app.set_version_flag("--version", "stochtex " STOCHTEX_VERSION);
    bool progress_lines = false;
    app.add_flag("--progress-lines", progress_lines,
                 "Report progress as lines 'progress FRACTION STAGE' on stderr (for programs running stex)");
    // Every command, the built-in ones and the models' own, comes from the registry.
    const std::vector<std::unique_ptr<Command>> commands = add_registered_commands(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    set_progress_lines(progress_lines);
    install_signal_handlers();
    if (app.get_subcommands().empty()) {
        std::fprintf(stderr, "stex: error: a sub-command is required (%s); see stex --help\n",
                     registered_command_names().c_str());
        return 1;
    }
    try {
        for (const auto& command : commands)
            if (command->selected()) return command->run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stex: error: %s\n", e.what());
        return 1;
    }
    return 2;
}
