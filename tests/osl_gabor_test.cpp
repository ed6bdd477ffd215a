// The gabor OSL shader (osl/stochtex_gabor.h, docs/osl.md): its 64-bit random draws against the
// core's bit for bit, its maths compiled as C++ (osl_shim.h) against GaborTexture::eval /
// eval_solid at thousands of points, point-sampled and filtered (isotropic and anisotropic
// footprints, 2D and sliced solid, every gabor kind - the oriented kind's per-impulse choice
// too - with and without histogram maps), and oslc / testshade where OSL is installed.
#include "test_support.h"

#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/models/gabor_parameters.h>
#include <stochtex/osl/osl_shader.h>
#include <stochtex/render.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include "models/gabor/gabor_noise.h"
#include "models/gabor/gabor_texture.h"
#include "numerics/random.h"
#include "osl_shim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

namespace osl_shim {
#include "../osl/stochtex_gabor.h"
}  // namespace osl_shim

namespace {

using namespace stochtex;

void to_limbs(std::uint64_t value, int limbs[4])
{
    for (int k = 0; k < 4; ++k) limbs[k] = int((value >> (16 * k)) & 0xffff);
}

std::uint64_t from_limbs(const int limbs[4])
{
    std::uint64_t value = 0;
    for (int k = 0; k < 4; ++k) value |= std::uint64_t(limbs[k]) << (16 * k);
    return value;
}

TEST(OslGaborShader, SixtyFourBitArithmeticMatchesNativeIntegers)
{
    std::mt19937_64 rng(11);
    for (int n = 0; n < 20000; ++n) {
        const std::uint64_t a = rng(), b = n % 7 == 0 ? ~std::uint64_t(0) : rng();
        int la[4], lb[4], r[4];
        to_limbs(a, la);
        to_limbs(b, lb);
        osl_shim::stochtex_u64_mul(la, lb, r);
        ASSERT_EQ(from_limbs(r), a * b) << std::hex << a << " * " << b;
        osl_shim::stochtex_u64_add(la, lb, r);
        ASSERT_EQ(from_limbs(r), a + b);
        osl_shim::stochtex_u64_xorshift(la, 1 + n % 63, r);
        ASSERT_EQ(from_limbs(r), a ^ (a >> (1 + n % 63)));
        osl_shim::stochtex_u64_shift_right(la, n % 64, r);
        ASSERT_EQ(from_limbs(r), a >> (n % 64));
        // Unsigned order, also between values that differ in one low limb only.
        const std::uint64_t c = n % 3 == 0 ? a ^ std::uint64_t(n % 65536) : b;
        int lc[4];
        to_limbs(c, lc);
        ASSERT_EQ(osl_shim::stochtex_u64_less(la, lc), int(a < c)) << std::hex << a << " < " << c;
        ASSERT_EQ(osl_shim::stochtex_u64_bits(la, n % 64, 24), int((a >> (n % 64)) & 0xffffff));
        // SplitMix64::next() of state a (numerics/random.h): the core's mix64 after the gamma step.
        int state[4];
        to_limbs(a, state);
        osl_shim::stochtex_splitmix_next(state, r);
        SplitMix64 core(a);
        ASSERT_EQ(from_limbs(r), core.next());
        const int i = int(std::int32_t(std::uint32_t(rng())));
        osl_shim::stochtex_u64_from_int(i, r);
        ASSERT_EQ(from_limbs(r), std::uint64_t(std::int64_t(i)));
    }
}

TextureDescription concrete(HistogramMode histogram, GaborKind kind = GaborKind::isotropic, ColourMode colour = ColourMode::pca,
                            bool joint_colour = false)
{
    AnalysisOptions options;
    options.model = "gabor";
    options.histogram = histogram;
    options.colour_mode = colour;
    options.joint_colour = joint_colour;
    options.max_bands = 6;  // the six finest octaves: every frequency range, a few seconds per test
    options.model_options = {{"gabor-kind", to_string(kind)}};
    return analyze(read_image_linear(test::repo_exemplar("concrete_512.png")), options);
}

/// A generated shader evaluated through the shim.
class GaborShim {
public:
    GaborShim(const TextureDescription& description, const std::string& dir)
    {
        osl::OslShaderOptions options;
        options.shader_name = "stochtex_test";
        options.images = osl::osl_image_paths(description, dir, "test");
        text = osl::make_osl_shader(description, options);
        osl::write_osl_images(description, options.images);
        p = osl_test::parse_parameters(text);
        osl_shim::load_image(p.s("sphere_table"));
        osl_shim::load_image(p.s("rows_probe"));
    }

    /// 2D: p = (u, v), dpdx = (dudx, dvdx), dpdy = (dudy, dvdy); solid: as SurfacePoint. As the
    /// shader: the row probe read first (rows_bottom_up < 0), then the texture; or with the row
    /// flag given (a shader that ignored the probe would pass 0).
    Rgb eval(bool solid, const Vec3& point, const Vec3& normal, const Vec3& dpdx, const Vec3& dpdy,
             int rows_bottom_up = -1)
    {
        if (rows_bottom_up < 0) rows_bottom_up = osl_shim::stochtex_rows_bottom_up(p.s("rows_probe"));
        float pp[3], nn[3], dx[3], dy[3];
        for (int e = 0; e < 3; ++e) {
            pp[e] = float(point[e]);
            nn[e] = float(normal[e]);
            dx[e] = float(dpdx[e]);
            dy[e] = float(dpdy[e]);
        }
        float r = 0, g = 0, b = 0;
        osl_shim::stochtex_gabor(solid, pp, nn, dx, dy, p.f("pixels_per_unit"), p.n("octave_count"), p.a("octave"),
                                 p.i("key_2d"), p.i("key_3d"), p.i("oriented_below"), p.n("kind"), p.a("direction"), p.f("direction_length"),
                                 p.a("plane_e1"), p.a("plane_e2"), p.n("channels"), p.a("sigma_m"), p.i("knot_count"),
                                 p.a("knot_z"), p.a("knot_value"), p.a("knot_slope"), p.a("gh_node"), p.a("gh_weight"),
                                 p.n("joint_count"), p.f("joint_first"), p.f("joint_inverse_step"), p.a("joint_curve"),
                                 p.a("mean"), p.a("basis"), p.s("sphere_table"), p.n("sphere_table_size"),
                                 p.f("sphere_table_step"), rows_bottom_up, r, g, b);
        return {r, g, b};
    }

    std::string text;
    osl_test::ShaderParameters p;
};

TEST(OslGaborShader, ImpulsesMatchTheCoreBitForBit)
{
    const TextureDescription description = concrete(HistogramMode::off);
    const std::string dir = test::temp_dir("oslgaborbits");
    GaborShim shim(description, dir);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> position(-2000.0, 2000.0);
    int compared = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const GaborNoise noise(gabor_octave(description, k));
        int key_2d[4], key_3d[4];
        for (int l = 0; l < 4; ++l) key_2d[l] = shim.p.i("key_2d")[4 * k + l], key_3d[l] = shim.p.i("key_3d")[4 * k + l];
        const double cell = noise.cell_size_2d()[0], cell_3d = noise.cell_size_3d(), r = noise.radius();
        for (int n = 0; n < 50; ++n) {
            const double x = position(rng), y = position(rng), z = position(rng);
            // impulses_near_2d: rows j, then columns i, over the support's bounding cells.
            const auto impulses = noise.impulses_near_2d(x, y);
            const int i0 = int(std::floor((x - r) / cell)), i1 = int(std::floor((x + r) / cell));
            const int j0 = int(std::floor((y - r) / cell));
            ASSERT_EQ(impulses.size() % std::size_t(i1 - i0 + 1), 0u);
            for (std::size_t m = 0; m < impulses.size(); ++m) {
                const int i = i0 + int(m % std::size_t(i1 - i0 + 1)), j = j0 + int(m / std::size_t(i1 - i0 + 1));
                int key[4], bits[4], attributes[4];
                osl_shim::stochtex_gabor_cell_key(key_2d, 2, i, j, 0, key);
                osl_shim::stochtex_mix64(key, bits);
                osl_shim::stochtex_gabor_attributes(key, attributes);
                EXPECT_EQ((i + double(osl_shim::stochtex_gabor_fraction(bits, 0))) * cell, impulses[m].position[0]);
                EXPECT_EQ((j + double(osl_shim::stochtex_gabor_fraction(bits, 21))) * cell, impulses[m].position[1]);
                for (int c = 0; c < 3; ++c)
                    EXPECT_EQ(osl_shim::stochtex_u64_bits(attributes, 10 * c, 10),
                              int(std::lround(impulses[m].phase[c] * 1024 / (2 * M_PI))));
                float omega[3], orientation[3] = {0, 0, 0};
                int below[4] = {0, 0, 0, 0};
                osl_shim::stochtex_gabor_frequency(shim.p.n("kind"), float(noise.parameters().frequency), shim.p.a("direction"),
                                                   shim.p.f("direction_length"), shim.p.a("plane_e1"), shim.p.a("plane_e2"),
                                                   orientation, below, key, attributes, omega);
                EXPECT_NEAR(omega[0], impulses[m].omega[0], 1e-6 * noise.parameters().frequency);
                EXPECT_NEAR(omega[1], impulses[m].omega[1], 1e-6 * noise.parameters().frequency);
                ++compared;
            }
            // impulses_near_3d: k, j, i over the support's bounding cells.
            const auto solid = noise.impulses_near_3d({x, y, z});
            int lo[3], count[3];
            const double p3[3] = {x, y, z};
            for (int e = 0; e < 3; ++e) {
                lo[e] = int(std::floor((p3[e] - r) / cell_3d));
                count[e] = int(std::floor((p3[e] + r) / cell_3d)) - lo[e] + 1;
            }
            ASSERT_EQ(solid.size(), std::size_t(count[0] * count[1] * count[2]));
            for (std::size_t m = 0; m < solid.size(); ++m) {
                const int i = lo[0] + int(m % count[0]), j = lo[1] + int(m / count[0] % count[1]),
                          kk = lo[2] + int(m / (count[0] * count[1]));
                int key[4], bits[4];
                osl_shim::stochtex_gabor_cell_key(key_3d, 3, i, j, kk, key);
                osl_shim::stochtex_mix64(key, bits);
                EXPECT_EQ((i + double(osl_shim::stochtex_gabor_fraction(bits, 0))) * cell_3d, solid[m].position[0]);
                EXPECT_EQ((j + double(osl_shim::stochtex_gabor_fraction(bits, 21))) * cell_3d, solid[m].position[1]);
                EXPECT_EQ((kk + double(osl_shim::stochtex_gabor_fraction(bits, 42))) * cell_3d, solid[m].position[2]);
                ++compared;
            }
        }
    }
    EXPECT_GT(compared, 10000);
}

/// Kind oriented on the concrete photo, with orientations and shares set to cover the range: all
/// oriented (p = 1), none (p = 0), θ = ±90° and oblique angles, shares between.
TextureDescription oriented_concrete(HistogramMode histogram)
{
    TextureDescription description = concrete(histogram, GaborKind::oriented);
    GaborParameters& gabor = description.parameters.get<GaborParameters>();
    const double degrees[] = {-90, -53.5, 0, 17.25, 64, 90}, shares[] = {1, 0.62, 0, 0.35, 0.9, 0.2};
    for (std::size_t k = 0; k < gabor.frequencies.size(); ++k) {
        gabor.orientations[k] = degrees[k % 6];
        gabor.oriented_fractions[k] = shares[k % 6];
    }
    validate(description, "oriented concrete");
    return description;
}

TEST(OslGaborShader, OrientedImpulsesMatchTheCoreBitForBit)
{
    // Each impulse's frequency, hence its oriented-or-isotropic draw, against the core's impulses
    // (2D: projected, solid: 3D). A wrong draw gives an unrelated frequency, ~F off.
    const TextureDescription description = oriented_concrete(HistogramMode::off);
    ASSERT_EQ(description.parameters.get<GaborParameters>().kind, GaborKind::oriented);
    GaborShim shim(description, test::temp_dir("oslgaborientedbits"));
    const int* below_all = shim.p.i("oriented_below");
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> position(-2000.0, 2000.0);
    for (std::size_t k = 0; k < 6; ++k) {
        const GaborNoise noise(gabor_octave(description, k));
        const double f = noise.parameters().frequency;
        int key_2d[4], key_3d[4], below[4];
        for (int l = 0; l < 4; ++l)
            key_2d[l] = shim.p.i("key_2d")[4 * k + l], key_3d[l] = shim.p.i("key_3d")[4 * k + l], below[l] = below_all[4 * k + l];
        EXPECT_EQ(from_limbs(below), noise.oriented_bound()) << k;
        float orientation[3];
        for (int e = 0; e < 3; ++e) orientation[e] = shim.p.a("octave")[k * STOCHTEX_GABOR_STRIDE + STOCHTEX_GABOR_ORIENTATION + e];
        const double cell = noise.cell_size_2d()[0], cell_3d = noise.cell_size_3d(), r = noise.radius();
        int oriented = 0, total = 0;
        for (int n = 0; n < 40; ++n) {
            const double x = position(rng), y = position(rng), z = position(rng);
            const auto impulses = noise.impulses_near_2d(x, y);
            const int i0 = int(std::floor((x - r) / cell)), i1 = int(std::floor((x + r) / cell));
            const int j0 = int(std::floor((y - r) / cell));
            for (std::size_t m = 0; m < impulses.size(); ++m) {
                const int i = i0 + int(m % std::size_t(i1 - i0 + 1)), j = j0 + int(m / std::size_t(i1 - i0 + 1));
                int key[4], attributes[4];
                osl_shim::stochtex_gabor_cell_key(key_2d, 2, i, j, 0, key);
                osl_shim::stochtex_gabor_attributes(key, attributes);
                float omega[3];
                osl_shim::stochtex_gabor_frequency(shim.p.n("kind"), float(f), shim.p.a("direction"), shim.p.f("direction_length"),
                                                   shim.p.a("plane_e1"), shim.p.a("plane_e2"), orientation, below, key,
                                                   attributes, omega);
                ASSERT_NEAR(omega[0], impulses[m].omega[0], 1e-6 * f) << "octave " << k << " cell " << i << ", " << j;
                ASSERT_NEAR(omega[1], impulses[m].omega[1], 1e-6 * f) << "octave " << k << " cell " << i << ", " << j;
                oriented += osl_shim::stochtex_gabor_is_oriented(key, below);
                ++total;
            }
            const auto solid = noise.impulses_near_3d({x, y, z});
            int lo[3], count[3];
            const double p3[3] = {x, y, z};
            for (int e = 0; e < 3; ++e) {
                lo[e] = int(std::floor((p3[e] - r) / cell_3d));
                count[e] = int(std::floor((p3[e] + r) / cell_3d)) - lo[e] + 1;
            }
            ASSERT_EQ(solid.size(), std::size_t(count[0] * count[1] * count[2]));
            for (std::size_t m = 0; m < solid.size(); ++m) {
                const int i = lo[0] + int(m % count[0]), j = lo[1] + int(m / count[0] % count[1]),
                          kk = lo[2] + int(m / (count[0] * count[1]));
                int key[4], attributes[4];
                osl_shim::stochtex_gabor_cell_key(key_3d, 3, i, j, kk, key);
                osl_shim::stochtex_gabor_attributes(key, attributes);
                float omega[3];
                osl_shim::stochtex_gabor_frequency(shim.p.n("kind"), float(f), shim.p.a("direction"), shim.p.f("direction_length"),
                                                   shim.p.a("plane_e1"), shim.p.a("plane_e2"), orientation, below, key,
                                                   attributes, omega);
                for (int e = 0; e < 3; ++e) ASSERT_NEAR(omega[e], solid[m].omega[e], 1e-6 * f) << "octave " << k << " axis " << e;
                oriented += osl_shim::stochtex_gabor_is_oriented(key, below);
                ++total;
            }
        }
        // The draws' share is the octave's p (binomial: 4 σ bounds), exactly 0 and 1 at the ends.
        const double p = description.parameters.get<GaborParameters>().oriented_fractions[k];
        const double share = double(oriented) / total, bound = 4 * std::sqrt(p * (1 - p) / total);
        std::printf("octave %zu: p %.2f, %d of %d impulses oriented (%.4f)\n", k, p, oriented, total, share);
        EXPECT_NEAR(share, p, bound + 1e-12) << k;
    }
}

// ---- The shader against the core ----------------------------------------------------------------

/// A footprint in texture units per pixel: columns (dudx, dvdx), (dudy, dvdy) of a pixel
/// `size_px` exemplar pixels wide, stretched `anisotropy` times along a random direction.
struct Jacobian {
    double dudx, dvdx, dudy, dvdy;
};
Jacobian random_footprint(std::mt19937& rng, double size_px, double anisotropy, double ppu)
{
    std::uniform_real_distribution<double> angle(0, 2 * M_PI);
    const double a = angle(rng), c = std::cos(a), s = std::sin(a), major = size_px * anisotropy / ppu, minor = size_px / ppu;
    return {c * major, s * major, -s * minor, c * minor};
}

/// Footprint classes: point sampling, then isotropic and anisotropic filters of several sizes.
struct FootprintClass {
    const char* name;
    double size_px, anisotropy;
};
const FootprintClass footprint_classes[] = {
    {"point", 0, 1},        {"iso 0.7px", 0.7, 1},   {"iso 2px", 2, 1},      {"iso 8px", 8, 1},
    {"iso 40px", 40, 1},    {"aniso 1px x4", 1, 4},  {"aniso 3px x8", 3, 8}, {"aniso 6px x16", 6, 16},
};

struct Agreement {
    double max_sigma = 0, rms_sigma = 0;
    int samples = 0, outliers = 0;  ///< channel samples, those more than 1e-4 σ off
};

/// |shader − core| in units of each RGB channel's σ (the core's point samples), per footprint class.
std::vector<Agreement> compare(const TextureDescription& description, bool solid, int points_per_class, const std::string& label)
{
    const std::string dir = test::temp_dir("oslgabor");
    GaborShim shim(description, dir);
    const auto texture = make_texture(description);
    const double ppu = description.pixels_per_unit;
    std::mt19937 rng(solid ? 21 : 12);
    std::uniform_real_distribution<double> position(-3.0, 3.0), unit(-1.0, 1.0);
    auto f32 = [](double v) { return double(float(v)); };  // the shader's inputs are floats

    const std::array<double, 3> sigma = osl_test::channel_sigmas(*texture);

    std::vector<Agreement> result;
    for (const FootprintClass& fc : footprint_classes) {
        Agreement agreement;
        double squares = 0;
        int outliers = 0;
        for (int n = 0; n < points_per_class; ++n) {
            const Vec3 p{f32(position(rng)), f32(position(rng)), f32(position(rng))};
            Jacobian j = random_footprint(rng, fc.size_px, fc.anisotropy, ppu);
            j = {f32(j.dudx), f32(j.dvdx), f32(j.dudy), f32(j.dvdy)};
            Rgb core, osl;
            if (solid) {
                // A random tangent plane; the footprint's columns along its two axes.
                Vec3 n{unit(rng), unit(rng), unit(rng)};
                const TangentFrame frame = tangent_frame(n, {0, 0, 0});
                n = {f32(frame.n[0]), f32(frame.n[1]), f32(frame.n[2])};
                Vec3 dpdx, dpdy;
                for (int e = 0; e < 3; ++e) {
                    dpdx[e] = f32(j.dudx * frame.t[e] + j.dvdx * frame.b[e]);
                    dpdy[e] = f32(j.dudy * frame.t[e] + j.dvdy * frame.b[e]);
                }
                SurfacePoint point;
                point.p = p;
                point.n = n;
                point.dpdx = dpdx;
                point.dpdy = dpdy;
                core = texture->eval_solid(point);
                osl = shim.eval(true, p, n, dpdx, dpdy);
            } else {
                core = texture->eval({p[0], p[1]}, Footprint2D{j.dudx, j.dvdx, j.dudy, j.dvdy});
                osl = shim.eval(false, {p[0], p[1], 0}, {0, 0, 0}, {j.dudx, j.dvdx, 0}, {j.dudy, j.dvdy, 0});
            }
            for (int c = 0; c < 3; ++c) {
                const double e = std::abs(double(osl[c]) - core[c]) / sigma[c];
                outliers += e > 1e-4;
                agreement.max_sigma = std::max(agreement.max_sigma, e);
                squares += e * e;
                ++agreement.samples;
            }
        }
        agreement.rms_sigma = std::sqrt(squares / agreement.samples);
        agreement.outliers = outliers;
        std::printf("gabor OSL vs core  %-22s %-5s %-14s max %.2e sigma  rms %.2e sigma  %d of %d channel samples > 1e-4 sigma\n",
                    label.c_str(), solid ? "solid" : "2D", fc.name, agreement.max_sigma, agreement.rms_sigma, outliers,
                    agreement.samples);
        result.push_back(agreement);
    }
    return result;
}

// Tolerances, in units of the channel's σ. The shader runs in float where the core runs in
// double (impulse offsets are exact to ~1e-7 px: cell sides as hi + lo); typical samples agree to
// ~1e-5 σ. The outliers are kernels at the 5 % edge of their truncated support that one side
// keeps and the other does not: each moves a value by ≤ 0.05 × a kernel's amplitude, measured
// ≤ 0.035 σ, in ~0.1–1 % of samples, most often where a footprint axis is about one exemplar pixel
// (the photo's own blur is then subtracted from the filter: float cancellation in its short axis).
// A wrong impulse, phase, filter, fade or retained variance moves values by ~0.1–1 σ everywhere.
// So: max ≤ 0.05 σ, RMS ≤ 3e-3 σ, and ≥ 99 % of channel samples within 1e-4 σ (typical: 2e-6).
constexpr double max_tolerance = 0.05, rms_tolerance = 3e-3, outlier_fraction = 0.01;

void expect_agreement(const std::vector<Agreement>& agreements)
{
    for (std::size_t k = 0; k < agreements.size(); ++k) {
        EXPECT_LT(agreements[k].max_sigma, max_tolerance) << footprint_classes[k].name;
        EXPECT_LT(agreements[k].rms_sigma, rms_tolerance) << footprint_classes[k].name;
        EXPECT_LE(agreements[k].outliers, outlier_fraction * agreements[k].samples) << footprint_classes[k].name;
    }
}

TEST(OslGaborShader, TwoDimensionalMatchesCore)
{
    expect_agreement(compare(concrete(HistogramMode::on), false, 400, "isotropic, histograms"));
    expect_agreement(compare(concrete(HistogramMode::off), false, 250, "isotropic, Gaussian"));
}

TEST(OslGaborShader, SolidMatchesCore)
{
    expect_agreement(compare(concrete(HistogramMode::on), true, 400, "isotropic, histograms"));
}

TEST(OslGaborShader, AnisotropicAndHybridKindsMatchCore)
{
    for (const GaborKind kind : {GaborKind::anisotropic, GaborKind::hybrid}) {
        const TextureDescription description = concrete(HistogramMode::on, kind);
        const std::string label = std::string(to_string(kind)) + ", histograms";
        expect_agreement(compare(description, false, 150, label));
        expect_agreement(compare(description, true, 150, label));
    }
}

TEST(OslGaborShader, OrientedKindMatchesCore)
{
    const TextureDescription description = oriented_concrete(HistogramMode::on);
    expect_agreement(compare(description, false, 250, "oriented, histograms"));
    expect_agreement(compare(description, true, 250, "oriented, histograms"));
}

TEST(OslGaborShader, OrientedPhotoDefaultAnalysisMatchesCore)
{
    // What `stex analyze --model gabor` now writes for an oriented photo: --gabor-kind auto gives
    // kind oriented on the sand dunes (ripples oriented, the finest grain isotropic).
    const std::string path = test::shared_exemplar("sand_dunes.png");
    if (path.empty()) GTEST_SKIP() << "../shared/exemplars/sand_dunes.png missing";
    AnalysisOptions options;
    options.model = "gabor";
    options.histogram = HistogramMode::on;
    options.max_bands = 6;
    const TextureDescription description = analyze(read_image_linear(path), options);
    ASSERT_EQ(description.parameters.get<GaborParameters>().kind, GaborKind::oriented);
    expect_agreement(compare(description, false, 150, "sand dunes auto"));
    expect_agreement(compare(description, true, 150, "sand dunes auto"));
}

TEST(OslGaborShader, RgbSharedColourModeMatchesCore)
{
    expect_agreement(compare(concrete(HistogramMode::automatic, GaborKind::isotropic, ColourMode::rgb_shared), false, 150,
                             "isotropic, rgb-shared"));
}

TEST(OslGaborShader, JointColourMatchesCore)
{
    // Joint colour (chroma given brightness): the curves' point and Gauss–Hermite-filtered forms,
    // at every footprint class, within the same tolerances as the independent channels.
    const TextureDescription description = concrete(HistogramMode::on, GaborKind::isotropic, ColourMode::pca, true);
    ASSERT_TRUE(description.chroma_given_brightness.enabled());
    expect_agreement(compare(description, false, 250, "isotropic, joint colour"));
    expect_agreement(compare(description, true, 250, "isotropic, joint colour"));
}

// A host whose texture() runs rows bottom-up (Cycles 5.2) gets the same texture through the row
// probe, bit for bit; the shader without it (flag 0 there) reads the sphere-average table
// mirrored, which the retained variance of filtered octaves shows (measured: up to 0.11 σ).
TEST(OslGaborShader, MirroringHostGivesTheSameTextureThroughTheRowProbe)
{
    const TextureDescription description = concrete(HistogramMode::on);
    GaborShim shim(description, test::temp_dir("oslgaborrows"));
    const std::array<double, 3> sigma = osl_test::channel_sigmas(*make_texture(description));
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> position(-3.0, 3.0);
    double unprobed = 0;  // in σ: the largest difference a shader ignoring the probe would show
    for (const FootprintClass& fc : footprint_classes) {
        for (int n = 0; n < 20; ++n) {
            const Vec3 p{position(rng), position(rng), 0};
            const Jacobian j = random_footprint(rng, fc.size_px, fc.anisotropy, description.pixels_per_unit);
            const auto shade = [&](int rows) {
                return shim.eval(false, p, {0, 0, 0}, {j.dudx, j.dvdx, 0}, {j.dudy, j.dvdy, 0}, rows);
            };
            unprobed = std::max(unprobed, osl_test::mirroring_host_difference(shade, sigma, fc.name));
        }
    }
    EXPECT_GT(unprobed, 0.01) << "the mirrored host must read other texels of the table";
}

TEST(OslGaborShader, GeneratedShaderIsSelfContained)
{
    const std::string dir = test::temp_dir("oslgaborself");
    GaborShim shim(concrete(HistogramMode::automatic), dir);
    osl_test::expect_self_contained(shim.text);
    EXPECT_NE(shim.text.find("void stochtex_mix64("), std::string::npos) << "the nested headers must be inlined too";
}

// ---- With OSL installed ---------------------------------------------------------------------------

TEST(OslGaborCompiler, GeneratedShaderCompilesAndTestshadeMatchesCore)
{
    if (!test::on_path("oslc") || !test::on_path("testshade")) GTEST_SKIP() << "oslc/testshade not on PATH (Debian packages no OSL): not run";
    const std::string dir = test::temp_dir("oslgabortestshade");
    const TextureDescription description = concrete(HistogramMode::on);
    // testshade --center shades pixel centres; the shader's (u, v) = (x, −y) (docs/osl.md).
    EXPECT_LT(osl_test::testshade_rms("gabor", GaborShim(description, dir).text, *make_texture(description), dir, 128, 0.25), 0.01);
}

}  // namespace
