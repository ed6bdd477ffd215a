// Calibration of the structure distance (docs/metrics.md, "Structure"): the orderings it must
// get right before anyone trusts it, with the figures printed. A photo's other crop is near the
// floor; its random-phase version (same spectrum, no structure) and a blurred copy are far; a
// blend of two offset copies at Σw² = 1 (the ghosts of a variance-preserving tiling blend)
// is farther than a clean crop.
#include <stochtex/error.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>

#include "analysis/structure_statistics.h"
#include "spectra/steerable_pyramid.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>

namespace stochtex {
namespace {

Image crop(const Image& source, int x0, int y0, int size) {
    Image out(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = source.at(x0 + x, y0 + y, c);
    return out;
}

/// Separable Gaussian blur, edges clamped.
Image blurred(const Image& source, double sigma) {
    const int radius = int(std::ceil(3 * sigma));
    std::vector<double> kernel(2 * radius + 1);
    double sum = 0;
    for (int i = -radius; i <= radius; ++i) sum += kernel[i + radius] = std::exp(-0.5 * i * i / (sigma * sigma));
    for (double& k : kernel) k /= sum;
    Image pass = source, out = source;
    for (int y = 0; y < source.height; ++y)
        for (int x = 0; x < source.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double v = 0;
                for (int i = -radius; i <= radius; ++i) v += kernel[i + radius] * source.at(std::clamp(x + i, 0, source.width - 1), y, c);
                pass.at(x, y, c) = float(v);
            }
    for (int y = 0; y < source.height; ++y)
        for (int x = 0; x < source.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double v = 0;
                for (int i = -radius; i <= radius; ++i) v += kernel[i + radius] * pass.at(x, std::clamp(y + i, 0, source.height - 1), c);
                out.at(x, y, c) = float(v);
            }
    return out;
}

/// What a variance-preserving blend of two tiles shows where they meet: mean + (a − mean)·w +
/// (b − mean)·w with w = 1/√2 (Σw² = 1), each channel's mean the average of both.
Image ghosted_blend(const Image& a, const Image& b) {
    Image out(a.width, a.height, 3);
    const double w = 1 / std::sqrt(2.0);
    for (int c = 0; c < 3; ++c) {
        double mean = 0;
        for (std::size_t i = 0; i < a.pixel_count(); ++i) mean += a.pixels[3 * i + c] + b.pixels[3 * i + c];
        mean /= 2.0 * double(a.pixel_count());
        for (std::size_t i = 0; i < a.pixel_count(); ++i)
            out.pixels[3 * i + c] = float(mean + w * (a.pixels[3 * i + c] - mean) + w * (b.pixels[3 * i + c] - mean));
    }
    return out;
}

std::string parts_text(const StructureDistance& d) {
    char line[200];
    std::snprintf(line, sizeof line, "%.3f (marginals %.3f, auto-correlation %.3f, cross-orientation %.3f, cross-scale %.3f, phase %.3f)",
                  d.total, d.parts[0], d.parts[1], d.parts[2], d.parts[3], d.parts[4]);
    return line;
}

struct Calibration {
    StructureDistance other_crop, random_phase, blurred_copy, ghosted, clean_blend_partner;
};

/// The figures of one photo: reference = its top-left size² crop; the tests are made from a
/// crop at the opposite corner (never overlapping the reference where the photo is ≥ 2·size).
Calibration calibrate(const Image& photo, int size, const char* name) {
    const Image reference = crop(photo, 0, 0, size);
    const Image other = crop(photo, photo.width - size, photo.height - size, size);
    const Image shifted = crop(photo, photo.width - size - size / 3, photo.height - size - size / 5, size);
    const StructureReference prepared(reference);  // compare_images' structure part, alone
    Calibration c;
    c.other_crop = prepared.distance_to(other);
    c.random_phase = prepared.distance_to(random_phase_image(other, 7));
    c.blurred_copy = prepared.distance_to(blurred(other, 1.5));
    c.ghosted = prepared.distance_to(ghosted_blend(other, shifted));
    c.clean_blend_partner = prepared.distance_to(shifted);
    std::printf("%s, %d² crops, structure distance to the photo's top-left crop:\n"
                "  other crop          %s\n  random phase        %s\n  blurred (σ 1.5 px)  %s\n"
                "  ghosted blend       %s\n  the blend's 2nd crop %s\n",
                name, size, parts_text(c.other_crop).c_str(), parts_text(c.random_phase).c_str(),
                parts_text(c.blurred_copy).c_str(), parts_text(c.ghosted).c_str(),
                parts_text(c.clean_blend_partner).c_str());
    return c;
}

void expect_calibrated(const Calibration& c) {
    // The floor: another crop of the same photo is well under the photo's own noise.
    EXPECT_LT(c.other_crop.total, 0.35);
    EXPECT_LT(c.clean_blend_partner.total, 0.35);
    // Structureless versions are far: at least 2.5× the other crop, and near or past the unit.
    EXPECT_GT(c.random_phase.total, 2.5 * c.other_crop.total);
    EXPECT_GT(c.random_phase.total, 0.7);
    EXPECT_GT(c.blurred_copy.total, 2.5 * c.other_crop.total);
    // Ghosts: the blend of two crops is farther than either crop alone.
    EXPECT_GT(c.ghosted.total, 1.5 * std::max(c.other_crop.total, c.clean_blend_partner.total));
}

TEST(StructureDistance, CalibratedOnTheCommittedExemplar) {
    const Image photo = read_image_linear(test::repo_exemplar("concrete_512.png"));
    expect_calibrated(calibrate(photo, 256, "concrete_512.png"));
}

TEST(StructureDistance, CalibratedOnStructuredSharedPhotos) {
    // Gravel (grains) and sandy rock (fine cracks) are stationary enough that their opposite
    // 512² corners are one texture.
    for (const char* name : {"gravel.png", "sandy_rock.png"}) {
        const std::string path = test::shared_exemplar(name);
        if (path.empty()) GTEST_SKIP() << "../shared/exemplars is not here";
        SCOPED_TRACE(name);
        expect_calibrated(calibrate(read_image_linear(path), 512, name));
    }
}

TEST(StructureDistance, SeesTheNonStationaryKarstRock) {
    // Karst rock's corners are different rock (red stains and a dark cleft bottom right, plain
    // plates top left): their distance is most of the way to noise, in the marginals (skewness
    // 0.05 against 0.64) and the phase. Only "noise is farther" is asserted; the figures are
    // docs/metrics.md's.
    const std::string path = test::shared_exemplar("karst_rock.png");
    if (path.empty()) GTEST_SKIP() << "../shared/exemplars is not here";
    const Calibration c = calibrate(read_image_linear(path), 512, "karst_rock.png");
    EXPECT_GT(c.random_phase.total, c.other_crop.total);
    EXPECT_GT(c.other_crop.parts[0], 1.0);  // the marginals: the corners' skewness and colours differ
}

TEST(StructureDistance, ZeroForTheSameImageAndNanWhenTooSmallOrFlat) {
    const Image photo = crop(read_image_linear(test::repo_exemplar("concrete_512.png")), 0, 0, 128);
    const ComparisonReport same = compare_images(photo, photo);
    EXPECT_EQ(same.structure.total, 0.0);
    for (double part : same.structure.parts) EXPECT_EQ(part, 0.0);
    Image small = crop(photo, 0, 0, 48);
    EXPECT_TRUE(std::isnan(compare_images(small, small).structure.total));
    Image flat(128, 128, 3);
    std::fill(flat.pixels.begin(), flat.pixels.end(), 0.5f);
    EXPECT_FALSE(structure_statistics(flat).measurable);
    EXPECT_TRUE(std::isnan(StructureReference(photo).distance_to(flat).total));
    EXPECT_NE(format_report(compare_images(small, small)).find("structure distance"), std::string::npos);
}

TEST(StructureDistance, IsTheSeventhPenaltyTermOnlyWithATarget) {
    ComparisonReport report;
    FidelityTargets targets;
    report.log_psd_db = {targets.radial_log_psd_db, targets.radial_log_psd_db, targets.radial_log_psd_db};
    report.polar_log_psd_db = targets.polar_log_psd_db;
    report.w1_relative = {targets.w1_sigma, 0.0, 0.0};
    report.false_colour_rate = targets.false_colour_rate;
    report.gradient_orientation_degrees = targets.gradient_orientation_degrees;
    report.gradient_magnitude_w1 = targets.gradient_magnitude_w1;
    report.structure.total = 0.75;
    EXPECT_DOUBLE_EQ(fidelity_penalty(report, targets), 1.0);  // default: six terms, structure ignored
    targets.structure_distance = 0.25;
    EXPECT_DOUBLE_EQ(fidelity_penalty(report, targets), (6.0 + 3.0) / 7.0);
    report.structure.total = std::numeric_limits<double>::quiet_NaN();  // not measurable: capped
    EXPECT_DOUBLE_EQ(fidelity_penalty(report, targets), (6.0 + 10.0) / 7.0);
}

TEST(SteerablePyramid, AnOrientedWaveLandsInItsBandAndScale) {
    // A wave of 0.25 cycles/px along x (ω = π/2, where level 0's high mask is 1 and its low-pass
    // 0): all its energy is in level 0, none at 90°; the steerable bands overlap, so orientations
    // 45° and 135° hold cos⁶ 45° = 1/8 each of orientation 0's.
    const int n = 64;
    std::vector<float> plane(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) plane[y * n + x] = float(std::cos(2 * M_PI * 16.0 / n * x));
    const SteerablePyramid pyramid = build_steerable_pyramid(plane, n, n, 4, 4);
    std::vector<double> energy;
    for (const auto& level : pyramid.levels)
        for (const auto& band : level.bands) {
            double e = 0;
            for (auto v : band) e += std::norm(v);
            energy.push_back(e);
        }
    double total = 0;
    for (double e : energy) total += e;
    EXPECT_NEAR(energy[0] / total, 0.8, 0.01);
    EXPECT_NEAR(energy[1] / energy[0], 0.125, 0.01);
    EXPECT_LT(energy[2] / total, 1e-6);
    // (Moisan's periodic component moves a little energy: the wave's last and first columns
    // differ, as a smooth wave's do.)
    EXPECT_LT((total - energy[0] - energy[1] - energy[2] - energy[3]) / total, 0.01);
    EXPECT_THROW(build_steerable_pyramid(plane, 60, 60, 4, 4), Error);
}

TEST(StructureDistance, RandomPhaseKeepsTheSpectrum) {
    const Image photo = crop(read_image_linear(test::repo_exemplar("concrete_512.png")), 0, 0, 128);
    const Image noise = random_phase_image(photo, 3);
    const ComparisonReport report = compare_images(photo, noise);
    // Periodic component against the photo's windowed spectrum: a small difference, not dBs.
    EXPECT_LT(report.log_psd_db[1], 1.5);
    EXPECT_NEAR(report.mean_test[1], report.mean_reference[1], 1e-4);
}

}  // namespace
}  // namespace stochtex
