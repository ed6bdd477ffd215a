#include "command_registry.h"

#include <algorithm>
#include <tuple>

namespace stex_cli {

namespace {

struct Registered {
    HelpPosition position;
    std::vector<std::string> names;
    CommandFactory add;
};

std::vector<Registered>& registry()
{
    static std::vector<Registered> commands;  // constructed on first use: registrations run before main()
    return commands;
}

/// The registry in help order. Registrations run in an order the linker chooses, so it is sorted.
std::vector<const Registered*> in_help_order()
{
    std::vector<const Registered*> sorted;
    for (const Registered& command : registry()) sorted.push_back(&command);
    std::sort(sorted.begin(), sorted.end(), [](const Registered* a, const Registered* b) {
        return std::tie(a->position, a->names) < std::tie(b->position, b->names);
    });
    return sorted;
}

}  // namespace

CommandRegistration::CommandRegistration(HelpPosition position, std::vector<std::string> names, CommandFactory add)
{
    registry().push_back({position, std::move(names), std::move(add)});
}

std::vector<std::unique_ptr<Command>> add_registered_commands(CLI::App& app)
{
    std::vector<std::unique_ptr<Command>> commands;
    for (const Registered* command : in_help_order()) commands.push_back(command->add(app));
    return commands;
}

std::string registered_command_names()
{
    std::string text;
    for (const Registered* command : in_help_order())
        for (const std::string& name : command->names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

}  // namespace stex_cli
