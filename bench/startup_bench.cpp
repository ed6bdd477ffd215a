// stochtex — what a user waits for at every `stex` call: process start to the first pixel.
//
//   Startup/render1x1/<model>[/solid]   `stex render T.stex --size 1x1 -o OUT.exr`: start, read the
//                                       .stex, build the texture (and the tables it needs),
//                                       evaluate one pixel, write it, exit (every model; solid
//                                       for those with a solid form; ptm reads its coefficient
//                                       EXR beside the .stex)
//   Startup/render1x1/<model>/png       the same to a PNG (sRGB-encoded on writing)
//   Ref/Version                         `stex --version`: the same executable, no texture (the
//                                       dynamic loader and static initialisation: the floor)
//   Ref/True                            `/bin/true`: fork + exec of a minimal process
//
// Each iteration is one fork/exec/wait of the command, timed on the wall clock (ms) and by the
// child's CPU time (cpu_ms, user + system: robust on a shared machine); report medians
// (bench/run.sh: STOCHTEX_BENCH=startup_bench bench/run.sh). The textures are analysed from
// data/exemplars/concrete_512.png once, before any timing, one per model (default options). The
// table ends with each model's median minus the Ref/Version floor: the time the texture itself
// costs before its first pixel (goal: the whole command ≤ 100 ms).
//
// STOCHTEX_REFERENCE_STEX=/path/to/other/stex adds the same commands run by another build
// (Reference/..., Reference/Version its floor), each registered right after this build's: the
// two alternate through the run, so before/after figures share the machine's load.
#include <benchmark/benchmark.h>

#include "median_reporter.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

/// Runs argv[0] with its arguments, stdout and stderr to /dev/null; returns its exit status and
/// adds the child's CPU time (user + system, seconds) to *cpu.
int run(const std::vector<std::string>& args, double* cpu = nullptr)
{
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        if (std::freopen("/dev/null", "w", stdout) == nullptr || std::freopen("/dev/null", "w", stderr) == nullptr)
            _exit(126);
        execv(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    struct rusage usage {};
    if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return -1;
    if (cpu)
        *cpu += double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void bm_command(benchmark::State& state, std::vector<std::string> args, std::string label)
{
    double cpu = 0;
    for (auto _ : state) {
        if (run(args, &cpu) != 0) {
            state.SkipWithError(("command failed: " + args[0]).c_str());
            break;
        }
    }
    state.counters["ms"] = benchmark::Counter(double(state.iterations()) * 1e-3,
                                              benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    // The child's own CPU time per run: what the command costs, however loaded the machine is.
    state.counters["cpu_ms"] = benchmark::Counter(1e3 * cpu / double(std::max<benchmark::IterationCount>(1, state.iterations())));
    state.SetLabel(label);
}

class StartupReporter : public stochtex::bench::MedianReporter {
public:
    explicit StartupReporter(OutputOptions options) : MedianReporter({"cpu_ms"}, options) {}

    void Finalize() override
    {
        ConsoleReporter::Finalize();
        const Entry* floor = find("Ref/Version");
        std::printf("\nStart-up (median CPU ms of the child process, user + system; above the floor = what the\n"
                    "texture costs; the ms column above is wall time, which a loaded machine inflates):\n");
        for (const auto& [name, entry] : medians()) {
            std::printf("  %-40s %8.1f ms", name.c_str(), entry.rate);
            // Each build's commands above its own floor.
            const bool reference = name.rfind("Reference/", 0) == 0;
            const Entry* own = reference ? find("Reference/Version") : floor;
            if (own && name.rfind("Ref/", 0) != 0 && name != "Reference/Version")
                std::printf("   %+8.1f ms above stex --version", entry.rate - own->rate);
            std::printf("\n");
        }
        std::fflush(stdout);
    }
};

}  // namespace

int main(int argc, char** argv)
{
    const bool console = stochtex::bench::console_format(argc, argv);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    const std::string stex = STOCHTEX_STEX;
    const fs::path photo = fs::path(STOCHTEX_SOURCE_DIR) / "data" / "exemplars" / "concrete_512.png";
    const fs::path folder = fs::temp_directory_path() / ("stochtex_startup_bench." + std::to_string(getpid()));
    fs::create_directories(folder);
    const std::string output = (folder / "pixel.exr").string(), output_png = (folder / "pixel.png").string();

    benchmark::RegisterBenchmark("Ref/True", bm_command, std::vector<std::string>{"/bin/true"},
                                 "fork+exec of /bin/true")
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    std::vector<std::pair<std::string, std::string>> programs{{"Startup", stex}};
    if (const char* reference = std::getenv("STOCHTEX_REFERENCE_STEX")) programs.push_back({"Reference", reference});
    auto add = [&](const std::string& name, const std::vector<std::string>& args, const std::string& label) {
        benchmark::RegisterBenchmark(name.c_str(), bm_command, args, label)->Unit(benchmark::kMillisecond)->UseRealTime();
    };
    for (const auto& [prefix, program] : programs)
        add(prefix == "Startup" ? "Ref/Version" : "Reference/Version", {program, "--version"},
            "stex --version: loader + static initialisation, " + program);

    // The textures: one per model, analysed once before any timing (ptm: fitted to a relief
    // rendered from the photo as a height map, 12 lights).
    std::vector<std::pair<std::string, std::string>> textures;
    for (const char* model : {"wavelet", "gabor", "lrp", "tiling"}) {
        const std::string texture = (folder / (std::string(model) + ".stex")).string();
        if (run({stex, "analyze", photo.string(), "--model", model, "-o", texture}) != 0) {
            std::fprintf(stderr, "startup_bench: cannot analyse %s with %s\n", photo.string().c_str(), model);
            return 1;
        }
        textures.push_back({model, texture});
    }
    const std::string relief = (folder / "relief").string(), ptm = (folder / "ptm.stex").string();
    if (run({stex, "ptm", "relief", photo.string(), "-o", relief, "--lights", "12"}) != 0 ||
        run({stex, "ptm", "fit", relief + "/lights.lp", "-o", ptm}) != 0) {
        std::fprintf(stderr, "startup_bench: cannot make the ptm texture from %s\n", photo.string().c_str());
        return 1;
    }
    textures.push_back({"ptm", ptm});

    for (const auto& [model, texture] : textures)
        for (const char* variant : {"", "/solid", "/png"}) {
            const bool solid = std::strcmp(variant, "/solid") == 0, png = std::strcmp(variant, "/png") == 0;
            if (solid && (model == "ptm" || model == "tiling")) continue;  // no solid form
            for (const auto& [prefix, program] : programs) {
                std::vector<std::string> args{program, "render", texture, "--size", "1x1", "-o", png ? output_png : output};
                if (solid) args.push_back("--solid");
                add(prefix + "/render1x1/" + model + variant, args,
                    model + (model == "ptm" ? " (fitted to a relief of concrete_512.png)" : " (default analysis of concrete_512.png)") +
                        ", " + (solid ? "solid" : "2D") + ", 1x1 " + (png ? "PNG" : "EXR") + ", " + program);
            }
        }

    if (console) {
        StartupReporter reporter(isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_ColorTabular
                                                       : benchmark::ConsoleReporter::OO_Tabular);
        benchmark::RunSpecifiedBenchmarks(&reporter);
    } else {
        benchmark::RunSpecifiedBenchmarks();
    }
    benchmark::Shutdown();
    std::error_code error;
    fs::remove_all(folder, error);
    return 0;
}
