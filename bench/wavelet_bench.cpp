// stochtex — benchmarks of the hot paths, with the references they compete with, in one run.
//
//   Analyze/...      analysis of a 512² RGB photo (top-left crop of exemplars/dirt.png); goal ≤ 30 ms
//   Render2D/...     512×512 filtered renders through stochtex::render(), 1 and 2 threads; hist:on,
//                    hist:off, and hist:on/joint:on (joint colour: the chroma curves' cost)
//   Render3D/...     the same raster as a solid (3D) texture slice
//   Raster2D/...     the same 512² raster evaluated on the calling thread, in 8-row bands like
//   Raster3D/...     render(): path:simd is the model's raster method (Texture::eval_region /
//                    eval_solid_region, vectorised), path:point the scalar reference in the same
//                    run (Texture's default loop over eval() / eval_solid(), one pixel at a time);
//                    rates from CPU time, so they hold on a loaded machine. Values are identical.
//   Points3D/...     512² scattered surface points (a position-map bake of a sphere), each with its
//                    own footprint: path:batch is Texture::eval_solid_points (vectorised), path:point
//                    the scalar loop over eval_solid(), calling thread, CPU time. Values are identical.
//   Ref/Bilinear...  a plain bilinear lookup of a baked 512² RGB float image (what a baked texture costs)
//   Ref/Perlin3D...  libnoise 3D Perlin, 3 evaluations per pixel (one per colour channel), as many
//                    octaves as the texture has bands (only when libnoise-dev is installed)
//
// Every benchmark reports "Mpix/s" (output pixels per second of wall-clock time; for Analyze,
// photo pixels) and names its model parameters (bands, histogram on/off, threads) in its name
// and label. Run it through bench/run.sh:
//   wavelet_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true --benchmark_min_time=0.25
// After the table a short comparison of the medians (wavelet vs the references) is printed.
#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>
#include <stochtex/models/wavelet_parameters.h>

#include <benchmark/benchmark.h>

#include "median_reporter.h"
#include "photo_crop.h"
#include "sphere_points.h"

#ifdef STOCHTEX_HAVE_LIBNOISE
#include <libnoise/noise.h>
#endif

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using stochtex::Image;

constexpr int exemplar_size = 512;  // analysis input: 512² RGB
constexpr int raster_size = 512;    // every synthesis benchmark fills a 512×512 raster

// ---------------------------------------------------------------------------------------------
// The exemplar: top-left 512² of dirt.png, else a project exemplar, else synthetic noise.


// Deterministic coloured noise with structure at several scales (used only without exemplars).
Image synthetic_exemplar(int size)
{
    Image image(size, size, 3);
    std::uint64_t state = 0x9e3779b97f4a7c15ull;
    auto next = [&] {
        state ^= state << 13, state ^= state >> 7, state ^= state << 17;
        return double(state >> 11) * (1.0 / 9007199254740992.0);
    };
    std::vector<double> white(std::size_t(size) * size);
    for (double& v : white) v = next();
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double sum = 0;  // a 5×5 box blur of the white noise plus a little of the raw noise
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx)
                    sum += white[std::size_t((y + dy + size) % size) * size + (x + dx + size) % size];
            const double v = 0.6 * sum / 25 + 0.4 * white[std::size_t(y) * size + x];
            const double wave = 0.1 * std::sin(x * 0.05) * std::cos(y * 0.031);
            image.at(x, y, 0) = float(0.25 + 0.3 * v + wave);
            image.at(x, y, 1) = float(0.18 + 0.25 * v + 0.5 * wave);
            image.at(x, y, 2) = float(0.12 + 0.2 * v);
        }
    return image;
}

struct Exemplar {
    Image image;
    std::string source;  // shown in the analysis label
};

Exemplar load_exemplar()
{
    std::vector<fs::path> candidates{fs::path(STOCHTEX_SHARED_DIR) / "exemplars" / "dirt.png"};
    std::error_code error;
    const fs::path local = fs::path(STOCHTEX_SOURCE_DIR) / "data" / "exemplars";
    if (fs::is_directory(local, error)) {
        std::vector<fs::path> pngs;
        for (const auto& entry : fs::directory_iterator(local, error))
            if (entry.path().extension() == ".png") pngs.push_back(entry.path());
        std::sort(pngs.begin(), pngs.end());
        candidates.insert(candidates.end(), pngs.begin(), pngs.end());
    }
    for (const fs::path& path : candidates) {
        if (!fs::is_regular_file(path, error)) continue;
        try {
            Image cropped = stochtex::bench::top_left_crop(stochtex::read_image_linear(path.string()), exemplar_size);
            return {std::move(cropped), path.filename().string()};
        } catch (const std::exception& e) {
            std::fprintf(stderr, "wavelet_bench: cannot use %s (%s)\n", path.string().c_str(), e.what());
        }
    }
    return {synthetic_exemplar(exemplar_size), "synthetic-noise"};
}

// ---------------------------------------------------------------------------------------------
// Model parameters for names and labels.

int band_count(const stochtex::TextureDescription& description)
{
    return description.parameters.holds<stochtex::WaveletParameters>() ? int(description.parameters.get<stochtex::WaveletParameters>().band_weights[0].size()) : 0;
}

std::string histogram_state(const stochtex::TextureDescription& description)
{
    int enabled = 0;
    for (const auto& map : description.histograms) enabled += map.enabled() ? 1 : 0;
    if (enabled == 0) return "off";
    if (enabled == 3) return "on";
    return "on" + std::to_string(enabled) + "of3";
}

void set_pixel_rate(benchmark::State& state, double pixels_per_iteration)
{
    state.counters["Mpix/s"] =
        benchmark::Counter(double(state.iterations()) * pixels_per_iteration / 1e6, benchmark::Counter::kIsRate);
}

// ---------------------------------------------------------------------------------------------
// The texture under test, analysed once (histogram on and off) before any timing.

struct Model {
    stochtex::TextureDescription description;
    std::unique_ptr<stochtex::Texture> texture;
    std::string histogram;  // "on" / "off", and "on/joint:on" with joint colour
};

stochtex::AnalysisOptions analysis_options(const Exemplar& exemplar, stochtex::HistogramMode mode, bool joint_colour = false)
{
    stochtex::AnalysisOptions options;
    options.histogram = mode;
    options.joint_colour = joint_colour;
    options.source_name = exemplar.source;
    return options;
}

Model make_model(const Exemplar& exemplar, stochtex::HistogramMode mode, bool joint_colour = false)
{
    Model model;
    model.description = stochtex::analyze(exemplar.image, analysis_options(exemplar, mode, joint_colour));
    model.texture = stochtex::make_texture(model.description);
    model.histogram = histogram_state(model.description);
    if (model.description.chroma_given_brightness.enabled()) model.histogram += "/joint:on";
    return model;
}

stochtex::RenderSettings raster_settings(const Model& model, bool solid, int threads)
{
    stochtex::RenderSettings settings;
    settings.width = settings.height = raster_size;
    settings.units_per_pixel = 1.0 / model.description.pixels_per_unit;  // the photo's own scale
    settings.origin_u = 0.25;
    settings.origin_v = 0.5;
    settings.solid = solid;
    settings.z = 0.375;
    settings.filter = true;
    settings.threads = threads;
    return settings;
}

// ---------------------------------------------------------------------------------------------
// Benchmarks.

void bm_analyze(benchmark::State& state, const Exemplar* exemplar, stochtex::HistogramMode mode)
{
    const auto options = analysis_options(*exemplar, mode);
    stochtex::TextureDescription description;
    for (auto _ : state) {
        description = stochtex::analyze(exemplar->image, options);
        benchmark::DoNotOptimize(description);
    }
    set_pixel_rate(state, double(exemplar->image.pixel_count()));
    state.SetLabel(exemplar->source + " " + std::to_string(exemplar->image.width) + "x" +
                   std::to_string(exemplar->image.height) + ", bands=" + std::to_string(band_count(description)) +
                   ", hist=" + stochtex::to_string(mode) + "->" + histogram_state(description) +
                   ", goal<=30ms");
}

void bm_render(benchmark::State& state, const Model* model, bool solid, int threads)
{
    const auto settings = raster_settings(*model, solid, threads);
    for (auto _ : state) {
        Image image = stochtex::render(*model->texture, settings);
        benchmark::DoNotOptimize(image.pixels.data());
        benchmark::ClobberMemory();
    }
    set_pixel_rate(state, double(settings.width) * settings.height);
    state.SetLabel(std::string(solid ? "3D" : "2D") + " filtered, bands=" + std::to_string(band_count(model->description)) +
                   ", hist=" + model->histogram + ", threads=" + std::to_string(threads));
}

// One thread, the model's raster method or the point loop (the scalar reference) over the same
// 8-row bands as render().
void bm_raster(benchmark::State& state, const Model* model, bool solid, bool simd)
{
    const auto settings = raster_settings(*model, solid, 1);
    constexpr int rows = 8;
    std::vector<float> out(std::size_t(settings.width) * rows * 3);
    const stochtex::Texture& texture = *model->texture;
    for (auto _ : state) {
        for (int y0 = 0; y0 < settings.height; y0 += rows) {
            stochtex::RasterRegion region;
            region.origin_u = settings.origin_u, region.origin_v = settings.origin_v;
            region.du = region.dv = settings.units_per_pixel;
            region.y0 = y0, region.width = settings.width, region.height = std::min(rows, settings.height - y0);
            region.footprint = {region.du, 0, 0, region.dv};
            const auto rgb = stochtex::RgbOutput::interleaved(out.data());
            if (solid) {
                if (simd) texture.eval_solid_region({region, settings.z}, rgb);
                else texture.Texture::eval_solid_region({region, settings.z}, rgb);
            } else {
                if (simd) texture.eval_region(region, rgb);
                else texture.Texture::eval_region(region, rgb);
            }
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    set_pixel_rate(state, double(settings.width) * settings.height);
    state.SetLabel(std::string(solid ? "3D" : "2D") + " filtered, bands=" + std::to_string(band_count(model->description)) +
                   ", hist=" + model->histogram + ", " + (simd ? "raster method (SIMD)" : "point loop (scalar reference)") +
                   ", calling thread");
}

// Scattered surface points (sphere_points.h): path:batch is the model's eval_solid_points
// (vectorised), path:point the scalar reference (Texture's default loop over eval_solid()), one
// 512-point row per call as bake.cpp does; calling thread.
void bm_surface_points(benchmark::State& state, const Model* model, bool batch)
{
    const std::vector<stochtex::SurfacePoint> points =
        stochtex::bench::sphere_points(raster_size, model->description.pixels_per_unit);
    std::vector<float> planes;
    for (auto _ : state) {
        stochtex::bench::eval_surface_rows(*model->texture, points, raster_size, batch, planes);
        benchmark::DoNotOptimize(planes.data());
        benchmark::ClobberMemory();
    }
    set_pixel_rate(state, double(points.size()));
    state.SetLabel(std::string("surface points of a sphere, filtered, bands=") + std::to_string(band_count(model->description)) +
                   ", hist=" + model->histogram + ", " + (batch ? "eval_solid_points (SIMD)" : "point loop (scalar reference)") +
                   ", calling thread");
}

// Reference (a): bilinear lookup, repeat wrap, of a baked 512² RGB float image, on one thread.
// The lookups are offset by a non-integer number of texels so every one really interpolates.
inline void bilinear_repeat(const Image& baked, double u, double v, float* out)
{
    const int w = baked.width, h = baked.height;
    const double x = u * w - 0.5, y = v * h - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const float tx = float(x - fx), ty = float(y - fy);
    int x0, y0;
    if ((w & (w - 1)) == 0 && (h & (h - 1)) == 0) {  // power-of-two sizes wrap with a mask
        x0 = int(fx) & (w - 1), y0 = int(fy) & (h - 1);
    } else {
        x0 = int(fx) % w, y0 = int(fy) % h;
        if (x0 < 0) x0 += w;
        if (y0 < 0) y0 += h;
    }
    const int x1 = x0 + 1 == w ? 0 : x0 + 1, y1 = y0 + 1 == h ? 0 : y0 + 1;
    const float* p00 = &baked.pixels[(std::size_t(y0) * w + x0) * 3];
    const float* p10 = &baked.pixels[(std::size_t(y0) * w + x1) * 3];
    const float* p01 = &baked.pixels[(std::size_t(y1) * w + x0) * 3];
    const float* p11 = &baked.pixels[(std::size_t(y1) * w + x1) * 3];
    for (int c = 0; c < 3; ++c) {
        const float top = p00[c] + tx * (p10[c] - p00[c]);
        const float bottom = p01[c] + tx * (p11[c] - p01[c]);
        out[c] = top + ty * (bottom - top);
    }
}

void bm_bilinear_baked(benchmark::State& state, const Image* baked)
{
    Image out(raster_size, raster_size, 3);
    const double step = 1.0 / baked->width, origin_u = 0.3137, origin_v = 0.7071;
    for (auto _ : state) {
        for (int y = 0; y < raster_size; ++y) {
            const double v = origin_v + (y + 0.5) * step;
            float* row = &out.pixels[std::size_t(y) * raster_size * 3];
            for (int x = 0; x < raster_size; ++x) bilinear_repeat(*baked, origin_u + (x + 0.5) * step, v, row + 3 * x);
        }
        benchmark::DoNotOptimize(out.pixels.data());
        benchmark::ClobberMemory();
    }
    set_pixel_rate(state, double(raster_size) * raster_size);
    state.SetLabel("baked " + std::to_string(baked->width) + "x" + std::to_string(baked->height) +
                   " RGB float, repeat wrap, threads=1");
}

#ifdef STOCHTEX_HAVE_LIBNOISE
// Reference (b): libnoise 3D Perlin (fBm of `octaves` octaves), 3 evaluations per pixel.
void bm_perlin3d(benchmark::State& state, int octaves)
{
    noise::module::Perlin perlin;
    perlin.SetOctaveCount(std::clamp(octaves, 1, noise::module::PERLIN_MAX_OCTAVE));
    perlin.SetFrequency(1.0);
    perlin.SetLacunarity(2.0);
    perlin.SetPersistence(0.5);
    perlin.SetNoiseQuality(noise::QUALITY_STD);
    // Finest octave at one cycle per pixel, like the finest wavelet band.
    const double step = 1.0 / std::ldexp(1.0, std::max(0, octaves - 1));
    const double channel_offset[3][3] = {{0.1, 0.2, 0.3}, {17.4, 5.9, 3.3}, {41.7, 29.2, 11.8}};
    std::vector<float> out(std::size_t(raster_size) * raster_size * 3);
    for (auto _ : state) {
        for (int y = 0; y < raster_size; ++y) {
            const double v = (y + 0.5) * step;
            for (int x = 0; x < raster_size; ++x) {
                const double u = (x + 0.5) * step;
                float* px = &out[(std::size_t(y) * raster_size + x) * 3];
                for (int c = 0; c < 3; ++c)
                    px[c] = float(perlin.GetValue(u + channel_offset[c][0], v + channel_offset[c][1],
                                                  0.375 + channel_offset[c][2]));
            }
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    set_pixel_rate(state, double(raster_size) * raster_size);
    state.SetLabel("libnoise Perlin 3D, octaves=" + std::to_string(perlin.GetOctaveCount()) +
                   ", 3 evals/pixel, threads=1");
}
#endif

// ---------------------------------------------------------------------------------------------
// Console output plus a comparison of the medians at the end.

class ComparingReporter : public stochtex::bench::MedianReporter {
public:
    explicit ComparingReporter(OutputOptions options) : MedianReporter({"Mpix/s"}, options) {}

    void Finalize() override
    {
        ConsoleReporter::Finalize();
        const Entry* bilinear = find("Ref/BilinearBaked");
        const Entry* perlin = find("Ref/Perlin3D");
        int width = 34;
        for (const auto& [name, entry] : medians()) width = std::max(width, int(name.size()));
        bool header = false;
        for (const auto& [name, entry] : medians()) {
            if (name.rfind("Render", 0) != 0 && name.rfind("Raster", 0) != 0) continue;
            if (!header) {
                std::printf("\nComparison (median Mpix/s of this run; x = speed relative to the reference):\n");
                if (bilinear) std::printf("  %-*s %9.2f Mpix/s  (%s)\n", width, "reference: bilinear baked", bilinear->rate, bilinear->label.c_str());
                if (perlin) std::printf("  %-*s %9.2f Mpix/s  (%s)\n", width, "reference: libnoise Perlin 3D x3", perlin->rate, perlin->label.c_str());
                header = true;
            }
            std::printf("  %-*s %9.2f Mpix/s", width, name.c_str(), entry.rate);
            if (name.rfind("Raster", 0) == 0 && name.find("/path:simd") != std::string::npos) {
                std::string reference_name = name;
                reference_name.replace(reference_name.find("/path:simd"), 10, "/path:point");
                if (const Entry* reference = find(reference_name)) std::printf("  %7.2fx point loop", entry.rate / reference->rate);
            }
            if (bilinear) std::printf("  %8.4fx bilinear", entry.rate / bilinear->rate);
            if (perlin) std::printf("  %7.3fx Perlin", entry.rate / perlin->rate);
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

    // Everything below runs before any timing: it also builds the shared noise tiles.
    static Exemplar exemplar;
    static Model hist_on, hist_off, joint;
    static Image baked;
    try {
        exemplar = load_exemplar();
        hist_on = make_model(exemplar, stochtex::HistogramMode::on);
        hist_off = make_model(exemplar, stochtex::HistogramMode::off);
        // Joint colour's cost: its curves per pixel, Gauss–Hermite averaged where bands fade.
        joint = make_model(exemplar, stochtex::HistogramMode::on, true);
        baked = stochtex::render(*hist_on.texture, raster_settings(hist_on, false, 0));
        stochtex::render(*hist_on.texture, raster_settings(hist_on, true, 0));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "wavelet_bench: setup failed: %s\n", e.what());
        return 1;
    }
    const int bands = band_count(hist_on.description);
    const std::string size = std::to_string(raster_size) + "x" + std::to_string(raster_size);

    for (auto mode : {stochtex::HistogramMode::automatic}) {
        const std::string name = "Analyze/" + std::to_string(exemplar.image.width) + "x" +
                                 std::to_string(exemplar.image.height) + "/hist:" + stochtex::to_string(mode);
        benchmark::RegisterBenchmark(name.c_str(), bm_analyze, &exemplar, mode)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    }
    for (bool solid : {false, true})
        for (const Model* model : {&hist_on, &hist_off, &joint})
            for (int threads : {1, 2}) {
                const std::string name = std::string(solid ? "Render3D/" : "Render2D/") + size + "/bands:" +
                                         std::to_string(band_count(model->description)) + "/hist:" + model->histogram +
                                         "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(), bm_render, model, solid, threads)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
            }
    for (bool solid : {false, true})
        for (const Model* model : {&hist_on, &hist_off})
            for (bool simd : {true, false}) {
                const std::string name = std::string(solid ? "Raster3D/" : "Raster2D/") + size + "/bands:" +
                                         std::to_string(band_count(model->description)) + "/hist:" + model->histogram +
                                         (simd ? "/path:simd" : "/path:point");
                benchmark::RegisterBenchmark(name.c_str(), bm_raster, model, solid, simd)->Unit(benchmark::kMillisecond);
            }
    for (const Model* model : {&hist_on, &hist_off})
        for (bool batch : {true, false}) {
            const std::string name = "Points3D/" + size + "/bands:" + std::to_string(band_count(model->description)) +
                                     "/hist:" + model->histogram + (batch ? "/path:batch" : "/path:point");
            benchmark::RegisterBenchmark(name.c_str(), bm_surface_points, model, batch)->Unit(benchmark::kMillisecond);
        }
    benchmark::RegisterBenchmark(("Ref/BilinearBaked/" + size).c_str(), bm_bilinear_baked, &baked)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
#ifdef STOCHTEX_HAVE_LIBNOISE
    benchmark::RegisterBenchmark(("Ref/Perlin3D/" + size + "/octaves:" + std::to_string(bands) + "/x3").c_str(),
                                 bm_perlin3d, bands)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
#else
    (void)bands;
#endif

    if (console) {
        ComparingReporter reporter(isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_ColorTabular
                                                         : benchmark::ConsoleReporter::OO_Tabular);
        benchmark::RunSpecifiedBenchmarks(&reporter);
    } else {
        benchmark::RunSpecifiedBenchmarks();
    }
    benchmark::Shutdown();
    return 0;
}
