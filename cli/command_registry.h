// The `stex` sub-commands as a registry: each command (the built-in ones in commands.cpp, bench,
// batch, and a model's own commands in core/src/models/<name>/front_ends/<name>_cli.cpp) adds
// itself with a static CommandRegistration, and main() builds the command line from the list.
// A model's command thus needs no edit here or in main().
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace stex_cli {

/// One registered command, added to the command line: its sub-command(s) and their options.
class Command {
public:
    virtual ~Command() = default;
    /// Whether the parsed command line chose this command.
    virtual bool selected() const = 0;
    /// Runs it: the process exit code; throws stochtex::Error for bad input (main() exits 1).
    virtual int run() const = 0;
};

/// Where a command stands in `stex --help` and in the "a sub-command is required" list: by
/// position, then name. The texture's life first, then tools, then a model's own commands.
enum class HelpPosition {
    analyze, render, info, compare, morph, bake, osl, pov, models,  // the built-in commands, in this order
    bench,
    model_command,  ///< a model's own commands (ptm, tiling, …), by name
    batch,
};

/// Adds a command's sub-command(s) to `app` and returns the command (which keeps its options).
using CommandFactory = std::function<std::unique_ptr<Command>(CLI::App& app)>;

/// Registers a command (a static object of this type beside the command's code). `names` are the
/// sub-commands it adds (batch adds two), for the list of commands main() prints.
struct CommandRegistration {
    CommandRegistration(HelpPosition position, std::vector<std::string> names, CommandFactory add);
};

/// Registers a command of type T, built from the app it adds its sub-command(s) to.
template <class T>
CommandRegistration register_command(HelpPosition position, std::vector<std::string> names)
{
    return CommandRegistration(position, std::move(names),
                               [](CLI::App& app) -> std::unique_ptr<Command> { return std::make_unique<T>(app); });
}

/// A command that is one sub-command whose options fill an `Options` struct, which declares them
/// (`void add_options(CLI::App&)`) and runs (`int run() const`).
template <class Options>
class OptionsCommand : public Command {
public:
    OptionsCommand(CLI::App& app, const std::string& name, const std::string& description)
        : command_(app.add_subcommand(name, description))
    {
        options_.add_options(*command_);  // binds to options_'s members: the object never moves (unique_ptr)
    }
    bool selected() const override { return command_->parsed(); }
    int run() const override { return options_.run(); }

private:
    CLI::App* command_;
    Options options_;
};

/// Registers an OptionsCommand<Options> named `name`.
template <class Options>
CommandRegistration register_options_command(HelpPosition position, std::string name, std::string description)
{
    return CommandRegistration(position, {name}, [name, description](CLI::App& app) -> std::unique_ptr<Command> {
        return std::make_unique<OptionsCommand<Options>>(app, name, description);
    });
}

/// Adds every registered command to `app` in help order; the commands keep the parsed options.
std::vector<std::unique_ptr<Command>> add_registered_commands(CLI::App& app);

/// The registered sub-commands' names in help order, as "analyze, render, …".
std::string registered_command_names();

}  // namespace stex_cli
