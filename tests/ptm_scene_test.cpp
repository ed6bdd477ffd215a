// POV-Ray scene test (CTest label "scene"): the relief test data of the ptm model (Lambertian
// reflection and cast shadows, core/src/relief_shading.cpp) rendered by POV-Ray from the same
// height map (scenes/ptm/relief.pov), so the "known model" the PTM acceptance numbers rest on
// is checked against an independent renderer. Skips without povray.
#include "test_support.h"

#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/relief_shading.h>

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;
using namespace stochtex;

namespace {

constexpr int size = 96;         // texels (and pixels) per side
constexpr double depth = 6;      // texels
constexpr int margin = 16;       // POV-Ray's field ends at its edges, ours repeats: compare inside

/// A size² crop of the rock scan, box-filtered by 4, as a 16-bit grey PNG (heights 0 … 1).
void write_height_map(const std::string& source, const std::string& path)
{
    const Image scan = read_image_linear(source, {"linear"});
    std::vector<float> heights(std::size_t(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double sum = 0;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) sum += scan.at(4 * x + i, 4 * y + j, 0);
            heights[std::size_t(y) * size + x] = float(sum / 16);
        }
    auto out = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(size, size, 1, OIIO::TypeDesc::UINT16);
    ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, heights.data()) && out->close());
}

}  // namespace

TEST(PtmScene, PovRayRendersTheReliefModelLikeTheCore)
{
    if (!test::on_path("povray")) GTEST_SKIP() << "povray is not on PATH (apt-get install povray)";
    const std::string scan = test::shared_exemplar("rock_height.png");
    if (scan.empty()) GTEST_SKIP() << "../shared/exemplars is absent";
    const fs::path dir = test::temp_dir("ptm-scene");
    write_height_map(scan, (dir / "relief_height.png").string());
    const ReliefSurface surface = make_relief_surface((dir / "relief_height.png").string(), 1, depth);
    const fs::path scene = fs::path(STOCHTEX_SOURCE_DIR) / "scenes" / "ptm" / "relief.pov";
    std::vector<Vec3> lights = spiral_light_directions(3, 25, 40);
    lights.push_back({-0.9077, -0.3304, 0.2588});  // 15° elevation: long cast shadows
    for (const Vec3& light : lights) {
        const std::string output = (dir / "pov.exr").string();
        const test::ProgramResult r = test::run_program(
            {"povray", "-D", "-A", "+FE", "+W" + std::to_string(size), "+H" + std::to_string(size), "+L" + dir.string(),
             "+I" + scene.string(), "+O" + output, "Declare=Size=" + std::to_string(size),
             "Declare=Depth=" + std::to_string(depth), "Declare=Light_X=" + std::to_string(light[0]),
             "Declare=Light_Y=" + std::to_string(light[1]), "Declare=Light_Z=" + std::to_string(light[2])},
            dir.string());
        ASSERT_TRUE(r.succeeded()) << r;
        const Image pov = read_image_linear(output, {"linear"});
        const Image core = shade_relief(surface, light);
        double sum_a = 0, sum_b = 0, sum_ab = 0, sum_aa = 0, sum_bb = 0, difference = 0, n = 0;
        long long shadow_a = 0, shadow_b = 0;
        for (int y = margin; y < size - margin; ++y)
            for (int x = margin; x < size - margin; ++x)
                for (int c = 0; c < 3; ++c) {
                    const double a = core.at(x, y, c), b = pov.at(x, y, c);
                    sum_a += a, sum_b += b, sum_ab += a * b, sum_aa += a * a, sum_bb += b * b, n += 1;
                    difference += (a - b) * (a - b);
                    shadow_a += a < 1e-4, shadow_b += b < 1e-4;
                }
        const double mean_a = sum_a / n, mean_b = sum_b / n;
        const double correlation = (sum_ab / n - mean_a * mean_b) /
                                   std::sqrt((sum_aa / n - mean_a * mean_a) * (sum_bb / n - mean_b * mean_b));
        std::printf("[ scene ] light (%+.2f, %+.2f, %.2f): mean %.4f (POV-Ray %.4f), correlation %.4f, RMS difference "
                    "%.1f %% of the mean, in shadow %.1f %% (POV-Ray %.1f %%)\n",
                    light[0], light[1], light[2], mean_a, mean_b, correlation, 100 * std::sqrt(difference / n) / mean_a,
                    100.0 * shadow_a / n, 100.0 * shadow_b / n);
        // The residue is where the models differ by construction: POV-Ray intersects triangles and
        // interpolates vertex normals, the core uses central differences and a marched bilinear
        // field; the albedo ramp is a 10-step colour map in POV-Ray.
        EXPECT_NEAR(mean_b / mean_a, 1.0, 0.01);
        EXPECT_GT(correlation, 0.98);
        EXPECT_NEAR(double(shadow_b), double(shadow_a), 0.02 * n);
    }
}
