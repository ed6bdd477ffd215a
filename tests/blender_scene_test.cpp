// Blender scene tests (CTest label "scene"; docs/blender.md): Debian's Blender, headless, installs
// and enables the add-on from the built zip (Blender 3.4, Debian 12: the legacy add-on path;
// Blender 4.2+, Debian 13 in scripts/debian13-lane.sh: as an extension), analyses the committed
// exemplar with the add-on's operator, builds the material, renders with Cycles (CPU, few
// samples, fixed seed, no denoiser), and the render is compared with the core's own render of
// the same texture and region.
// Skips when `blender` is not on PATH (scripts/install-deps.sh --with-blender installs it).
#include "test_support.h"

#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/mip_image.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <utility>

namespace fs = std::filesystem;
using namespace stochtex;

namespace {

bool have_blender() { return test::on_path("blender"); }

/// The Blender on PATH as (major, minor), from `blender --version`'s first line ("Blender 4.3.2").
std::pair<int, int> blender_version()
{
    const auto result = test::run_command("blender --version");
    int major = 0, minor = 0;
    const auto at = result.output.find("Blender ");
    if (at != std::string::npos) std::sscanf(result.output.c_str() + at, "Blender %d.%d", &major, &minor);
    return {major, minor};
}

/// The environment of a Blender run: its own user-scripts and user-extensions folders (the
/// add-on is installed there, not in the user's profile), the built stex, and its own temporary
/// folder — the checks count the add-on's temporary folders, so tests running at the same time
/// must not see each other's.
std::string blender_environment(const std::string& out)
{
    std::filesystem::create_directories(out + "/tmp");
    return "env BLENDER_USER_SCRIPTS=" + test::shell_quote(out + "/user-scripts") +
           " BLENDER_USER_EXTENSIONS=" + test::shell_quote(out + "/user-extensions") + " TMPDIR=" + test::shell_quote(out + "/tmp") +
           " STOCHTEX_STEX=" + test::shell_quote(STOCHTEX_CLI);
}

/// Runs scenes/blender/<script> in a headless Blender (blender_environment()).
test::CommandResult run_blender(const std::string& script, const std::string& out, const std::string& extra = "",
                                const std::string& environment = "")
{
    const std::string line = blender_environment(out) + environment +
                             " timeout 300 blender -b --factory-startup --python " +
                             test::shell_quote(std::string(STOCHTEX_SOURCE_DIR) + "/scenes/blender/" + script) +
                             " -- --addon " + test::shell_quote(STOCHTEX_ADDON_ZIP) + " --photo " +
                             test::shell_quote(test::repo_exemplar("concrete_512.png")) + " --out " +
                             test::shell_quote(out) + " " + extra;
    return test::run_command(line);
}

nlohmann::json read_json(const std::string& path)
{
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

double rms_difference_over_sigma(const Image& a, const Image& b)
{
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += double(a.pixels[i] - b.pixels[i]) * (a.pixels[i] - b.pixels[i]);
    const ComparisonReport self = compare_images(b, b);
    const double sigma = (self.stddev_reference[0] + self.stddev_reference[1] + self.stddev_reference[2]) / 3;
    return std::sqrt(sum / double(a.pixels.size())) / sigma;
}

// The plane shows the top-left plane_size² texels of a bake_size² map (one period; a period
// much smaller than the coarsest band's wavelength, 256 · 2^7 photo pixels for 8 bands, holds
// only approximations of the coarse bands: make_periodic_texture, docs/oiio-plugin.md).
constexpr int plane_size = 512, bake_size = 2048;

// Blender 4.2+ reads the zip as an extension: its own validator must accept the manifest
// (the scene scripts then install it with package_install_files, stochtex_scene.py).
TEST(BlenderScene, ExtensionManifestValidates)
{
    if (!have_blender()) GTEST_SKIP() << "blender not on PATH (scripts/install-deps.sh --with-blender)";
    const auto [major, minor] = blender_version();
    if (major * 100 + minor < 402) GTEST_SKIP() << "Blender " << major << "." << minor << " has no extensions (4.2+)";
    const std::string out = test::temp_dir("blender-validate");
    const auto result = test::run_command(blender_environment(out) + " timeout 120 blender --command extension validate " +
                                          test::shell_quote(STOCHTEX_ADDON_ZIP));
    EXPECT_EQ(result.status, 0) << result.output;
    EXPECT_NE(result.output.find("Success"), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find("Error"), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find("Warning"), std::string::npos) << result.output;
}

TEST(BlenderScene, MeasurementPlaneMatchesCore)
{
    if (!have_blender()) GTEST_SKIP() << "blender not on PATH (scripts/install-deps.sh --with-blender)";
    const std::string out = test::temp_dir("blender-plane");
    const auto result = run_blender("measure_plane.py", out, "--size " + std::to_string(plane_size) + " --bake-size " + std::to_string(bake_size) + " --samples 16");
    ASSERT_EQ(result.status, 0) << result.output;
    const auto report = read_json(out + "/plane.json");
    const auto [major, minor] = blender_version();
    std::printf("Blender %d.%d: ", major, minor);
    std::printf("analyse + bake %.2f s, Cycles render %dx%d at 16 samples %.2f s\n",
                report["analyse_and_bake_seconds"].get<double>(), plane_size, plane_size,
                report["render_seconds"].get<double>());
    EXPECT_TRUE(report["image_packed"].get<bool>()) << "an unsaved blend packs the baked map";

    const Image blender = read_image_linear(out + "/plane.exr");
    ASSERT_EQ(blender.width, plane_size);
    const TextureDescription description = read_stex(out + "/plane.stex");  // the text stored in the blend
    RenderSettings settings;
    settings.width = settings.height = plane_size;
    settings.units_per_pixel = 1.0 / description.pixels_per_unit;  // the bake's texels: photo pixels

    // 1. Texel for texel: the plane shows the bake, the bake is the core's periodic texture.
    // Differences come only from the map's half floats (relative rounding ≤ 2^-12 of values
    // ~5σ: ~1e-3 σ RMS) and Cycles' 0.01 px pixel filter; 0.01 σ leaves room for neither a
    // flipped or shifted map (0.7 σ and more) nor a colour-space error (tens of per cent).
    const Vec2 period{bake_size / description.pixels_per_unit, bake_size / description.pixels_per_unit};
    const Image baked = render(*make_periodic_texture(description, period), settings);
    const double texel_rms = rms_difference_over_sigma(blender, baked);
    std::printf("texel-for-texel RMS difference: %.4f sigma\n", texel_rms);
    EXPECT_LT(texel_rms, 0.01);

    // 2. Statistics against the core's own render of the texture (non-periodic, `stex render`),
    // same region, same seed. The periodic texture is another realisation of the same process
    // (its coarse bands use other tiles), so a distance of zero is not expected; the yardstick
    // is how far the core's own renders at 8 other seeds lie from the reference:
    //   mean colour: within 3 × the RMS of their mean differences (a 3-sigma bound: the
    //     difference of two realisations' means is roughly normal);
    //   log-PSD distance and W1 (distances, not signed): within 1.5 × the largest of the 8.
    const Image reference = render(*make_texture(description), settings);
    const ComparisonReport measured = compare_images(reference, blender);
    constexpr int seeds = 8;
    std::array<double, 3> mean_rms{}, psd_max{}, w1_max{};
    for (std::uint32_t k = 1; k <= seeds; ++k) {
        TextureDescription other = description;
        other.seed = description.seed + k;
        const ComparisonReport spread = compare_images(reference, render(*make_texture(other), settings));
        for (int c = 0; c < 3; ++c) {
            const double d = spread.mean_test[c] - spread.mean_reference[c];
            mean_rms[c] += d * d / seeds;
            psd_max[c] = std::max(psd_max[c], spread.log_psd_db[c]);
            w1_max[c] = std::max(w1_max[c], spread.w1[c]);
        }
    }
    std::printf("Blender vs core (seed %u) | core at %d other seeds vs core (RMS or max)\n", description.seed, seeds);
    for (int c = 0; c < 3; ++c) {
        const double mean_error = std::abs(measured.mean_test[c] - measured.mean_reference[c]);
        mean_rms[c] = std::sqrt(mean_rms[c]);
        std::printf("  %c: mean %.5f vs %.5f (|d| %.5f | RMS %.5f)  log-PSD %.2f dB | max %.2f  W1 %.5f | max %.5f\n",
                    "RGB"[c], measured.mean_test[c], measured.mean_reference[c], mean_error, mean_rms[c],
                    measured.log_psd_db[c], psd_max[c], measured.w1[c], w1_max[c]);
        EXPECT_LE(mean_error, 3 * mean_rms[c]);
        EXPECT_LE(measured.log_psd_db[c], 1.5 * psd_max[c]);
        EXPECT_LE(measured.w1[c], 1.5 * w1_max[c]);
    }
}

// The add-on's OSL route (no bake: its generated shader in a Script node, Cycles on the CPU with
// OSL), on the measurement plane: the render is the core's texture itself, not a periodic bake,
// so it must equal the core's render of the same region. The plane's UVs are texture units
// (uv_repeats 1, Scale 1), the camera frames u ∈ [0, s], UV v ∈ [1 − s, 1] with s = size /
// bake size, and the shader shows (u, −v): the core's region from v = −1, rows not flipped.
// One sample per pixel (an OSL render is slow): the 0.01-px pixel filter moves it off the pixel
// centre by ≤ 0.005 px, hence the tolerance (measured: docs/blender.md).
TEST(BlenderScene, OslRouteMatchesCore)
{
    if (!have_blender()) GTEST_SKIP() << "blender not on PATH (scripts/install-deps.sh --with-blender)";
    constexpr int osl_size = 128, osl_bake_size = 512;
    const std::string out = test::temp_dir("blender-osl-route");
    const auto result = run_blender("measure_plane.py", out, "--route OSL --size " + std::to_string(osl_size) + " --bake-size " +
                                                             std::to_string(osl_bake_size) + " --samples 1");
    ASSERT_EQ(result.status, 0) << result.output;
    const auto report = read_json(out + "/plane.json");
    if (!report["cycles_osl"].get<bool>()) GTEST_SKIP() << "this Blender has no OSL (bpy.app.build_options.cycles_osl; Debian's builds)";
    EXPECT_TRUE(report["shading_system_osl"].get<bool>()) << "the route must switch Cycles to OSL";
    const auto [major, minor] = blender_version();
    std::printf("Blender %d.%d OSL route: analyse %.2f s, Cycles OSL render %dx%d at 1 sample %.2f s\n", major, minor,
                report["analyse_and_bake_seconds"].get<double>(), osl_size, osl_size, report["render_seconds"].get<double>());

    const Image blender = read_image_linear(out + "/plane.exr");
    ASSERT_EQ(blender.width, osl_size);
    const TextureDescription description = read_stex(out + "/plane.stex");
    RenderSettings settings;
    settings.width = settings.height = osl_size;
    settings.units_per_pixel = 1.0 / osl_bake_size;
    settings.origin_v = -1.0;
    const double rms = rms_difference_over_sigma(blender, render(*make_texture(description), settings));
    std::printf("OSL route vs core: RMS difference %.2e sigma\n", rms);
    // A flipped, shifted or wrongly scaled region is ≥ 0.5 σ; the sample's offset from the pixel
    // centre, a few thousandths.
    EXPECT_LT(rms, 0.02);
}

TEST(BlenderScene, AddonFailuresAreReportsAndLeaveNothing)
{
    if (!have_blender()) GTEST_SKIP() << "blender not on PATH (scripts/install-deps.sh --with-blender)";
    const std::string out = test::temp_dir("blender-checks");
    const auto result = run_blender("addon_checks.py", out);
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_EQ(result.output.find("Traceback"), std::string::npos) << result.output;
    const auto checks = read_json(out + "/checks.json");
    EXPECT_GE(checks.size(), 8u);
    for (const auto& [name, check] : checks.items())
        EXPECT_TRUE(check["ok"].get<bool>()) << name << ": " << check["detail"].get<std::string>();
}

TEST(BlenderScene, InteractiveOperatorIsModalCancellableAndUndoable)
{
    if (!have_blender() || !test::on_path("xvfb-run"))
        GTEST_SKIP() << "needs blender and xvfb-run (scripts/install-deps.sh --with-blender)";
    const std::string out = test::temp_dir("blender-modal");
    const std::string line = blender_environment(out) +
                             " timeout 300 xvfb-run -a -s '-screen 0 1280x800x24' blender --factory-startup "
                             "--enable-event-simulate --python " +
                             test::shell_quote(std::string(STOCHTEX_SOURCE_DIR) + "/scenes/blender/modal_checks.py") +
                             " -- --addon " + test::shell_quote(STOCHTEX_ADDON_ZIP) + " --photo " +
                             test::shell_quote(test::repo_exemplar("concrete_512.png")) + " --out " + test::shell_quote(out);
    const auto result = test::run_command(line);
    ASSERT_EQ(result.status, 0) << result.output;
    const auto checks = read_json(out + "/modal.json");
    EXPECT_EQ(checks.size(), 5u) << result.output;
    for (const auto& [name, check] : checks.items()) {
        std::printf("%s: %s\n", name.c_str(), check["detail"].get<std::string>().c_str());
        EXPECT_TRUE(check["ok"].get<bool>()) << name << ": " << check["detail"].get<std::string>();
    }
}

TEST(BlenderScene, ShowcaseRenders)
{
    if (!have_blender()) GTEST_SKIP() << "blender not on PATH (scripts/install-deps.sh --with-blender)";
    const std::string out = test::temp_dir("blender-showcase");
    const auto result = run_blender("showcase.py", out, "--width 320 --height 180 --samples 8");
    ASSERT_EQ(result.status, 0) << result.output;
    const Image image = read_image_linear(out + "/showcase.png");
    ASSERT_EQ(image.width, 320);
    const ComparisonReport self = compare_images(image, image);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(self.mean_reference[c], 0.01) << "a black render";
        EXPECT_GT(self.stddev_reference[c], 0.005) << "a flat render";
    }
    const auto report = read_json(out + "/showcase.json");
    std::printf("showcase 320x180, 8 samples: %.2f s render\n", report["render_seconds"].get<double>());
}

// Cycles renders a .stex live, through the OIIO plugin, with no bake (issue 31): straight on, one
// pixel per level-0 texel, the render equals the plugin's texels (the core's MipImage); Blender
// 5.2's texture cache streams only the tiles it needs (the plugin's STOCHTEX_TILE_STATS counts),
// older Blenders read the whole of level 0, so their file declares a smaller image.
TEST(BlenderScene, LiveStexRendersThroughThePlugin)
{
    if (!have_blender()) GTEST_SKIP() << "blender not on PATH (scripts/install-deps.sh --with-blender)";
    const auto [major, minor] = blender_version();
    const bool streams = major * 100 + minor >= 502;  // Cycles' own texture cache (5.2)
    const std::string out = test::temp_dir("blender-live");
    constexpr int size = 128;
    const int texels = streams ? 32768 : 4096;
    TextureDescription description = analyze(read_image_linear(test::repo_exemplar("concrete_512.png")), {});
    ImageLayout layout;
    layout.width = layout.height = texels;
    description.image = layout;
    const std::string stex = out + "/live.stex";
    write_stex(stex, description);
    const std::string plugins = test::shell_quote(STOCHTEX_PLUGIN_DIR);
    const auto result = test::run_command(
        blender_environment(out) + " OPENIMAGEIO_PLUGIN_PATH=" + plugins + " OIIO_LIBRARY_PATH=" + plugins +
        " STOCHTEX_TILE_STATS=" + test::shell_quote(out + "/tiles.jsonl") + " timeout 300 blender -b --factory-startup --python " +
        test::shell_quote(std::string(STOCHTEX_SOURCE_DIR) + "/scenes/blender/live_plane.py") + " -- --addon " +
        test::shell_quote(STOCHTEX_ADDON_ZIP) + " --photo " + test::shell_quote(test::repo_exemplar("concrete_512.png")) +
        " --out " + test::shell_quote(out) + " --stex " + test::shell_quote(stex) + " --texels " + std::to_string(texels) +
        " --size " + std::to_string(size) + " --samples 4" + (streams ? " --receding" : ""));
    ASSERT_EQ(result.status, 0) << result.output;

    // 1. Texel for texel: the top-left size² texels of level 0, as the plugin makes them.
    const Image blender = read_image_linear(out + "/live.exr");
    ASSERT_EQ(blender.width, size);
    const MipImage image(description, layout, "live.stex");
    Image texels_expected(size, size, 3);
    image.fill(0, 0, 0, size, size, texels_expected.pixels.data());
    const double texel_rms = rms_difference_over_sigma(blender, texels_expected);
    const auto report = read_json(out + "/live.json");
    std::printf("Blender %d.%d, live %d² of a %d² .stex: %.2f s render, texel-for-texel RMS %.4f sigma\n", major, minor,
                size, texels, report["live_seconds"].get<double>(), texel_rms);
    EXPECT_LT(texel_rms, 0.01);  // the baked route's tolerance (MeasurementPlaneMatchesCore)

    // 2. What Cycles asked the plugin for, per MIP level (one line per file Cycles opened).
    std::ifstream lines(out + "/tiles.jsonl");
    std::vector<std::uint64_t> made, served, tiles;
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json counts = nlohmann::json::parse(line);
        for (const auto& level : counts["levels"]) {
            const std::size_t l = level["level"].get<std::size_t>();
            made.resize(std::max(made.size(), l + 1)), served.resize(made.size()), tiles.resize(made.size());
            made[l] += level["made"].get<std::uint64_t>();
            served[l] += level["served"].get<std::uint64_t>();
            tiles[l] = level["tiles"].get<std::uint64_t>();
        }
    }
    ASSERT_FALSE(made.empty()) << "no tile counts: was the plugin loaded? " << result.output;
    std::uint64_t all_made = 0, all_tiles = 0;
    for (std::size_t l = 0; l < made.size(); ++l) {
        if (made[l] || served[l]) std::printf("  level %zu: %llu of %llu tiles made, %llu reads served from the cache\n", l,
                                              (unsigned long long)made[l], (unsigned long long)tiles[l], (unsigned long long)served[l]);
        all_made += made[l], all_tiles += tiles[l];
    }
    if (streams) {
        // Straight on and receding together: a small part of the texture's tiles, on several levels.
        EXPECT_LT(all_made * 100, all_tiles) << "more than 1 % of the tiles made";
        EXPECT_GE(std::count_if(made.begin(), made.end(), [](std::uint64_t m) { return m > 0; }), 3);
    } else {
        EXPECT_GE(made[0], tiles[0]) << "Blender < 5.2 reads the whole of level 0";
    }
}

// The add-on's Live route (docs/blender.md, "Live"): the analyse operator writes the .stex beside
// the saved blend with an image block, and the material gives Cycles its own output reading that
// file through the OIIO plugin (EEVEE keeps the baked map). Blender starts with no OIIO variable:
// the add-on must put the plugin (found through $STOCHTEX_PLUGIN_PATH) on OIIO's search path itself.
// Texel for texel against the plugin's level 0, then again after a tweak rewrote the live file.
TEST(BlenderScene, LiveRouteRendersThroughThePlugin)
{
    if (!have_blender()) GTEST_SKIP() << "blender not on PATH (scripts/install-deps.sh --with-blender)";
    const auto [major, minor] = blender_version();
    const int live_size = major * 100 + minor >= 502 ? 32768 : 4096;  // the add-on's defaults (stex_cli.live_size)
    constexpr int size = 128, preview_size = 256;
    const std::string out = test::temp_dir("blender-live-route");
    const std::string arguments = "--route LIVE --size " + std::to_string(size) + " --bake-size " +
                                  std::to_string(preview_size) + " --live-size " + std::to_string(live_size) + " --samples 4";
    const auto result = run_blender("measure_plane.py", out, arguments,
                                    " env -u OPENIMAGEIO_PLUGIN_PATH -u OIIO_LIBRARY_PATH STOCHTEX_PLUGIN_PATH=" +
                                        test::shell_quote(STOCHTEX_PLUGIN_DIR));
    ASSERT_EQ(result.status, 0) << result.output;
    const auto report = read_json(out + "/plane.json");
    EXPECT_EQ(report["cycles_output"], "stochtex live output");
    EXPECT_NE(report["eevee_output"], "stochtex live output");
    EXPECT_NE(report["eevee_surface"], "stochtex live BSDF") << "EEVEE must keep the baked map";
    EXPECT_EQ(report["image_size"], nlohmann::json::array({preview_size, preview_size})) << "the baked map EEVEE shows";
    EXPECT_EQ(report["live_image_filepath"], "//stochtex/concrete_512.stex") << "the live file goes beside the blend";

    for (const char* name : {"live", "tweaked"}) {
        const TextureDescription description = read_stex(out + "/" + name + ".stex");
        ASSERT_TRUE(description.image.has_value()) << name;
        EXPECT_EQ(description.image->width, live_size) << name;
        EXPECT_EQ(description.seed, std::string(name) == "tweaked" ? 2u : 1u) << name;
        const Image blender = read_image_linear(out + "/" + (std::string(name) == "live" ? "plane" : name) + ".exr");
        ASSERT_EQ(blender.width, size);
        // The live file has the baked map's texel density: the plane's UV unit holds preview_size
        // of its texels, its top edge the file's row live_size - preview_size (measure_plane.py).
        const MipImage image(description, *description.image, std::string(name) + ".stex");
        Image expected(size, size, 3);
        image.fill(0, 0, live_size - preview_size, size, size, expected.pixels.data());
        const double rms = rms_difference_over_sigma(blender, expected);
        std::printf("Blender %d.%d, live route, %s (seed %u), %d² of a %d² .stex: RMS %.4f sigma\n", major, minor, name,
                    description.seed, size, live_size, rms);
        EXPECT_LT(rms, 0.01) << name;  // the baked route's tolerance (MeasurementPlaneMatchesCore)
    }
    // The tweak made another instance: a render that still showed the first file would fail above.
    EXPECT_GT(rms_difference_over_sigma(read_image_linear(out + "/tweaked.exr"), read_image_linear(out + "/plane.exr")), 0.3);
}

}  // namespace
