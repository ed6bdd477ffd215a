// Tiling and blending, and the ptm model: filtered evaluations per second through
// stochtex::render() (1 and 2 threads), each raster path next to its scalar reference — the
// same texture evaluated one eval() per pixel (Texture's default batch loop) — in the same run.
//
//   Raster/<kind>/threads:N   render(): the model's eval_region (rows share the tap plan, the
//                              triangle grid's vertices, the tabulated colour maps; tiling: the
//                              single-precision packed estimator, TilingRaster)
//   Double/<kind>/threads:N   tiling only: the previous raster path, measured in the same run —
//                              the double estimator (TilingNoise::footprint_estimate with the plan
//                              and vertex cache shared along rows) and the reference colour-map
//                              lookup (ColourMapFilter::filtered)
//   Point/<kind>/threads:N    the same raster, one eval() per pixel (the reference)
//   OneTap/<kind>/threads:N   tiling only: the raster of the texture with filter_taps 1 (one tap
//                              per footprint, the paper's single per-texel estimate) instead of the
//                              default 2×2 — what the default's accuracy costs (docs/models/tiling.md)
//   Part/<kind>/...           one thread, per pixel: the filtered moments alone, the colour alone
//                              (where the time goes)
//
// A 512×512 raster at 4 exemplar pixels per pixel (the footprint estimator's 2×2 taps at pyramid
// level 1), full colour, filtered; colour is concrete_512.png analysed with histograms on,
// colour_map the same photo twice through the "rgb" map (a perfectly correlated pair, read on
// tables pre-blurred along the diagonal), colour_map_pair the photo and its transpose (nearly
// uncorrelated: the general line quadrature), phasor "phasor-square" at 1/16 cycle per
// pixel (covariance filtering), ptm 256² random lrgb reflectance functions lit 40° off the
// normal (ptm_unbounded: the same, tiled and blended).
// Mpix/s = million filtered evaluations per second of wall time; Mpix/cpu-s = per second of CPU
// time of the whole process (what a core does while it runs: the figure to read on a machine
// shared with other jobs). After the table, each raster path's speed-up over its reference.
#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>
#include <stochtex/models/tiling.h>

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include "median_reporter.h"
#include "photo_crop.h"
#include "point_by_point.h"
#include "colour/tabulated_colour_mapping.h"
#include "models/tiling/tiling_texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

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
    } else if (kind == "colour_map_pair") {
        d = colour_mapped_texture(photo, bench::transposed(photo), "rgb", source);
    } else if (kind == "phasor") {
        d = phasor_texture("phasor-square", 1.0 / 16, source);
    } else {
        // 256² texels of random lrgb reflectance functions (a bright constant term, small slopes),
        // lit from 40° off the normal; "ptm_unbounded" tiles and blends them over the triangle grid.
        PtmMaps maps;
        maps.colour = PtmColour::lrgb;
        maps.coefficients = Image(256, 256, ptm_channel_count(maps.colour));
        std::mt19937 random(7);
        std::uniform_real_distribution<float> unit(0, 1);
        std::normal_distribution<float> normal(0, 1);
        for (std::size_t i = 0; i < maps.coefficients.pixel_count(); ++i) {
            float* texel = &maps.coefficients.pixels[i * maps.coefficients.channels];
            texel[0] = 1.0f + 0.2f * unit(random);
            for (int k = 1; k < 6; ++k) texel[k] = 0.08f * normal(random);
            for (int c = 0; c < 3; ++c) texel[6 + c] = 0.7f + 0.6f * unit(random);
        }
        d = make_ptm_description(std::move(maps), {0.6428, 0, 0.7660});
        d.parameters.get<PtmParameters>().unbounded = kind == "ptm_unbounded";
    }
    return cache.emplace(kind, d).first->second;
}

/// The previous tiling raster path (double estimator, reference colour-map lookup): the "before"
/// of docs/models/tiling.md's speed table, measured in the same run as the packed path.
class DoublePath final : public Texture {
public:
    explicit DoublePath(const TilingTexture& inner) : Texture(inner.description()), inner_(inner) {}
    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override { return colour(inner_.moments(uv, footprint)); }
    Rgb eval_solid(const SurfacePoint& point) const override { return inner_.eval_solid(point); }
    Rgb mean() const override { return inner_.mean(); }
    void eval_region(const RasterRegion& region, const RgbOutput& out) const override
    {
        const double ppu = description().pixels_per_unit;
        const TapPlan plan = inner_.noise().plan(region.footprint.scaled(ppu), inner_.options().sampling);
        TileCache cache;
        for (int j = 0; j < region.height; ++j)
            for (int i = 0; i < region.width; ++i)
                out.set(std::size_t(j) * region.width + i,
                        colour(inner_.noise().footprint_estimate(region.u(i) * ppu, region.v(j) * ppu, plan, cache)));
    }

private:
    Rgb colour(const Moments& m) const
    {
        const ColourMapFilter* map = inner_.colour_map_filter();
        if (!map) return inner_.colour(m);
        return map->filtered(m.mean[0], m.mean[1], {m.moment(0, 0), m.moment(0, 1), m.moment(1, 1)}, inner_.options().colour_map);
    }
    const TilingTexture& inner_;
};

using stochtex::bench::PointByPoint;  // the reference: eval() once per pixel

RenderSettings settings_for(const Texture& texture, int threads)
{
    RenderSettings settings;
    settings.width = settings.height = 512;
    settings.units_per_pixel = 4 / texture.description().pixels_per_unit;
    settings.filter = true;
    settings.threads = threads;
    return settings;
}

std::string label(const std::string& kind, const std::string& path, int threads)
{
    const TextureDescription& d = description(kind);
    return kind + " (" + d.model + "), 512², 4 exemplar px per pixel, filtered, " + path + ", " + std::to_string(threads) +
           " thread(s)";
}

/// CPU seconds of the whole process (every thread): on a machine shared with other jobs, pixels
/// per CPU second say what a core does when it runs, whatever the wall clock waited.
double process_cpu_seconds()
{
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) + 1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

enum class Path { raster, double_path, point, one_tap };

void Render(benchmark::State& state, const std::string& kind, Path path)
{
    TextureDescription d = description(kind);
    if (path == Path::one_tap) d.parameters.get<TilingParameters>().filter_taps = 1;
    const std::unique_ptr<Texture> texture = make_texture(d);
    const PointByPoint reference(*texture);
    const auto* tiling = dynamic_cast<const TilingTexture*>(texture.get());
    std::unique_ptr<DoublePath> previous;
    if (tiling) previous = std::make_unique<DoublePath>(*tiling);
    if (path == Path::double_path && !previous) {
        state.SkipWithError("not a tiling texture");
        return;
    }
    const Texture& evaluated = path == Path::raster || path == Path::one_tap ? *texture : path == Path::point ? static_cast<const Texture&>(reference) : *previous;
    const RenderSettings settings = settings_for(*texture, int(state.range(0)));
    const double cpu_start = process_cpu_seconds();
    for (auto _ : state) benchmark::DoNotOptimize(render(evaluated, settings).pixels.data());
    const double pixels = double(settings.width) * settings.height;
    state.counters["Mpix/s"] = benchmark::Counter(pixels * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["Mpix/cpu-s"] = pixels * 1e-6 * double(state.iterations()) / std::max(1e-9, process_cpu_seconds() - cpu_start);
    state.SetLabel(label(kind, path == Path::raster ? "eval_region" : path == Path::one_tap ? "eval_region, 1 tap" : path == Path::point ? "eval() per pixel" : "previous double path",
                         int(state.range(0))));
}

/// Where the time of one tiling eval() goes: the filtered moments, then their colour.
void Part(benchmark::State& state, const std::string& kind, bool colour_only)
{
    const TilingTexture texture(description(kind));
    const RenderSettings settings = settings_for(texture, 1);
    const Footprint2D footprint = Footprint2D::square(settings.units_per_pixel);
    const int n = 4096;
    std::vector<Moments> moments(n);
    for (int i = 0; i < n; ++i)
        moments[i] = texture.moments({(i % 64 + 0.5) * settings.units_per_pixel, (i / 64 + 0.5) * settings.units_per_pixel},
                                     footprint);
    for (auto _ : state)
        for (int i = 0; i < n; ++i) {
            if (colour_only)
                benchmark::DoNotOptimize(texture.colour(moments[i]));
            else
                benchmark::DoNotOptimize(texture.raster_moments(
                    {(i % 64 + 0.5) * settings.units_per_pixel, (i / 64 + 0.5) * settings.units_per_pixel}, footprint));
        }
    state.counters["Mpix/s"] = benchmark::Counter(n * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
    state.SetLabel(kind + ": " + (colour_only ? "colour() of given moments" : "raster_moments() (taps, grid, packed pyramid; plan per call)") +
                   ", 1 thread");
}

/// The colour step alone: exact (12-node Gauss–Hermite per channel), tabulated item by item, or
/// tabulated by rows of 64 (TabulatedColourMapping's row form, what eval_region runs; the same bits).
enum class ColourStepForm { exact, tabulated, row };
void ColourStep(benchmark::State& state, ColourStepForm form)
{
    const TilingTexture texture(description("colour"));
    const TabulatedColourMapping mapping(description("colour"), {1, 1, 1});
    const RenderSettings settings = settings_for(texture, 1);
    const Footprint2D footprint = Footprint2D::square(settings.units_per_pixel);
    const int n = 4096, row = 64;
    std::vector<std::array<double, 6>> inputs(n);
    std::vector<double> planar(6 * std::size_t(n));  // [field · n + i]
    for (int i = 0; i < n; ++i) {
        const Moments m = texture.moments({(i % 64 + 0.5) * settings.units_per_pixel, (i / 64 + 0.5) * settings.units_per_pixel}, footprint);
        for (int c = 0; c < 3; ++c) inputs[i][c] = m.mean[c], inputs[i][3 + c] = std::sqrt(std::max(0.0, m.moment(c, c)));
        for (int f = 0; f < 6; ++f) planar[std::size_t(f) * n + i] = inputs[i][f];
    }
    std::vector<float> rgb(3 * std::size_t(n));
    for (auto _ : state) {
        if (form == ColourStepForm::row) {
            for (int first = 0; first < n; first += row) {
                auto at = [&](int f) { return planar.data() + std::size_t(f) * n + first; };
                mapping.to_rgb({at(0), at(1), at(2)}, {at(3), at(4), at(5)}, row, RgbOutput::interleaved(rgb.data()), std::size_t(first));
            }
            benchmark::DoNotOptimize(rgb.data());
            continue;
        }
        for (const auto& in : inputs) {
            const std::array<double, 3> z{in[0], in[1], in[2]}, spread{in[3], in[4], in[5]};
            benchmark::DoNotOptimize(form == ColourStepForm::tabulated ? mapping.to_rgb(z, spread) : mapping.exact().to_rgb(z, spread));
        }
    }
    state.counters["Mpix/s"] = benchmark::Counter(n * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
    const char* what = form == ColourStepForm::exact ? "exact (Gauss–Hermite, 12 nodes)" : form == ColourStepForm::tabulated ? "tabulated, item by item" : "tabulated, rows of 64";
    state.SetLabel(std::string("colour: histogram maps ") + what + ", 1 thread");
}
BENCHMARK_CAPTURE(ColourStep, exact, ColourStepForm::exact)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(ColourStep, tabulated, ColourStepForm::tabulated)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(ColourStep, tabulated_row, ColourStepForm::row)->UseRealTime()->Unit(benchmark::kMicrosecond);

#define STOCHTEX_RENDER(kind)                                                                                           \
    BENCHMARK_CAPTURE(Render, Raster/kind, std::string(#kind), Path::raster)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond); \
    BENCHMARK_CAPTURE(Render, Point/kind, std::string(#kind), Path::point)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond)
#define STOCHTEX_RENDER_PREVIOUS(kind)                                                                                  \
    BENCHMARK_CAPTURE(Render, Double/kind, std::string(#kind), Path::double_path)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond)

STOCHTEX_RENDER(colour);
BENCHMARK_CAPTURE(Render, OneTap/colour, std::string("colour"), Path::one_tap)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Render, OneTap/phasor, std::string("phasor"), Path::one_tap)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
STOCHTEX_RENDER_PREVIOUS(colour);
STOCHTEX_RENDER(colour_map);
STOCHTEX_RENDER_PREVIOUS(colour_map);
STOCHTEX_RENDER(colour_map_pair);
STOCHTEX_RENDER(phasor);
STOCHTEX_RENDER_PREVIOUS(phasor);
STOCHTEX_RENDER(ptm);
STOCHTEX_RENDER(ptm_unbounded);
BENCHMARK_CAPTURE(Part, colour/moments, std::string("colour"), false)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Part, colour/colour, std::string("colour"), true)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Part, colour_map/moments, std::string("colour_map"), false)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Part, colour_map/colour, std::string("colour_map"), true)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Part, phasor/colour, std::string("phasor"), true)->UseRealTime()->Unit(benchmark::kMicrosecond);

class ComparingReporter : public bench::MedianReporter {
public:
    explicit ComparingReporter(OutputOptions options) : MedianReporter({"Mpix/s"}, options), cpu_(std::make_unique<CpuRates>()) {}

    void ReportRuns(const std::vector<Run>& reports) override
    {
        MedianReporter::ReportRuns(reports);
        for (const Run& run : reports) {
            if (run.error_occurred || (run.run_type == Run::RT_Aggregate && run.aggregate_name != "median")) continue;
            const auto counter = run.counters.find("Mpix/cpu-s");
            if (counter != run.counters.end()) cpu_->rates[run.run_name.str()] = counter->second.value;
        }
    }

    void Finalize() override
    {
        ConsoleReporter::Finalize();
        std::printf("\nComparison (medians of this run; Mpix/s of wall time, and per CPU second):\n");
        for (const auto& [name, entry] : medians()) {
            std::printf("  %-48s %9.3f", name.c_str(), entry.rate);
            const auto cpu = cpu_->rates.find(name);
            if (cpu != cpu_->rates.end()) std::printf("  (%7.3f per CPU-s)", cpu->second);
            if (name.rfind("Render/Raster/", 0) == 0) {
                // The speed-up over a reference of the same kind, in wall and CPU time.
                auto against = [&](const char* path, const char* what) {
                    const std::string twin = std::string("Render/") + path + "/" + name.substr(std::strlen("Render/Raster/"));
                    const Entry* reference = find(twin);
                    const auto reference_cpu = cpu_->rates.find(twin);
                    if (reference && reference->rate > 0) std::printf("  %6.2fx %s", entry.rate / reference->rate, what);
                    if (cpu != cpu_->rates.end() && reference_cpu != cpu_->rates.end() && reference_cpu->second > 0)
                        std::printf(" (%.2fx per CPU-s)", cpu->second / reference_cpu->second);
                };
                against("Point", "eval() per pixel");
                against("Double", "previous path");
            }
            std::printf("\n");
        }
        std::fflush(stdout);
    }

private:
    struct CpuRates {
        std::map<std::string, double> rates;
    };
    std::unique_ptr<CpuRates> cpu_;
};

}  // namespace

int main(int argc, char** argv)
{
    bool console = true;
    for (int i = 1; i < argc; ++i)
        if (std::strncmp(argv[i], "--benchmark_format=", 19) == 0) console = std::strcmp(argv[i] + 19, "console") == 0;
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    if (console) {
        ComparingReporter reporter(benchmark::ConsoleReporter::OO_Defaults);
        benchmark::RunSpecifiedBenchmarks(&reporter);
    } else {
        benchmark::RunSpecifiedBenchmarks();
    }
    benchmark::Shutdown();
    return 0;
}
