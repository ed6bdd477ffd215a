// `stex batch` (a texture library: every photo of a folder or manifest analysed, optionally
// previewed, compared and baked; sharded for array jobs; resumable) and `stex batch-report`
// (the shards' logs merged into report.json, report.csv and the index.html gallery).
// docs/batch.md and docs/cluster.md.
#pragma once

#include "command_registry.h"

#include <CLI/CLI.hpp>

#include <memory>

namespace stex_cli {

class BatchCommands : public Command {
public:
    /// Registers `batch` and `batch-report` on `app`.
    explicit BatchCommands(CLI::App& app);
    ~BatchCommands();
    bool selected() const override;
    /// Runs the chosen one. The exit status is the number of photos that failed (at most 100;
    /// 0: every photo done); stochtex::Error for a batch that cannot start (main() exits 1).
    int run() const override;

    struct Options;  // the options given (batch_command.cpp)

private:
    std::unique_ptr<Options> options_;
};

}  // namespace stex_cli
