// OSL shaders compiled and rendered by Cycles' own OSL (issue 34; docs/osl.md): every shipped
// osl/*.osl and every shader `stex osl` writes goes through a Script node (external file, Cycles
// on the CPU with the OSL shading system: scenes/blender/osl_plane.py) on a plane under an
// orthographic camera, and each render is compared with the core at the same points.
//
// The Blender is the `blender` on PATH: the bpy lane (scripts/bpy-lane.sh, label "bpy") puts the
// official builds there (bpy 4.5 LTS and 5.2, which have OSL); Debian's Blender has none, and
// the test skips with that reason.
//
// The footprint is checked, not assumed: a probe shader renders Dx(P), Dy(P) and P. At SIZE²
// pixels over the unit square every shading point must see |Dx(P)| = |Dy(P)| = 1 / SIZE (a 1 %
// error can move a filter across a step: issue 34's testshade finding) and P within the pixel
// (Cycles' pixel filter, 0.01 px wide, places the one sample near the centre). The core is
// evaluated at the P each pixel's sample actually used (the probe's render, same seed: the
// same sample positions), so the filter's offset is no difference.
#include "test_support.h"

#include <stochtex/analysis.h>
#include <stochtex/image.h>
#include <stochtex/models/tiling.h>
#include <stochtex/osl/osl_shader.h>
#include <stochtex/texture.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace stochtex;

constexpr int size = 128;  // render pixels per side

/// The shaders' own agreement with the core in C++ (tests/osl_*_test.cpp) and under testshade
/// (docs/osl.md: wavelet ≤ 1.4e-5 σ RMS, gabor ≤ 1.9e-4 σ RMS with 1–4 pixels at 3.8e-2 σ on
/// kernels' support edges, tiling colour ≤ 6e-5 σ RMS and 3.3e-3 σ at most): RMS within 1e-3 σ,
/// every pixel within 1e-2 σ (gabor: 0.1 σ, its support edges). A wrong footprint, coordinate
/// or colour stage moves a whole render by tenths of σ and more.
constexpr double rms_limit_sigma = 1e-3, max_limit_sigma = 1e-2, gabor_max_limit_sigma = 0.1;

struct Case {
    std::string name;
    TextureDescription description;
    double footprint_px;  ///< photo pixels per render pixel
    bool solid = false;
    double max_limit = max_limit_sigma;
};

const Image& photo()
{
    static const Image image = read_image_linear(test::repo_exemplar("concrete_512.png"));
    return image;
}

TextureDescription analysed(const std::string& model, HistogramMode histogram, bool joint_colour = false,
                            std::vector<std::pair<std::string, std::string>> model_options = {}, int max_bands = 0)
{
    AnalysisOptions options;
    options.model = model;
    options.histogram = histogram;
    options.joint_colour = joint_colour;
    if (max_bands > 0) options.max_bands = max_bands;
    options.model_options = std::move(model_options);
    return analyze(photo(), options);
}

std::vector<Case> cases()
{
    const TextureDescription wavelet = analysed("wavelet", HistogramMode::on);
    // gabor: the six finest octaves (every frequency range, seconds per analysis; osl_gabor_test).
    const TextureDescription gabor = analysed("gabor", HistogramMode::on, false, {{"gabor-kind", "isotropic"}}, 6);
    const TextureDescription tiling = analysed("tiling", HistogramMode::on, false, {{"exemplar-size", "128"}});
    TilingSourceOptions normal_options;
    normal_options.exemplar_size = 64;
    return {
        {"wavelet_2d", wavelet, 1.0},
        {"wavelet_solid", wavelet, 1.0, true},
        {"wavelet_joint_colour", analysed("wavelet", HistogramMode::on, true), 2.0},
        {"gabor_2d", gabor, 2.0, false, gabor_max_limit_sigma},
        {"gabor_solid", gabor, 2.0, true, gabor_max_limit_sigma},
        {"tiling_colour_1px", tiling, 1.0},
        {"tiling_colour_4px", tiling, 4.0},
        {"tiling_normal_map", normal_map_texture(photo(), 8, normal_options), 2.0},
    };
}

/// The probe: what Cycles hands a shader on the plane (tests the camera's footprint).
const char* probe_shader = R"(shader stochtex_probe(
    point Vector = P,
    output color DxP = 0,
    output color DyP = 0,
    output color Position = 0)
{
    vector dx = Dx(Vector), dy = Dy(Vector);
    DxP = color(dx[0], dx[1], dx[2]);
    DyP = color(dy[0], dy[1], dy[2]);
    Position = color(Vector[0], Vector[1], Vector[2]);
}
)";

/// What the generated shaders' row probe reads in this host (osl/stochtex_subset.h): 0 where
/// texture() runs rows top-down, 1 where bottom-up. Reported, so a run says which way it went.
std::string rows_shader(const std::string& probe)
{
    return "shader stochtex_rows(string probe = \"" + probe + "\", output color Rows = 0)\n"
           "{\n    Rows = color(texture(probe, 0.5, 0.25, \"interp\", \"closest\", \"width\", 0.0));\n}\n";
}

std::string blender_command(const std::string& jobs, const std::string& out)
{
    return "env TMPDIR=" + test::shell_quote(out) + " timeout 900 blender -b --factory-startup --python " +
           test::shell_quote(std::string(STOCHTEX_SOURCE_DIR) + "/scenes/blender/osl_plane.py") + " -- --jobs " +
           test::shell_quote(jobs) + " --out " + test::shell_quote(out) + " --size " + std::to_string(size);
}

nlohmann::json read_json(const std::string& path)
{
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

/// Each channel's standard deviation over an image: the unit the differences are stated in.
std::array<double, 3> channel_sigmas(const Image& image)
{
    std::array<double, 3> sum{}, sum2{}, sigma{};
    const double n = double(image.width) * image.height;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) sum[c] += image.at(x, y, c), sum2[c] += double(image.at(x, y, c)) * image.at(x, y, c);
    for (int c = 0; c < 3; ++c) sigma[c] = std::sqrt(std::max(1e-30, sum2[c] / n - (sum[c] / n) * (sum[c] / n)));
    return sigma;
}

struct Agreement {
    double rms_sigma = 0, max_sigma = 0;  ///< the worst channel's
};

Agreement agreement(const Image& core, const Image& cycles)
{
    const std::array<double, 3> sigma = channel_sigmas(core);
    Agreement result;
    for (int c = 0; c < 3; ++c) {
        double sum2 = 0, worst = 0;
        for (int y = 0; y < core.height; ++y)
            for (int x = 0; x < core.width; ++x) {
                const double d = std::abs(double(core.at(x, y, c)) - cycles.at(x, y, c));
                sum2 += d * d;
                worst = std::max(worst, d);
            }
        result.rms_sigma = std::max(result.rms_sigma, std::sqrt(sum2 / (double(core.width) * core.height)) / sigma[c]);
        result.max_sigma = std::max(result.max_sigma, worst / sigma[c]);
    }
    return result;
}

/// The core at the points and with the derivatives the probe saw (P, Dx(P), Dy(P) on the plane),
/// in the shader's coordinates: 2D (u, v) = (x, −y) · scale, solid (x, y, z) · scale.
Image core_at(const Texture& texture, const Image& position, const Image& dx, const Image& dy, double scale, bool solid)
{
    Image image(position.width, position.height, 3);
    for (int y = 0; y < position.height; ++y)
        for (int x = 0; x < position.width; ++x) {
            const auto at = [&](const Image& i, int c) { return double(i.at(x, y, c)) * scale; };
            Rgb value;
            if (solid) {
                SurfacePoint point;
                point.p = {at(position, 0), at(position, 1), at(position, 2)};
                point.dpdx = {at(dx, 0), at(dx, 1), at(dx, 2)};
                point.dpdy = {at(dy, 0), at(dy, 1), at(dy, 2)};
                value = texture.eval_solid(point);
            } else {
                value = texture.eval({at(position, 0), -at(position, 1)}, {at(dx, 0), -at(dx, 1), at(dy, 0), -at(dy, 1)});
            }
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(value[c]);
        }
    return image;
}

/// Whether the Blender on PATH has OSL (bpy.app.build_options.cycles_osl), from an empty job list.
bool blender_has_osl(const std::string& dir, std::string& log)
{
    std::ofstream(dir + "/none.json") << "[]";
    const auto result = test::run_command(blender_command(dir + "/none.json", dir + "/probe-osl"));
    log = result.output;
    if (result.status != 0) return false;
    return read_json(dir + "/probe-osl/osl_plane.json").value("cycles_osl", false);
}

/// One Blender run: every job compiled and, with `render`, the probe and the cases rendered
/// (the compile-only run costs a few seconds, the renders a minute on 2 cores).
struct BlenderRun {
    std::string skip;  ///< why the tests skip (no blender, no OSL), or empty
    std::string dir;
    nlohmann::json jobs, report;
    std::vector<Case> cases;
    std::vector<double> scales;  ///< each case's Scale
    test::CommandResult blender;
};

BlenderRun make_run(bool render)
{
    BlenderRun run;
    if (!test::on_path("blender")) {
        run.skip = "blender not on PATH (the bpy lane: scripts/bpy-lane.sh)";
        return run;
    }
    run.dir = test::temp_dir(render ? "cycles-osl-render" : "cycles-osl-compile");
    const std::string& dir = run.dir;
    std::string log;
    if (!blender_has_osl(dir, log)) {
        if (log.find("osl_plane: cycles_osl False") == std::string::npos)
            throw std::runtime_error("Blender did not answer whether it has OSL:\n" + log);
        run.skip = "this Blender has no OSL (bpy.app.build_options.cycles_osl is False; Debian's builds)";
        return run;
    }

    // The jobs: the probe (its three outputs), the four shipped shaders, and each case's
    // generated shader. Cycles writes the compiled .oso beside an external .osl (as Blender does
    // for an artist's file): the shipped shaders are compiled from a copy of osl/ with their
    // headers, not in the source tree.
    const std::string shipped_dir = dir + "/shipped";
    std::filesystem::create_directories(shipped_dir);
    for (const auto& entry : std::filesystem::directory_iterator(std::string(STOCHTEX_SOURCE_DIR) + "/osl"))
        if (entry.path().extension() == ".osl" || entry.path().extension() == ".h")
            std::filesystem::copy_file(entry.path(), shipped_dir + "/" + entry.path().filename().string(),
                                       std::filesystem::copy_options::overwrite_existing);
    nlohmann::json& jobs = run.jobs = nlohmann::json::array();
    std::ofstream(dir + "/probe.osl") << probe_shader;
    jobs.push_back({{"name", "probe_dx"}, {"osl", dir + "/probe.osl"}, {"output", "DxP"}, {"render", render}});
    jobs.push_back({{"name", "probe_dy"}, {"osl", dir + "/probe.osl"}, {"output", "DyP"}, {"render", render}});
    jobs.push_back({{"name", "probe_position"}, {"osl", dir + "/probe.osl"}, {"output", "Position"}, {"render", render}});
    for (const char* shipped : {"stochtex_wavelet", "stochtex_gabor", "stochtex_tiling", "stochtex_texture"})
        jobs.push_back({{"name", shipped},
                        {"osl", shipped_dir + "/" + shipped + ".osl"},
                        {"output", "Color"}, {"render", false}});
    run.cases = cases();
    for (const Case& c : run.cases) {
        osl::OslShaderOptions options;
        options.shader_name = "stochtex_" + c.name;
        options.images = osl::osl_image_paths(c.description, dir, c.name);
        std::ofstream(dir + "/" + c.name + ".osl") << osl::make_osl_shader(c.description, options);
        osl::write_osl_images(c.description, options.images);
        const double scale = c.footprint_px * size / c.description.pixels_per_unit;
        run.scales.push_back(scale);
        nlohmann::json inputs = {{"Scale", scale}};
        if (c.description.model != "tiling") inputs["Solid"] = c.solid ? 1 : 0;
        jobs.push_back({{"name", c.name}, {"osl", dir + "/" + c.name + ".osl"}, {"output", "Color"}, {"render", render},
                        {"inputs", inputs}});
    }
    // The row probe every generated shader here reads (one file, beside them), read on its own.
    std::ofstream(dir + "/rows.osl") << rows_shader(osl::osl_image_paths(run.cases.front().description, dir, "").rows_probe);
    jobs.push_back({{"name", "probe_rows"}, {"osl", dir + "/rows.osl"}, {"output", "Rows"}, {"render", render}});
    std::ofstream(dir + "/jobs.json") << jobs.dump(2);
    run.blender = test::run_command(blender_command(dir + "/jobs.json", dir));
    if (run.blender.status == 0) {
        run.report = read_json(dir + "/osl_plane.json");
        std::printf("%s, Cycles OSL, %dx%d\n", run.report["blender"].get<std::string>().c_str(), size, size);
    }
    return run;
}

const BlenderRun& compile_run()
{
    static const BlenderRun run = make_run(false);
    return run;
}

const BlenderRun& render_run()
{
    static const BlenderRun run = make_run(true);
    return run;
}

// A compile error is a failure with the compiler's message.
TEST(CyclesOsl, EveryShaderCompiles)
{
    const BlenderRun& run = compile_run();
    if (!run.skip.empty()) GTEST_SKIP() << run.skip;
    ASSERT_EQ(run.blender.status, 0) << run.blender.output;
    for (const auto& job : run.jobs) {
        const auto& entry = run.report["jobs"][job["name"].get<std::string>()];
        EXPECT_TRUE(entry["compiled"].get<bool>()) << job["osl"] << " does not compile:\n" << entry["messages"].get<std::string>();
    }
}

TEST(CyclesOsl, RendersMatchTheCore)
{
    const BlenderRun& run = render_run();
    if (!run.skip.empty()) GTEST_SKIP() << run.skip;
    ASSERT_EQ(run.blender.status, 0) << run.blender.output;
    const std::string& dir = run.dir;
    const nlohmann::json& report = run.report;
    // The footprint and positions Cycles gave. Cycles keeps ray differentials compact (one
    // spread per ray) and hands OSL Dx(P), Dy(P) as two orthogonal tangent vectors of that length
    // whose directions come from the normal, not from the screen's axes: the footprint is the
    // pixel's size, turned (45° on this plane). So it is checked for its size and shape, and the
    // core gets the same Jacobian, pixel by pixel.
    ASSERT_TRUE(report["jobs"]["probe_dx"]["compiled"].get<bool>());
    const Image dx = read_image_linear(dir + "/probe_dx.exr"), dy = read_image_linear(dir + "/probe_dy.exr");
    const Image position = read_image_linear(dir + "/probe_position.exr");
    ASSERT_EQ(dx.width, size);
    ASSERT_EQ(position.width, size);
    double length_error = 0, skew = 0, out_of_plane = 0, offset = 0, turn = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const double ax = dx.at(x, y, 0) * size, ay = dx.at(x, y, 1) * size, az = dx.at(x, y, 2) * size;
            const double bx = dy.at(x, y, 0) * size, by = dy.at(x, y, 1) * size, bz = dy.at(x, y, 2) * size;
            length_error = std::max({length_error, std::abs(std::hypot(ax, ay, az) - 1), std::abs(std::hypot(bx, by, bz) - 1)});
            skew = std::max(skew, std::abs(ax * bx + ay * by + az * bz));
            out_of_plane = std::max({out_of_plane, std::abs(az), std::abs(bz)});
            turn = std::max(turn, std::atan2(std::abs(ay), std::abs(ax)) * 180 / M_PI);
            offset = std::max({offset, std::abs(double(position.at(x, y, 0)) * size - (x + 0.5)),
                               std::abs(double(position.at(x, y, 1)) * size - (size - y - 0.5)),
                               std::abs(double(position.at(x, y, 2)) * size)});
        }
    std::printf("footprint: | |Dx(P)|, |Dy(P)| | x %d - 1 <= %.1e, Dx.Dy <= %.1e, out of the plane <= %.1e px,"
                " turned by up to %.1f deg from the screen axes; P within %.4f px of the pixel centres\n",
                size, length_error, skew, out_of_plane, turn, offset);
    EXPECT_LT(length_error, 1e-3) << "Cycles' footprint is not the pixel's size: a filter would cross its steps elsewhere";
    EXPECT_LT(skew, 1e-3);
    EXPECT_LT(out_of_plane, 1e-3);
    EXPECT_LT(offset, 0.01) << "the render does not frame the unit square pixel for pixel";

    // Which way this host runs rows: the shaders adapt (the comparisons below hold either way).
    ASSERT_TRUE(report["jobs"]["probe_rows"]["compiled"].get<bool>());
    const Image rows = read_image_linear(dir + "/probe_rows.exr");
    const double row_probe = rows.at(size / 2, size / 2, 0);
    std::printf("row probe: %.6g (texture() rows run %s in this host)\n", row_probe, row_probe > 0.5 ? "bottom-up" : "top-down");
    EXPECT_LT(std::min(std::abs(row_probe), std::abs(row_probe - 1)), 1e-3) << "the probe's texels are 0 and 1";

    for (std::size_t i = 0; i < run.cases.size(); ++i) {
        const Case& c = run.cases[i];
        if (!report["jobs"][c.name]["compiled"].get<bool>()) continue;
        const Image cycles = read_image_linear(dir + "/" + c.name + ".exr");
        const Image core = core_at(*make_texture(c.description), position, dx, dy, run.scales[i], c.solid);
        write_image(dir + "/" + c.name + ".core.exr", core);  // beside Cycles' render, to look at
        const Agreement a = agreement(core, cycles);
        std::printf("  %-22s footprint %.0f px: RMS %.2e sigma, max %.2e sigma (render %.2f s)\n", c.name.c_str(),
                    c.footprint_px, a.rms_sigma, a.max_sigma, report["jobs"][c.name]["render_seconds"].get<double>());
        EXPECT_LT(a.rms_sigma, rms_limit_sigma) << c.name;
        EXPECT_LT(a.max_sigma, c.max_limit) << c.name;
    }
}

}  // namespace
