// The lrp raster (lrp_raster.h): the SIMD kernels against the scalar reference, bit for bit, and
// both against a double-precision evaluation of the same terms, in units of the stratum's σ —
// over an ordinary raster and over a long row far from the origin (nothing accumulates along a
// row: every factor is computed from its own position, so the error must not grow).
#include "models/lrp/discrete_spectrum.h"
#include "models/lrp/lrp_fit.h"
#include "models/lrp/lrp_noise.h"
#include "models/lrp/lrp_raster.h"
#include "models/lrp/lrp_raster_kernels.h"
#include "models/lrp/lrp_window.h"
#include "numerics/fast_math.h"
#include "numerics/random.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace stochtex {
namespace {

constexpr double pi = 3.14159265358979323846;

/// A one-stratum noise of σ = 1 per channel (ring spectrum, paper Fig. 10), J cosines.
LrpStratumNoise ring_noise(int cosines, const std::array<double, 3>& sigma = {1, 1, 1})
{
    static const DiscreteSpectrum ring = ring_spectrum(256, 0.125, 0.01);
    LrpStratum stratum = lrp_for_spectrum(ring, cosines, 1).strata.front();
    stratum.sigma = sigma;
    return LrpStratumNoise(stratum, 256, {});
}

/// The stratum at (x, y) in double precision from the same drawn terms: exact window, std::cos.
void double_reference(const LrpStratumNoise& noise, const LrpFilter& filter, double x, double y, double out[3])
{
    const LrpLattice& lattice = noise.lattice();
    const std::int64_t cx = lattice.nearest(0, x), cy = lattice.nearest(1, y);
    double sum[3] = {0, 0, 0}, weight_squared = 0;
    LrpTerms terms;
    for (std::int64_t j = cy - 1; j <= cy + 1; ++j)
        for (std::int64_t i = cx - 1; i <= cx + 1; ++i) {
            const double dx = x - (lattice.origin[0] + double(i) * lattice.spacing[0]);
            const double dy = y - (lattice.origin[1] + double(j) * lattice.spacing[1]);
            const double w = lrp_window(std::hypot(dx / lattice.spacing[0], dy / lattice.spacing[1]));
            if (!(w > 0)) continue;
            weight_squared += w * w;
            terms.count = 0;
            noise.draw(i, j, filter, terms);
            for (int t = 0; t < terms.count; ++t) {
                const double theta = 2 * pi * (double(terms.fx()[t]) * dx + double(terms.fy()[t]) * dy);
                for (int c = 0; c < 3; ++c) sum[c] += w * (terms.re(c)[t] * std::cos(theta) - terms.im(c)[t] * std::sin(theta));
            }
        }
    for (int c = 0; c < 3; ++c) out[c] = sum[c] / std::sqrt(weight_squared);
}

struct Grid {
    std::vector<double> x, y;
    LrpRasterGrid view() const { return {x.data(), int(x.size()), y.data(), int(y.size())}; }
};

Grid make_grid(double x0, double dx, int width, double y0, double dy, int height)
{
    Grid g;
    for (int k = 0; k < width; ++k) g.x.push_back(x0 + (k + 0.5) * dx);
    for (int r = 0; r < height; ++r) g.y.push_back(y0 + (r + 0.5) * dy);
    return g;
}

/// Runs the raster over `grid`; checks every value against eval() (bit for bit) and returns the
/// per-pixel error against the double reference, in σ (= 1), channel by channel.
std::vector<double> raster_errors(const LrpStratumNoise& noise, const LrpFilter& filter, const Grid& grid,
                                  LrpRasterMethod method = LrpRasterMethod::automatic)
{
    const std::size_t pixels = grid.x.size() * grid.y.size();
    std::vector<float> out[3];
    for (auto& channel : out) channel.resize(pixels);
    float* const channels[3] = {out[0].data(), out[1].data(), out[2].data()};
    LrpTermCache terms;
    const LrpLattice& lattice = noise.lattice();
    const std::int64_t i0 = lattice.nearest(0, grid.x.front()) - 1, i1 = lattice.nearest(0, grid.x.back()) + 1;
    const std::int64_t j0 = lattice.nearest(1, grid.y.front()) - 1, j1 = lattice.nearest(1, grid.y.back()) + 1;
    terms.fill(i0, j0, int(i1 - i0 + 1), int(j1 - j0 + 1),
               [&](std::int64_t i, std::int64_t j, LrpTerms& t) { noise.draw(i, j, filter, t); });
    lrp_raster_stratum(noise, terms, grid.view(), channels, method);
    std::vector<double> errors;
    for (std::size_t r = 0; r < grid.y.size(); ++r)
        for (std::size_t k = 0; k < grid.x.size(); ++k) {
            const std::size_t p = r * grid.x.size() + k;
            float point[3];
            noise.eval(grid.x[k], grid.y[r], filter, point);
            double reference[3];
            double_reference(noise, filter, grid.x[k], grid.y[r], reference);
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(out[c][p], point[c]) << "pixel " << k << ", " << r << " channel " << c;
                errors.push_back(double(out[c][p]) - reference[c]);
            }
        }
    return errors;
}

/// lrp_raster_stratum_drawn (the lattice-row raster drawing its own terms) against eval(), bit for bit.
void drawn_matches_eval(const LrpStratumNoise& noise, const LrpFilter& filter, const Grid& grid)
{
    const std::size_t pixels = grid.x.size() * grid.y.size();
    std::vector<float> out[3];
    for (auto& channel : out) channel.resize(pixels);
    float* const channels[3] = {out[0].data(), out[1].data(), out[2].data()};
    lrp_raster_stratum_drawn(noise, filter, grid.view(), channels);
    for (std::size_t r = 0; r < grid.y.size(); ++r)
        for (std::size_t k = 0; k < grid.x.size(); ++k) {
            float point[3];
            noise.eval(grid.x[k], grid.y[r], filter, point);
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(out[c][r * grid.x.size() + k], point[c]) << "drawn, pixel " << k << ", " << r << " channel " << c;
        }
}

double max_abs(const std::vector<double>& e, std::size_t begin, std::size_t end)
{
    double m = 0;
    for (std::size_t i = begin; i < end; ++i) m = std::max(m, std::abs(e[i]));
    return m;
}

double rms(const std::vector<double>& e)
{
    double s = 0;
    for (double v : e) s += v * v;
    return std::sqrt(s / double(e.size()));
}

TEST(LrpRaster, SimdSineCosineIsTheScalarOneBitForBit)
{
    // The kernel's sin/cos is fast_sincos_turns operation for operation, on whatever target
    // Highway dispatched to: turns across ±2^12, quadrant borders included.
    SplitMix64 rng(3);
    std::vector<float> b(4096 + lrp_raster::padding), sine(b.size()), cosine(b.size());
    for (std::size_t k = 0; k < 4096; ++k) b[k] = float(8192 * rng.uniform() - 4096);
    for (int k = 0; k < 64; ++k) b[std::size_t(k)] = 0.125f * float(k - 32);  // exact eighths of a turn
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        SCOPED_TRACE(hwy::TargetName(target));
        for (float a : {1.0f, 0.0371f, -3.5f}) {
            lrp_raster::sincos_of_products(a, b.data(), 4096, sine.data(), cosine.data());
            for (std::size_t k = 0; k < 4096; ++k) {
                float s, c;
                fast_sincos_turns(a * b[k], s, c);
                ASSERT_EQ(sine[k], s) << a << " · " << b[k];
                ASSERT_EQ(cosine[k], c) << a << " · " << b[k];
            }
        }
    }
    hwy::SetSupportedTargetsForTest(0);
}

TEST(LrpRaster, RowDrawIsDrawBitForBit)
{
    // draw_row (SIMD, lattice points in the lanes) against draw() point by point, on every
    // target: unfiltered, a footprint that drops some of a window's terms and one that drops
    // more, plain and periodic (snapped frequencies, wrapped keys), separate and shared phases.
    static const DiscreteSpectrum ring = ring_spectrum(256, 0.125, 0.01);
    const LrpStratum stratum = lrp_for_spectrum(ring, 24, 1).strata.front();
    const auto bits = [](float v) {
        std::uint32_t b;
        std::memcpy(&b, &v, sizeof b);
        return b;
    };
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        SCOPED_TRACE(hwy::TargetName(target));
        for (const bool periodic : {false, true})
            for (const bool shared : {false, true}) {
                LrpStratumNoise::Options options;
                options.seed = 77, options.shared_phase = shared;
                if (periodic) options.period = {97.0, 61.0};
                const LrpStratumNoise noise(stratum, 256, options);
                constexpr std::size_t count = 37, stride = 64;
                std::vector<float> planes(8 * std::size_t(noise.term_count()) * stride, -1.0f);
                float* const plane[8] = {&planes[0], &planes[1 * planes.size() / 8], &planes[2 * planes.size() / 8],
                                         &planes[3 * planes.size() / 8], &planes[4 * planes.size() / 8],
                                         &planes[5 * planes.size() / 8], &planes[6 * planes.size() / 8],
                                         &planes[7 * planes.size() / 8]};
                for (double footprint : {0.0, 2.0, 7.0}) {
                    const LrpFilter filter = LrpFilter::from_footprint(Footprint2D::square(footprint), 1.0);
                    for (std::int64_t j : {-3, 0, 5}) {
                        const std::int64_t i_begin = -13;
                        const int most = noise.draw_row(i_begin, count, j, filter, plane, stride);
                        int expected_most = 0;
                        for (std::size_t w = 0; w < stride; ++w) {
                            LrpTerms terms;
                            if (w < count) noise.draw(i_begin + std::int64_t(w), j, filter, terms);
                            expected_most = std::max(expected_most, terms.live);
                            for (int t = 0; t < noise.term_count(); ++t)
                                for (int p = 0; p < 8; ++p) {
                                    const float expected = t < terms.live ? terms.data[p * LrpTerms::capacity + t] : 0.0f;
                                    ASSERT_EQ(bits(plane[p][std::size_t(t) * stride + w]), bits(expected))
                                        << "periodic " << periodic << " shared " << shared << " footprint " << footprint
                                        << " point " << w << ", " << j << " term " << t << " plane " << p;
                                }
                        }
                        EXPECT_EQ(most, expected_most);
                    }
                }
            }
    }
    hwy::SetSupportedTargetsForTest(0);
}

TEST(LrpRaster, EveryInstructionSetGivesTheSameRaster)
{
    // Determinism across machines: the raster on each target Highway compiled equals eval().
    // Both methods; steps of 0.8, 3.7 and 16 exemplar px (spacing 10.8: at 16 a vector spans
    // more windows than lanes, and the lattice-row raster gathers instead of permuting).
    const LrpStratumNoise noise = ring_noise(12);
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        SCOPED_TRACE(hwy::TargetName(target));
        for (double step : {0.8, 3.7, 16.0})
            for (const LrpRasterMethod method : {LrpRasterMethod::separable, LrpRasterMethod::lattice_rows})
                raster_errors(noise, LrpFilter{}, make_grid(3.3, step, 45, -7.9, step * 1.375, 5), method);
        for (double step : {0.8, 3.7, 16.0}) drawn_matches_eval(noise, LrpFilter{}, make_grid(3.3, step, 45, -7.9, step * 1.375, 5));
        // A footprint of 7 px keeps 8–17 of a window's 24 terms: windows of unequal term counts
        // side by side (the lattice-row raster's zero terms).
        // A stratum of channel 0 only (the turbulence's): the raster sums that channel alone.
        const LrpStratumNoise first_channel = ring_noise(12, {1, 0, 0});
        for (const LrpRasterMethod method : {LrpRasterMethod::separable, LrpRasterMethod::lattice_rows})
            raster_errors(first_channel, LrpFilter{}, make_grid(3.3, 0.8, 45, -7.9, 1.1, 5), method);
        const LrpStratumNoise wide = ring_noise(24);
        const LrpFilter filter = LrpFilter::from_footprint(Footprint2D::square(7.0), 1.0);
        for (double step : {0.8, 3.7}) {
            const Grid grid = make_grid(-40.2, step, 51, 12.9, step, 7);
            for (const LrpRasterMethod method : {LrpRasterMethod::separable, LrpRasterMethod::lattice_rows})
                raster_errors(wide, filter, grid, method);
            drawn_matches_eval(wide, filter, grid);
        }
    }
    hwy::SetSupportedTargetsForTest(0);
}

TEST(LrpRaster, MatchesThePointPathAndTheDoublePathWithinStatedTolerance)
{
    // 24 cosines per window, unfiltered and filtered (footprint 2 px), magnified, unit and
    // minified steps: eval() bit for bit; the double path within max 1e-5 σ, RMS 2e-6 σ
    // (measured 3.4e-6 and 6e-7: docs/models/lrp.md, "Precision").
    const LrpStratumNoise noise = ring_noise(24);
    for (const LrpRasterMethod method : {LrpRasterMethod::separable, LrpRasterMethod::lattice_rows})
        for (double step : {0.37, 1.0, 2.3})
            for (double footprint : {0.0, 2.0}) {
                const LrpFilter filter = LrpFilter::from_footprint(Footprint2D::square(footprint), 1.0);
                const Grid grid = make_grid(-101.3, step, 67, 55.1, step * 0.9, 9);
                const std::vector<double> errors = raster_errors(noise, filter, grid, method);
                // Filtered windows keep different numbers of terms: the drawn form's per-row counts.
                drawn_matches_eval(noise, filter, grid);
                const double max = max_abs(errors, 0, errors.size()), r = rms(errors);
                std::printf("%s, step %.2f px, footprint %.0f px: max %.2e sigma, RMS %.2e sigma over %zu values\n",
                            method == LrpRasterMethod::separable ? "separable" : "lattice rows", step, footprint, max, r,
                            errors.size());
                EXPECT_LT(max, 1e-5) << "step " << step;
                EXPECT_LT(r, 2e-6) << "step " << step;
            }
}

TEST(LrpRaster, LongRowFarFromTheOriginDoesNotDrift)
{
    // 16384 pixels of one row at 1/8 exemplar pixel per pixel, starting 2^24 exemplar pixels out:
    // windows 100+ pixels wide, where a phasor recurrence would accumulate rounding. The error
    // of the last 2048 pixels is that of the first 2048 (within 2×, both under the stated max).
    const LrpStratumNoise noise = ring_noise(8);
    const Grid grid = make_grid(16777216.0, 0.125, 16384, -3.0e6, 1.0, 1);
    const std::vector<double> errors = raster_errors(noise, LrpFilter{}, grid);
    const std::size_t band = 3 * 2048;
    const double first = max_abs(errors, 0, band), last = max_abs(errors, errors.size() - band, errors.size());
    std::printf("long row: max error first 2048 px %.2e sigma, last 2048 px %.2e sigma, RMS %.2e sigma\n", first, last,
                rms(errors));
    EXPECT_LT(first, 1e-5);
    EXPECT_LT(last, 1e-5);
    EXPECT_LT(last, 2 * first + 1e-6);
}

}  // namespace
}  // namespace stochtex
