// `stex ptm …`: relightable textures (docs/models/ptm.md). Fit a PTM to photos under known
// lights, synthesise larger PTMs in ψ-space, relight them, export normal and albedo maps, and
// render the height-field test data with known truth.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace stex_cli {

class PtmCommands {
public:
    /// Registers the ptm command and its sub-commands on `app`.
    explicit PtmCommands(CLI::App& app);
    ~PtmCommands();
    /// Whether the command line chose the ptm command.
    bool selected() const;
    /// Runs the chosen sub-command; throws stochtex::Error for bad input.
    int run() const;

private:
    struct Options;
    std::unique_ptr<Options> options_;
};

}  // namespace stex_cli
