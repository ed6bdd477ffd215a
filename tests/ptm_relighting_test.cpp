// Relighting end to end (docs/models/ptm.md, "Acceptance"): the rock height map rendered under
// 40 known lights with a known model (Lambertian, cast shadows: relief_shading.h), a PTM fitted
// to those photos, synthesised larger in ψ-space and relit under 8 lights that were never
// photographed; compared with the truth rendered under the same lights. And the `stex ptm`
// commands on a small surface.
#include "test_support.h"

#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/relief_shading.h>
#include <stochtex/models/ptm_parameters.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;
using namespace stochtex;

namespace {

struct Statistics {
    double mean_error = 0, sigma_error = 0, w1 = 0, log_psd_db = 0, orientation_degrees = 0;
};

Statistics compare(const Image& truth, const Image& test)
{
    const RelitComparison c = compare_relit(truth, test);
    return {c.mean_error(), c.sigma_error(), c.w1, c.log_psd_db, c.orientation_error_degrees()};
}

Statistics worst(const Statistics& a, const Statistics& b)
{
    return {std::max(a.mean_error, b.mean_error), std::max(a.sigma_error, b.sigma_error), std::max(a.w1, b.w1),
            std::max(a.log_psd_db, b.log_psd_db), std::max(a.orientation_degrees, b.orientation_degrees)};
}

void print(const char* name, const Statistics& s)
{
    std::printf("[ relight ] %-34s mean %5.1f %%  σ %5.1f %%  W1/σ %.3f  log-PSD %.2f dB  orientation %4.1f°\n", name,
                100 * s.mean_error, 100 * s.sigma_error, s.w1, s.log_psd_db, s.orientation_degrees);
}

double rms(const Image& a)
{
    double sum = 0;
    for (float v : a.pixels) sum += double(v) * v;
    return std::sqrt(sum / double(a.pixels.size()));
}

}  // namespace

TEST(Relighting, SynthesisedPtmRelightsLikeTheTruthUnderUnseenLights)
{
    const std::string height_map = test::shared_exemplar("rock_height.png");
    if (height_map.empty()) GTEST_SKIP() << "../shared/exemplars is absent";
    // The 1024² scan down to 128² texels (heights 0 … 6 texels: slopes as at 512² with depth 24).
    const ReliefSurface surface = make_relief_surface(height_map, 8, 6);
    const std::vector<Vec3> lights = spiral_light_directions(40, 15);
    const std::vector<Vec3> unseen = spiral_light_directions(8, 20, 17);
    std::vector<Image> photos;
    for (const Vec3& l : lights) photos.push_back(shade_relief(surface, l));
    const PtmFit fit = fit_ptm(photos, lights, PtmColour::lrgb);
    std::printf("[ relight ] fit: residual %.2f %%, leave-one-light-out %.2f %% of the photos' RMS\n",
                100 * fit.rmse / fit.data_rms, 100 * fit.loo_rmse / fit.data_rms);
    EXPECT_LT(fit.loo_rmse, 0.12 * fit.data_rms);

    PtmSynthesisOptions options;
    options.width = options.height = 192;
    options.block = 32;
    options.overlap = 8;
    const PtmMaps synthesis = synthesize_ptm(fit.maps, options);

    // Thresholds: above the spread over synthesis seeds 1–6 (worst over the 8 lights: mean
    // 5.9–9.4 %, σ 6.1–11.1 %, W1/σ 0.18–0.31, log-PSD 1.5–2.0 dB, orientation 3–12°; a 128²
    // surface holds only a few of the rock's ridges, so one synthesis differs from the next), and
    // far below what a texture with its lighting baked in gets (the baseline, below).
    const Statistics limits{0.15, 0.15, 0.40, 2.5, 15};
    auto within = [&](const Statistics& s) {
        return s.mean_error <= limits.mean_error && s.sigma_error <= limits.sigma_error && s.w1 <= limits.w1 &&
               s.log_psd_db <= limits.log_psd_db && s.orientation_degrees <= limits.orientation_degrees;
    };
    // The baseline: the photo under the most overhead fitting light, as ordinary (baked)
    // synthesis would reproduce it under any light.
    std::size_t overhead = 0;
    for (std::size_t i = 0; i < lights.size(); ++i)
        if (lights[i][2] > lights[overhead][2]) overhead = i;
    Statistics synthesis_worst;
    double fit_rmse_worst = 0;
    for (const Vec3& l : unseen) {
        const Image truth = shade_relief(surface, l);
        fit_rmse_worst = std::max(fit_rmse_worst, compare_relit(truth, relight(fit.maps, l)).pixel_rmse / rms(truth));
        const Statistics s = compare(truth, relight(synthesis, l)), baked = compare(truth, photos[overhead]);
        char name[64];
        std::snprintf(name, sizeof name, "el %2.0f° az %4.0f°: synthesis", std::asin(l[2]) * 180 / M_PI,
                      std::atan2(l[1], l[0]) * 180 / M_PI);
        print(name, s);
        print("             baked lighting", baked);
        EXPECT_TRUE(within(s)) << name;
        synthesis_worst = worst(synthesis_worst, s);
        // The statistics tell relit from baked textures wherever the light is not near overhead.
        if (l[2] < std::sin(55 * M_PI / 180)) EXPECT_FALSE(within(baked)) << name << ": the baseline passes";
    }
    std::printf("[ relight ] fitted exemplar vs truth under the unseen lights: pixel RMSE ≤ %.2f %% of the truth's RMS\n",
                100 * fit_rmse_worst);
    print("synthesis, worst over the lights", synthesis_worst);
    EXPECT_LT(fit_rmse_worst, 0.10);
}

// ---- stex ptm ---------------------------------------------------------------------------------------

namespace {

test::ProgramResult stex(const std::vector<std::string>& args, const std::string& dir)
{
    std::vector<std::string> all{STOCHTEX_CLI};
    all.insert(all.end(), args.begin(), args.end());
    return test::run_program(all, dir);
}

}  // namespace

TEST(PtmCli, FitSynthesizeRelightExport)
{
    const std::string dir = test::temp_dir("ptm-cli");
    auto run = [&](const std::vector<std::string>& args) {
        const test::ProgramResult r = stex(args, dir);
        EXPECT_TRUE(r.succeeded()) << r;
        return r.output();
    };
    const std::string help = run({"ptm", "--help"});
    for (const char* command : {"fit", "synthesize", "relight", "export-maps", "relief"})
        EXPECT_TRUE(test::contains(help, command)) << help;
    // The committed photo as a small height field: 64² texels, 12 lights.
    run({"ptm", "relief", test::repo_exemplar("concrete_512.png"), "-o", dir + "/photos", "--lights", "12", "--downsample",
         "8", "--depth", "4"});
    ASSERT_TRUE(fs::exists(dir + "/photos/lights.lp"));
    EXPECT_TRUE(fs::exists(dir + "/photos/light_011.exr"));
    EXPECT_TRUE(test::contains(run({"ptm", "fit", dir + "/photos/lights.lp", "-o", dir + "/t.stex", "--colour", "rgb"}),
                               "leave-one-light-out RMSE"));
    EXPECT_TRUE(fs::exists(dir + "/t.ptm.exr"));
    EXPECT_TRUE(test::contains(run({"info", dir + "/t.stex"}), "ptm          rgb, 64x64 texels"));
    const std::string synthesis = run({"ptm", "synthesize", dir + "/t.stex", "-o", dir + "/s.stex", "--size", "80x80",
                                       "--block", "16", "--overlap", "4", "--tileable", "--verify"});
    EXPECT_TRUE(test::contains(synthesis, "outputs identical")) << synthesis;
    EXPECT_TRUE(test::contains(synthesis, "84x84 texels, tileable")) << synthesis;  // 7 whole steps of 12
    run({"ptm", "relight", dir + "/s.stex", "-o", dir + "/strip.png", "--light", "0,0,1", "--light-angles", "45,30"});
    const Image strip = read_image_linear(dir + "/strip.png");
    EXPECT_EQ(strip.width, 168);
    EXPECT_EQ(strip.height, 84);
    EXPECT_TRUE(test::contains(run({"ptm", "relight", dir + "/t.stex", "--lights-from", dir + "/photos/lights.lp", "--compare",
                                    "--pixelwise", "-o", dir + "/all.exr"}),
                               "pixel RMSE"));
    EXPECT_TRUE(test::contains(run({"ptm", "export-maps", dir + "/t.stex", "--normal", dir + "/n.png", "--albedo",
                                    dir + "/a.png", "--reference-normals", dir + "/photos/normal.exr"}),
                               "normal error (lambertian): mean"));
    EXPECT_TRUE(fs::exists(dir + "/n.png") && fs::exists(dir + "/a.png"));
    run({"render", dir + "/s.stex", "-o", dir + "/render.png", "--size", "48x48"});  // the generic route

    auto failure = [&](const std::vector<std::string>& args) {
        const test::ProgramResult r = stex(args, dir);
        EXPECT_TRUE(r.exited && r.code != 0) << r;
        return r.err;
    };
    EXPECT_TRUE(test::contains(failure({"ptm", "fit", dir + "/missing.lp", "-o", dir + "/x.stex"}), "missing.lp"));
    EXPECT_TRUE(test::contains(failure({"ptm", "relight", dir + "/t.stex", "-o", dir + "/x.png", "--light", "0,0,-1"}),
                               "must point out of the surface"));
    EXPECT_TRUE(test::contains(failure({"ptm", "synthesize", dir + "/t.stex", "-o", dir + "/x.stex", "--block", "80"}),
                               "does not fit"));
}
