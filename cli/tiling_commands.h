// `stex tiling …`: tiling textures that are not analysed from one colour photo
// (docs/models/tiling.md): colour-mapped noise pairs, phasor noise, normal maps from a height
// photo, and the LEAN-filtered shading of a normal map. (`stex analyze --model tiling` covers
// colour photos.)
#pragma once

#include <CLI/CLI.hpp>

#include <memory>

namespace stex_cli {

class TilingCommands {
public:
    /// Registers the tiling command and its sub-commands on `app`.
    explicit TilingCommands(CLI::App& app);
    ~TilingCommands();
    bool selected() const;
    /// Runs the chosen sub-command; throws stochtex::Error for bad input.
    int run() const;

private:
    struct Options;
    std::unique_ptr<Options> options_;
};

}  // namespace stex_cli
