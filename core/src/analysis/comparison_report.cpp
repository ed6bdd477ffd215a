// stochtex — compare_images, its report and the one-number fidelity penalty (metrics.h): every
// measure of a synthesis against its photo, each computed once per image.
#include <stochtex/metrics.h>

#include <stochtex/error.h>

#include "analysis/colour_statistics.h"
#include "analysis/distribution_distances.h"
#include "analysis/gradient_statistics.h"
#include "analysis/spectral_distances.h"
#include "analysis/structure_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <string>

namespace stochtex {
namespace {

constexpr const char* kChannelNames[3] = {"R", "G", "B"};

std::vector<float> luma_plane(const Image& rgb) {
    std::vector<float> luma(rgb.pixel_count());
    for (std::size_t i = 0; i < luma.size(); ++i) {
        const float* p = &rgb.pixels[i * 3];
        luma[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    }
    return luma;
}

using Matrix3 = std::array<std::array<double, 3>, 3>;

}  // namespace

/// The reference's side of compare_images: every statistic of the photo the report compares.
struct ComparisonReference::Prepared {
    int width = 0, height = 0;
    std::array<double, 3> mean{};
    Matrix3 covariance{};
    std::array<std::vector<double>, 3> sorted_channel;  ///< for W1
    std::array<RadialPsd, 3> channel_psd;
    std::array<std::string, 3> channel_psd_error;        ///< radial_psd's message where it failed
    WindowedSpectrum luma_spectrum;
    RadialPsd luma_psd;
    PolarPsd luma_polar_psd;
    bool has_gradients = false;                          ///< at least 3×3
    std::string gradient_error;                          ///< gradient_statistics' message where it failed
    std::vector<double> orientation, sorted_magnitude;
    double mean_magnitude = 0;
    std::vector<char> held_chroma;
    std::shared_ptr<const StructureReference> structure;
};

namespace {
constexpr int kBinsPerOctave = 4, kAngleBins = 12, kMinSamples = 128, kPlotSize = 256;
}  // namespace

ComparisonReference::ComparisonReference(const Image& reference, bool with_structure) {
    require_rgb(reference, "compare_images: reference");
    auto prepared = std::make_shared<Prepared>();
    Prepared& p = *prepared;
    p.width = reference.width, p.height = reference.height;
    p.mean = channel_means(reference);
    p.covariance = colour_covariance(reference);
    for (int c = 0; c < 3; ++c) {
        const std::vector<float> plane = reference.channel(c);
        p.sorted_channel[c] = sorted_doubles(plane);
        // A failure is reported when a test is compared, as compare_images always has.
        try {
            p.channel_psd[c] = radial_psd(plane, reference.width, reference.height);
        } catch (const Error& e) {
            p.channel_psd_error[c] = e.what();
        }
    }
    const std::vector<float> luma = luma_plane(reference);
    p.luma_spectrum = windowed_spectrum(luma, reference.width, reference.height, "compare_images: reference");
    p.luma_psd = radial_psd_of(p.luma_spectrum, kBinsPerOctave);
    p.luma_polar_psd = polar_psd_of(p.luma_spectrum, kBinsPerOctave, kAngleBins);
    p.has_gradients = std::min(reference.width, reference.height) >= 3;
    if (p.has_gradients) {
        try {
            GradientStatistics gradients = gradient_statistics(luma, reference.width, reference.height);
            for (float m : gradients.magnitude_over_sigma) p.mean_magnitude += m;
            p.mean_magnitude /= double(gradients.magnitude_over_sigma.size());
            p.sorted_magnitude = sorted_doubles(gradients.magnitude_over_sigma);
            p.orientation = std::move(gradients.orientation);
        } catch (const Error& e) {
            p.gradient_error = e.what();
        }
    }
    p.held_chroma = held_chroma_region(reference);
    if (with_structure) p.structure = std::make_shared<const StructureReference>(reference);
    prepared_ = std::move(prepared);
}

int ComparisonReference::width() const { return prepared_->width; }
int ComparisonReference::height() const { return prepared_->height; }

ComparisonReport compare_images(const Image& reference, const Image& test) {
    return compare_images(ComparisonReference(reference), test);
}

ComparisonReport compare_images(const ComparisonReference& prepared_reference, const Image& test) {
    const ComparisonReference::Prepared& reference = *prepared_reference.prepared_;
    require_rgb(test, "compare_images: test");
    ComparisonReport report;
    report.mean_reference = reference.mean;
    report.mean_test = channel_means(test);
    const auto test_covariance = colour_covariance(test);
    report.covariance_error = relative_frobenius_error(reference.covariance, test_covariance);
    for (int c = 0; c < 3; ++c) {
        report.stddev_reference[c] = std::sqrt(reference.covariance[c][c]);
        report.stddev_test[c] = std::sqrt(test_covariance[c][c]);
        const std::vector<float> test_plane = test.channel(c);
        report.w1[c] = wasserstein1_of_sorted(reference.sorted_channel[c], sorted_doubles(test_plane));
        report.w1_relative[c] = report.w1[c] / report.stddev_reference[c];
        try {
            if (!reference.channel_psd_error[c].empty()) throw Error(reference.channel_psd_error[c]);
            report.log_psd_db[c] = log_psd_distance_or_nan(reference.channel_psd[c],
                                                           radial_psd(test_plane, test.width, test.height),
                                                           resolved_bin_samples);
        } catch (const Error& e) {
            throw Error(std::string("compare_images: channel ") + kChannelNames[c] + ": " + e.what());
        }
    }
    // One windowed spectrum of each luma serves the radial, the polar and the plotted spectrum.
    const std::vector<float> test_luma = luma_plane(test);
    const WindowedSpectrum test_spectrum = windowed_spectrum(test_luma, test.width, test.height, "compare_images: test");
    report.psd_reference_luma = reference.luma_psd;
    report.psd_test_luma = radial_psd_of(test_spectrum, kBinsPerOctave);
    const PolarDistances polar =
        polar_distances_or_nan(reference.luma_polar_psd, polar_psd_of(test_spectrum, kBinsPerOctave, kAngleBins), kMinSamples);
    report.polar_log_psd_db = polar.total_db;
    report.polar_log_psd_angular_db = polar.angular_db;
    const int plot_size = std::min({kPlotSize, reference.width, reference.height, test.width, test.height});
    report.spectrum_reference_luma = centred_spectrum_of(reference.luma_spectrum, plot_size);
    report.spectrum_test_luma = centred_spectrum_of(test_spectrum, plot_size);

    if (reference.has_gradients && std::min(test.width, test.height) >= 3) {
        if (!reference.gradient_error.empty()) throw Error(reference.gradient_error);
        const GradientStatistics test_gradients = gradient_statistics(test_luma, test.width, test.height);
        report.gradient_orientation_degrees = circular_wasserstein1_degrees(reference.orientation, test_gradients.orientation);
        report.gradient_magnitude_w1 =
            wasserstein1_of_sorted(reference.sorted_magnitude, sorted_doubles(test_gradients.magnitude_over_sigma)) /
            reference.mean_magnitude;
    } else {
        report.gradient_orientation_degrees = report.gradient_magnitude_w1 = std::numeric_limits<double>::quiet_NaN();
    }
    report.false_colour_rate = outside_region_rate(reference.held_chroma, test);
    if (reference.structure) report.structure = reference.structure->distance_to(test);
    else report.structure.total = std::numeric_limits<double>::quiet_NaN(), report.structure.parts.fill(report.structure.total);
    return report;
}

double fidelity_penalty(const ComparisonReport& report, const FidelityTargets& targets) {
    constexpr double kTermCap = 10;
    const auto term = [&](double metric, double target) {
        return std::isnan(metric) ? kTermCap : std::min(kTermCap, metric / target);
    };
    const double radial = (report.log_psd_db[0] + report.log_psd_db[1] + report.log_psd_db[2]) / 3;
    const double w1 = std::max({report.w1_relative[0], report.w1_relative[1], report.w1_relative[2]});
    const double terms[] = {term(radial, targets.radial_log_psd_db),
                            term(report.polar_log_psd_db, targets.polar_log_psd_db),
                            term(w1, targets.w1_sigma),
                            term(report.false_colour_rate, targets.false_colour_rate),
                            term(report.gradient_orientation_degrees, targets.gradient_orientation_degrees),
                            term(report.gradient_magnitude_w1, targets.gradient_magnitude_w1)};
    double sum = 0;
    for (double t : terms) sum += t;
    if (targets.structure_distance > 0)
        return (sum + term(report.structure.total, targets.structure_distance)) / (std::size(terms) + 1);
    return sum / std::size(terms);
}

std::string format_report(const ComparisonReport& report) {
    std::string text;
    char line[160];
    std::snprintf(line, sizeof line, "%-14s %12s %12s %12s\n", "", kChannelNames[0], kChannelNames[1],
                  kChannelNames[2]);
    text += line;
    const auto add_row = [&](const char* label, const std::array<double, 3>& values) {
        std::snprintf(line, sizeof line, "%-14s", label);
        text += line;
        for (double v : values) {
            if (std::isnan(v)) std::snprintf(line, sizeof line, " %12s", "n/a");  // too small to measure
            else std::snprintf(line, sizeof line, " %12.5g", v);
            text += line;
        }
        text += "\n";
    };
    add_row("mean ref", report.mean_reference);
    add_row("mean test", report.mean_test);
    add_row("stddev ref", report.stddev_reference);
    add_row("stddev test", report.stddev_test);
    add_row("W1", report.w1);
    add_row("W1/sigma", report.w1_relative);
    add_row("log-PSD dB", report.log_psd_db);
    std::snprintf(line, sizeof line, "colour covariance error (relative Frobenius): %.5g\n", report.covariance_error);
    text += line;
    // NaN (images too small for the measure) prints as "n/a", not as a number to trust.
    const auto value = [](double v, const char* format) {
        char buffer[32];
        if (std::isnan(v)) return std::string("n/a");
        std::snprintf(buffer, sizeof buffer, format, v);
        return std::string(buffer);
    };
    text += "2D log-PSD distance (luma, log-polar sectors): " + value(report.polar_log_psd_db, "%.3g") +
            " dB, of which angular (orientation) " + value(report.polar_log_psd_angular_db, "%.3g") + " dB\n";
    text += "gradient orientation W1 (luma, |grad|-weighted, mod 180): " +
            value(report.gradient_orientation_degrees, "%.3g") + " deg\n";
    text += "gradient magnitude W1 (|grad|/sigma, relative to the reference mean): " +
            value(report.gradient_magnitude_w1, "%.3g") + "\n";
    text += "false-colour rate (test chroma outside the reference's 99.5% a*b* region): " +
            value(100.0 * report.false_colour_rate, "%.3g") + " %\n";
    text += "structure distance (Portilla-Simoncelli statistics; 0 = the photo's, 1 = its random-phase noise's): " +
            value(report.structure.total, "%.3g") + "\n ";
    for (int part = 0; part < StructureDistance::kParts; ++part)
        text += std::string(" ") + StructureDistance::part_name(part) + " " + value(report.structure.parts[part], "%.3g");
    text += "\n";
    return text;
}

}  // namespace stochtex
