// stochtex — the cost of `analyze --model auto` (stochtex/analysis.h) against the analyses it
// runs, measured in the same run:
//
//   Analyze/auto/<n>     every analysable model fitted, rendered (≤ 384²) and scored against
//                        an n² photo crop (gravel.png, else the committed exemplar); goal ≤ 5 s at 512²
//   Analyze/<model>/<n>  that model's analysis alone (wavelet: the CLI's default before auto)
//
// After the table: auto's time as a multiple of the wavelet analysis and of the sum of the
// single-model analyses (the rest is rendering and scoring).
#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/model.h>

#include <benchmark/benchmark.h>

#include "median_reporter.h"
#include "photo_crop.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace stochtex;

constexpr int photo_size = 512;


void bm_analyze(benchmark::State& state, const Image* photo, std::string model)
{
    AnalysisOptions options;
    options.model = model;
    // What `stex analyze` asks for by default: with auto, the colour modes and joint colour left open.
    options.try_colour_modes = options.try_joint_colour = model == automatic_model;
    std::string chosen;
    for (auto _ : state) chosen = analyze(*photo, options).model;
    state.counters["analyses/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.SetLabel(std::to_string(photo->width) + "x" + std::to_string(photo->height) + ", stex analyze's defaults" +
                   (model == automatic_model ? ", chose " + chosen + ", goal <= 5 s" : std::string()));
}

class ComparisonReporter : public stochtex::bench::MedianReporter {
public:
    explicit ComparisonReporter(std::vector<std::string> models) : MedianReporter({"analyses/s"}), models_(std::move(models)) {}

    void Finalize() override
    {
        MedianReporter::Finalize();
        const std::string size = "/" + std::to_string(photo_size);
        const Entry* automatic = find("Analyze/auto" + size);
        const Entry* wavelet = find("Analyze/wavelet" + size);
        if (!automatic || !wavelet) return;
        double sum_of_fits = 0;
        for (const std::string& model : models_)
            if (const Entry* entry = find("Analyze/" + model + size)) sum_of_fits += 1 / entry->rate;
        std::printf("\nauto at %d²: %.2f s median = %.1f× the wavelet analysis (%.2f s), %.2f× the sum of the %zu single-model analyses (%.2f s)\n",
                    photo_size, 1 / automatic->rate, wavelet->rate / automatic->rate, 1 / wavelet->rate,
                    (1 / automatic->rate) / sum_of_fits, models_.size(), sum_of_fits);
    }

private:
    std::vector<std::string> models_;
};

}  // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    static Image photo;
    static std::string source;
    try {
        const fs::path shared = fs::path(STOCHTEX_SHARED_DIR) / "exemplars" / "gravel.png";
        const fs::path path =
            fs::exists(shared) ? shared : fs::path(STOCHTEX_SOURCE_DIR) / "data" / "exemplars" / "concrete_512.png";
        source = path.filename().string();
        photo = stochtex::bench::top_left_crop(read_image_linear(path.string()), photo_size);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "model_choice_bench: setup failed: %s\n", e.what());
        return 1;
    }
    std::printf("photo: %s (top-left %d²)\n", source.c_str(), photo_size);
    static std::vector<std::string> models;
    for (const ModelInfo* model : registered_model_infos())
        if (model->capabilities.analysis) models.push_back(model->name);
    std::vector<std::string> all{automatic_model};
    all.insert(all.end(), models.begin(), models.end());
    for (const std::string& model : all)
        benchmark::RegisterBenchmark(("Analyze/" + model + "/" + std::to_string(photo_size)).c_str(), bm_analyze, &photo, model)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    ComparisonReporter reporter(models);
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}
