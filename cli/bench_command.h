// `stex bench T.stex`: this texture's throughput on this machine — 2D, solid, plugin tiles —
// next to the same texture baked and read through OIIO's TextureSystem (stochtex/throughput.h).
#pragma once

#include "command_registry.h"

#include <CLI/CLI.hpp>

#include <stochtex/throughput.h>

#include <string>

namespace stex_cli {

class BenchCommand : public Command {
public:
    /// Registers `bench` and its options on `app`.
    explicit BenchCommand(CLI::App& app);
    bool selected() const override { return command_->parsed(); }
    int run() const override;

private:
    CLI::App* command_;
    std::string texture_;
    stochtex::ThroughputSettings settings_;
};

}  // namespace stex_cli
