// stochtex — benchmarks of the lrp model (paper 003), with the wavelet model measured in the same
// run for comparison, and the paper's equal-cost comparison with Gabor noise (Fig. 10).
//
//   Analyze/lrp/<n>            analysis of an n² photo crop (gravel.png, else the committed
//                              exemplar), default options (J = 50, L = 8, r = 0.1); goal < 300 ms at 512²
//   Render2D/lrp/<J,L,r>/...   512² filtered renders through stochtex::render(), full colour, 1 and 2 threads
//   PointEval2D/lrp/...        the same renders through eval() per pixel (the scalar reference
//                              the raster is bit-identical to), one iteration each
//   Render2D/wavelet/...       the same raster with the wavelet model of the same photo
//   Region/lrp/.../rows:R      eval_region over the same raster in 512×R bands, one thread
// Counters: Mpix/s (wall) and cpu_ns/px (CPU time of all the process's threads per pixel, the
// steadier figure on a shared machine).
//
// Before the table: special-function calls per sample (9(J + s), paper §6.2) of each lrp
// texture, and the ring-spectrum comparison with Gabor noise: LRP with J cosines (1 stratum)
// against the project's Gabor noise (gabor_noise.h, hybrid kind: frequencies on the ring in the
// (u, v) plane) with 9J impulses per kernel — the paper's "equal cost" — both rendered, their
// Welch PSDs compared with the ring, and their time per sample measured in this run.
// After the table: lrp vs wavelet speed. Run it through bench/run-lrp.sh.
#include "models/lrp/discrete_spectrum.h"
#include "models/gabor/gabor_noise.h"
#include "models/lrp/lrp_fit.h"
#include "models/lrp/lrp_noise.h"
#include "models/lrp/lrp_raster.h"
#include "models/lrp/lrp_texture.h"
#include "models/lrp/lrp_window.h"
#include "numerics/random.h"

#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/render.h>
#include <stochtex/texture.h>
#include <stochtex/models/gabor_parameters.h>
#include <stochtex/models/lrp_parameters.h>

#include <benchmark/benchmark.h>

#include "median_reporter.h"
#include "photo_crop.h"
#include "point_by_point.h"

#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace stochtex;

constexpr int raster_size = 512;


Image load_photo(std::string& source)
{
    const fs::path shared = fs::path(STOCHTEX_SHARED_DIR) / "exemplars" / "gravel.png";
    const fs::path path = fs::exists(shared) ? shared : fs::path(STOCHTEX_SOURCE_DIR) / "data" / "exemplars" / "concrete_512.png";
    source = path.filename().string();
    return read_image_linear(path.string());
}

struct Model {
    std::string name;
    TextureDescription description;
    std::unique_ptr<Texture> texture;
};

Model make_model(const Image& photo, const std::string& model, int cosines, int strata, double r)
{
    AnalysisOptions options;
    options.model = model;
    if (model == "lrp") {
        char share[32];
        std::snprintf(share, sizeof share, "%g", r);
        options.model_options = {{"J", std::to_string(cosines)}, {"L", std::to_string(strata)}, {"r", share}};
    }
    Model result;
    result.description = analyze(photo, options);
    result.texture = make_texture(result.description);
    char name[64];
    std::snprintf(name, sizeof name, "lrp/J:%d,L:%d,r:%g", cosines, strata, r);
    result.name = model == "lrp" ? name : model;
    return result;
}

void bm_analyze(benchmark::State& state, const Image* photo)
{
    AnalysisOptions options;
    options.model = "lrp";
    for (auto _ : state) benchmark::DoNotOptimize(analyze(*photo, options));
    state.SetLabel(std::to_string(photo->width) + "x" + std::to_string(photo->height) + ", J=50 L=8 r=0.1, goal<300ms");
}

double process_cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

void bm_render(benchmark::State& state, const Model* model, int threads, bool point_path)
{
    RenderSettings settings;
    settings.width = settings.height = raster_size;
    settings.units_per_pixel = 1.0 / model->description.pixels_per_unit;
    settings.origin_u = 0.25, settings.origin_v = 0.5;
    settings.threads = threads;
    // The point path: eval() per pixel, for lrp the scalar reference the raster is bit-identical to.
    const stochtex::bench::PointByPoint point(*model->texture);
    const Texture& texture = point_path ? static_cast<const Texture&>(point) : *model->texture;
    const double cpu_start = process_cpu_seconds();
    for (auto _ : state) {
        Image image = render(texture, settings);
        benchmark::DoNotOptimize(image.pixels.data());
    }
    const double pixels = double(state.iterations()) * raster_size * raster_size;
    state.counters["Mpix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsRate);
    // CPU time of every thread of the process per pixel: steadier than wall time on a shared machine.
    state.counters["cpu_ns/px"] = benchmark::Counter(1e9 * (process_cpu_seconds() - cpu_start) / pixels);
    state.SetLabel(std::string(point_path ? "eval() per pixel" : "eval_region") + ", 2D filtered, full colour, threads=" +
                   std::to_string(threads));
}

/// eval_region straight over the 512² raster in bands of `rows` rows, one thread: what a region's
/// height costs the lrp raster (each window's terms and column factors are made once per region;
/// render() hands out bands of 8 rows, the plugin 64² tiles).
void bm_region(benchmark::State& state, const Model* model, int rows)
{
    RasterRegion region;
    region.origin_u = 0.25, region.origin_v = 0.5;
    region.du = region.dv = 1.0 / model->description.pixels_per_unit;
    region.footprint = Footprint2D{region.du, 0, 0, region.dv};
    region.width = raster_size;
    std::vector<float> rgb(std::size_t(raster_size) * raster_size * 3);
    const double cpu_start = process_cpu_seconds();
    for (auto _ : state)
        for (int y0 = 0; y0 < raster_size; y0 += rows) {
            region.y0 = y0, region.height = std::min(rows, raster_size - y0);
            model->texture->eval_region(region, &rgb[std::size_t(y0) * raster_size * 3]);
            benchmark::DoNotOptimize(rgb.data());
        }
    const double pixels = double(state.iterations()) * raster_size * raster_size;
    state.counters["Mpix/s"] = benchmark::Counter(pixels / 1e6, benchmark::Counter::kIsRate);
    state.counters["cpu_ns/px"] = benchmark::Counter(1e9 * (process_cpu_seconds() - cpu_start) / pixels);
    state.SetLabel("eval_region in 512x" + std::to_string(rows) + " bands, 1 thread, filtered, full colour");
}

/// One random-phase stratum of a texture over the same raster in 512×64 bands, one thread, with
/// each method of lrp_raster_stratum: what each stratum costs, and where the lattice-row raster
/// starts to pay (lrp_lattice_row_spacing). Terms drawn per band, as eval_region does (the
/// lattice-row raster draws its own, lrp_raster_stratum_drawn).
void bm_stratum(benchmark::State& state, const Model* model, std::size_t s, LrpRasterMethod method)
{
    const TextureDescription& description = model->description;
    const LrpParameters& lrp = description.parameters.get<LrpParameters>();
    LrpStratumNoise::Options options;
    options.seed = mix_seed(description.seed, s, 0x1e9);
    const LrpStratumNoise noise(lrp.strata[s], lrp.spectrum_size, options);
    constexpr int rows = 64;
    std::vector<double> x(raster_size), y(raster_size);
    for (int k = 0; k < raster_size; ++k) x[std::size_t(k)] = 0.25 * description.pixels_per_unit + k + 0.5;
    for (int k = 0; k < raster_size; ++k) y[std::size_t(k)] = 0.5 * description.pixels_per_unit + k + 0.5;
    std::vector<float> out[3];
    for (auto& channel : out) channel.resize(std::size_t(raster_size) * rows);
    float* const channels[3] = {out[0].data(), out[1].data(), out[2].data()};
    const LrpLattice& lattice = noise.lattice();
    const LrpFilter identity;
    LrpTermCache terms;
    const double cpu_start = process_cpu_seconds();
    for (auto _ : state)
        for (int y0 = 0; y0 < raster_size; y0 += rows) {
            const LrpRasterGrid grid{x.data(), raster_size, y.data() + y0, rows};
            const std::int64_t i0 = lattice.nearest(0, x.front()) - 1, i1 = lattice.nearest(0, x.back()) + 1;
            const std::int64_t j0 = lattice.nearest(1, grid.y[0]) - 1, j1 = lattice.nearest(1, grid.y[rows - 1]) + 1;
            if (method == LrpRasterMethod::lattice_rows) {
                lrp_raster_stratum_drawn(noise, identity, grid, channels);  // as eval_region takes it
            } else {
                terms.fill(i0, j0, int(i1 - i0 + 1), int(j1 - j0 + 1),
                           [&](std::int64_t i, std::int64_t j, LrpTerms& t) { noise.draw(i, j, identity, t); });
                lrp_raster_stratum(noise, terms, grid, channels, method);
            }
            benchmark::DoNotOptimize(out[0].data());
        }
    const double pixels = double(state.iterations()) * raster_size * raster_size;
    state.counters["cpu_ns/px"] = benchmark::Counter(1e9 * (process_cpu_seconds() - cpu_start) / pixels);
    char label[96];
    std::snprintf(label, sizeof label, "spacing %.1f px, %d cosines", noise.lattice().spacing[0], noise.term_count());
    state.SetLabel(label);
}

// ---- The paper's Fig. 10 comparison --------------------------------------------------------

/// Excess kurtosis: 0 for a Gaussian; sparse (too few impulses) noise is positive, a sum of too
/// few cosines negative.
double excess_kurtosis(const std::vector<float>& values)
{
    double m2 = 0, m4 = 0;
    for (float v : values) m2 += double(v) * v, m4 += double(v) * v * double(v) * v;
    m2 /= double(values.size()), m4 /= double(values.size());
    return m4 / (m2 * m2) - 3;
}

template <class Noise>
void compare_on_ring(const char* model, int j, double calls, const DiscreteSpectrum& ring, const Noise& noise)
{
    constexpr int size = 768;
    std::vector<float> image(std::size_t(size) * size);
    const auto start = std::chrono::steady_clock::now();
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) image[std::size_t(y) * size + x] = noise(x + 0.5, y + 0.5);
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / (size * size);
    const DiscreteSpectrum measured = welch_psd(image, size, size, ring.size);
    std::printf("  %-10s J=%d  %5.0f calls/sample  %7.1f ns/sample  log-PSD distance %5.2f dB  energy ratio %.3f  "
                "excess kurtosis %+.3f\n",
                model, j, calls, ns, log_spectrum_distance_db(measured, ring), measured.total() / ring.total(),
                excess_kurtosis(image));
}

void ring_comparison()
{
    // A ring of radius 1/8 cycle per pixel whose radial profile is a Gaussian of σ = 1/100: the
    // spectrum of isotropic ("hybrid" in the (u, v) plane) Gabor noise of frequency 1/8 and
    // bandwidth a = 2√π σ, so Gabor is judged on its own ground.
    const double radius = 0.125, sigma = 0.01;
    const DiscreteSpectrum ring = ring_spectrum(128, radius, sigma);
    std::printf("Ring spectrum (radius %.3f, sigma %.3f cycles/px), one stratum; Gabor with 9J impulses per kernel "
                "(paper Fig. 10's equal cost: LRP 9(J+1) calls, Gabor 2 per impulse):\n",
                radius, sigma);
    // LRP's window: Δ by the paper's coverage rule (small: the ring covers many bins), or Δ whose
    // spectral spread 0.41/Δ is 2σ or σ of the ring (the user's choice for a continuous spectrum).
    const double spread = lrp_window_spread_2d(0.75);
    for (int j : {1, 3, 5, 9}) {
        for (double spacing : {0.0, spread / (2 * sigma), spread / sigma}) {
            const LrpStratum stratum = lrp_for_spectrum(ring, j, 1, spacing).strata.front();
            const LrpStratumNoise lrp(stratum, ring.size, {});
            const LrpFilter identity;
            char name[32];
            std::snprintf(name, sizeof name, "LRP Δ=%.0f", stratum.spacing);
            compare_on_ring(name, j, 9.0 * (j + 1), ring, [&](double x, double y) {
                float value[3];
                lrp.eval(x, y, identity, value);
                return value[0];
            });
        }
        GaborNoiseParameters parameters;
        parameters.kind = GaborKind::hybrid;
        parameters.direction = {0, 0, 1};
        parameters.frequency = radius;
        parameters.bandwidth = 2 * std::sqrt(M_PI) * sigma;
        parameters.impulses_per_kernel = 9.0 * j;
        parameters.channels = 1;
        const GaborNoise gabor(parameters);
        const GaborFilter unfiltered;
        compare_on_ring("Gabor", j, 2 * 9.0 * j, ring, [&](double x, double y) {
            float value[GaborNoise::max_channels];
            gabor.eval_2d(x, y, unfiltered, value);
            return value[0];
        });
    }
    std::printf("\n");
}

// ---- After the table: lrp vs wavelet -------------------------------------------------------

class ComparisonReporter : public stochtex::bench::MedianReporter {
public:
    ComparisonReporter() : MedianReporter({"Mpix/s"}) {}

    void Finalize() override
    {
        ConsoleReporter::Finalize();
        std::printf("\nlrp vs wavelet (median Mpix/s of this run, same photo, same raster):\n");
        for (int threads : {1, 2}) {
            const std::string suffix = "/threads:" + std::to_string(threads);
            double wavelet = 0;
            for (const auto& [name, entry] : medians())
                if (name.find("wavelet") != std::string::npos && name.find(suffix) != std::string::npos) wavelet = entry.rate;
            for (const auto& [name, entry] : medians())
                if (name.rfind("Render2D/lrp", 0) == 0 && name.find(suffix) != std::string::npos && wavelet > 0)
                    std::printf("  %-44s %6.2f Mpix/s = %.2fx wavelet (%.2f)\n", name.c_str(), entry.rate, entry.rate / wavelet,
                                wavelet);
        }
        std::printf("\nlrp raster (eval_region) vs the point path (eval() per pixel, the reference), same run:\n");
        for (const auto& [name, entry] : medians()) {
            if (name.rfind("Render2D/lrp", 0) != 0) continue;
            // The point path runs one iteration per repetition: its name says so.
            std::string point = "PointEval2D/" + name.substr(std::string("Render2D/").size());
            point.insert(point.rfind('/') + 1, "iterations:1/");
            const auto reference = medians().find(point);
            if (reference != medians().end() && reference->second.rate > 0)
                std::printf("  %-44s %6.2f vs %6.3f Mpix/s = %.1fx\n", name.c_str(), entry.rate, reference->second.rate,
                            entry.rate / reference->second.rate);
        }
    }

};

}  // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    static std::string source;
    static Image photo, crop256, crop512;
    static std::vector<Model> models;
    try {
        photo = load_photo(source);
        crop256 = stochtex::bench::top_left_crop(photo, 256);
        crop512 = stochtex::bench::top_left_crop(photo, 512);
        models.push_back(make_model(crop512, "lrp", 50, 4, 0));
        models.push_back(make_model(crop512, "lrp", 50, 8, 0.1));
        models.push_back(make_model(crop512, "wavelet", 0, 0, 0));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "lrp_bench: setup failed: %s\n", e.what());
        return 1;
    }
    std::printf("photo: %s (top-left crops)\n", source.c_str());
    for (const Model& model : models)
        if (const auto* lrp = dynamic_cast<const LrpTexture*>(model.texture.get()))
            std::printf("%s: %.0f special-function calls per sample, 9(J + s); %.0f with placement and turbulence\n",
                        model.name.c_str(), lrp->cost().paper_calls, lrp->cost().total_calls);
    std::printf("\n");
    ring_comparison();

    for (const Image* crop : {&crop256, &crop512})
        benchmark::RegisterBenchmark(("Analyze/lrp/" + std::to_string(crop->width)).c_str(), bm_analyze, crop)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    for (const Model& model : models)
        for (int threads : {1, 2}) {
            benchmark::RegisterBenchmark(("Render2D/" + model.name + "/threads:" + std::to_string(threads)).c_str(), bm_render,
                                         &model, threads, false)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
            // The lrp point path (the reference), for the speed-up in the same run.
            if (model.name.rfind("lrp", 0) == 0)
                benchmark::RegisterBenchmark(("PointEval2D/" + model.name + "/threads:" + std::to_string(threads)).c_str(),
                                             bm_render, &model, threads, true)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime()
                    ->Iterations(1);
        }
    for (const Model& model : models)
        if (model.name.rfind("lrp", 0) == 0)
            for (int rows : {8, 64})
                benchmark::RegisterBenchmark(("Region/" + model.name + "/rows:" + std::to_string(rows)).c_str(), bm_region,
                                             &model, rows)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
    for (const Model& model : models)
        if (model.name == "lrp/J:50,L:8,r:0.1")
            for (std::size_t s = 0; s < model.description.parameters.get<LrpParameters>().strata.size(); ++s)
                for (const auto& [method, name] : {std::pair{LrpRasterMethod::separable, "separable"},
                                                   std::pair{LrpRasterMethod::lattice_rows, "lattice_rows"}})
                    benchmark::RegisterBenchmark(("Stratum/" + model.name + "/s:" + std::to_string(s) + "/" + name).c_str(),
                                                 bm_stratum, &model, s, method)
                        ->Unit(benchmark::kMillisecond)
                        ->UseRealTime();
    ComparisonReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}
