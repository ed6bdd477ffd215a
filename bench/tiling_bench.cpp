// Tiling and blending: filtered evaluations per second through stochtex::render() (1 and 2
// threads), for the three outputs, next to point sampling. A 512×512 raster at 4 exemplar
// pixels per pixel (the footprint estimator's 2×2 taps at pyramid level 1); Mpix/s = million
// filtered evaluations per second.
#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>
#include <stochtex/models/tiling.h>

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

namespace {

using namespace stochtex;

const TextureDescription& description(const std::string& kind)
{
    static std::map<std::string, TextureDescription> cache;
    auto found = cache.find(kind);
    if (found != cache.end()) return found->second;
    const Image photo = read_image_linear(STOCHTEX_SOURCE_DIR "/data/exemplars/concrete_512.png");
    TilingSourceOptions source;
    TextureDescription d;
    if (kind == "colour") {
        AnalysisOptions options;
        options.model = "tiling";
        options.histogram = HistogramMode::on;
        d = analyze(photo, options);
    } else if (kind == "colour_map") {
        d = colour_mapped_texture(photo, photo, "rgb", source);
    } else {
        d = phasor_texture("phasor-square", 1.0 / 16, source);
    }
    return cache.emplace(kind, d).first->second;
}

void Render(benchmark::State& state, const std::string& kind, bool filter)
{
    const std::unique_ptr<Texture> texture = make_texture(description(kind));
    RenderSettings settings;
    settings.width = settings.height = 512;
    settings.units_per_pixel = 4 / texture->description().pixels_per_unit;
    settings.filter = filter;
    settings.threads = int(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(render(*texture, settings).pixels.data());
    state.counters["Mpix/s"] =
        benchmark::Counter(double(settings.width) * settings.height * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
    state.SetLabel(kind + (filter ? ", filtered" : ", point-sampled") + ", " + std::to_string(state.range(0)) + " thread(s)");
}

BENCHMARK_CAPTURE(Render, colour_filtered, std::string("colour"), true)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Render, colour_map_filtered, std::string("colour_map"), true)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Render, phasor_filtered, std::string("phasor"), true)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Render, colour_point, std::string("colour"), false)->Arg(1)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
