#include "bench_command.h"

#include "commands.h"

#include <stochtex/model.h>
#include <stochtex/stex_file.h>

#include <cstdio>
#include <thread>

namespace stex_cli {

BenchCommand::BenchCommand(CLI::App& app)
{
    command_ = app.add_subcommand(
        "bench", "Measure a texture's throughput here: 2D, solid and plugin tiles, next to the same texture baked and read "
                 "through OIIO's TextureSystem");
    command_->add_option("texture", texture_, ".stex file")->required();
    command_->add_option("--size", settings_.size, "Raster side N (N×N pixels; the baked reference is an N² map), 16 to 8192")
        ->check(CLI::Range(16, 8192))->capture_default_str();
    command_->add_option("--scale", settings_.scale, "Exemplar pixels per output pixel (as render --scale)")
        ->check(positive_number())->capture_default_str();
    command_->add_option("--threads", settings_.threads, "Worker threads (0: all cores)")
        ->check(non_negative_number())->capture_default_str();
    command_->add_option("--repetitions", settings_.repetitions, "Timed runs per route (the median is reported), 1 to 100")
        ->check(CLI::Range(1, 100))->capture_default_str();
    command_->add_option("--tile", settings_.tile, "Tile side of the plugin route, 8 to 4096")
        ->check(CLI::Range(8, 4096))->capture_default_str();
}

int BenchCommand::run() const
{
    const stochtex::TextureDescription description = stochtex::read_stex(texture_);
    const unsigned threads = settings_.threads > 0 ? unsigned(settings_.threads) : std::max(1u, std::thread::hardware_concurrency());
    std::printf("%s: model %s (%s), %d² pixels, %u thread(s), median of %d runs\n", texture_.c_str(), description.model.c_str(),
                stochtex::model_info(description.model).summary.c_str(), settings_.size, threads, settings_.repetitions);
    std::fflush(stdout);
    const auto results = stochtex::measure_throughput(description, settings_);
    double reference = 0;
    for (const auto& result : results)
        if (result.route == "baked lookup (warm)") reference = result.median;
    for (const auto& result : results) {
        std::printf("  %-20s %9.3f M/s  (%.3f … %.3f)", result.route.c_str(), result.median, result.low, result.high);
        if (reference > 0) std::printf("  %6.2fx baked warm", result.median / reference);
        std::printf("\n  %-20s %s\n", "", result.detail.c_str());
    }
    return 0;
}

const CommandRegistration bench_registration = register_command<BenchCommand>(HelpPosition::bench, {"bench"});

}  // namespace stex_cli
