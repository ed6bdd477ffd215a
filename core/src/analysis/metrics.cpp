// stochtex — texture statistics and distances (see metrics.h).
#include <stochtex/metrics.h>

#include <stochtex/error.h>

#include "spectra/fft.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <string>

namespace stochtex {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNyquist = 0.5;  // cycles per pixel
constexpr const char* kChannelNames[3] = {"R", "G", "B"};

/// Radial bin k covers (0.5·2^(-(k+1)/b), 0.5·2^(-k/b)] cycles per pixel. Anchoring the edges at
/// Nyquist makes every image size share them, so spectra of different sizes match bin for bin.
int radial_bin(double frequency, int bins_per_octave) {
    // The epsilon keeps a frequency that lands on an edge up to rounding in the bin below it.
    return int(std::floor(bins_per_octave * std::log2(kNyquist / frequency) + 1e-9));
}

double radial_bin_centre(int bin, int bins_per_octave) {
    return kNyquist * std::exp2(-(bin + 0.5) / bins_per_octave);  // geometric centre
}

/// Symmetric Hann window sampled at pixel centres (no zero at the borders); returns its values
/// and fills the mean square used for power compensation.
std::vector<double> hann_window(int size, double& mean_square) {
    std::vector<double> window(size);
    mean_square = 0;
    for (int i = 0; i < size; ++i) {
        const double s = std::sin(kPi * (i + 0.5) / size);
        window[i] = s * s;
        mean_square += window[i] * window[i] / size;
    }
    return window;
}

std::vector<float> luma_plane(const Image& rgb) {
    std::vector<float> luma(rgb.pixel_count());
    for (std::size_t i = 0; i < luma.size(); ++i) {
        const float* p = &rgb.pixels[i * 3];
        luma[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    }
    return luma;
}

using Matrix3 = std::array<std::array<double, 3>, 3>;

double relative_frobenius_error(const Matrix3& reference, const Matrix3& test) {
    double difference_squared = 0, reference_squared = 0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const double d = test[r][c] - reference[r][c];
            difference_squared += d * d;
            reference_squared += reference[r][c] * reference[r][c];
        }
    if (reference_squared == 0)
        throw Error("covariance_relative_error: the reference image is constant (zero colour covariance)");
    return std::sqrt(difference_squared / reference_squared);
}

void require_rgb(const Image& image, const char* role) {
    if (image.channels != 3 || image.empty())
        throw Error(std::string(role) + " image: expected a non-empty 3-channel RGB image, got " +
                    std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                    std::to_string(image.channels) + " channels");
}

}  // namespace

// Normalisation. With x' = (x − mean)·w (w the separable Hann window) and F its unnormalised
// DFT, the periodogram P_k = |F_k|² / (W·H)² sums over all bins to mean(x'²) (Parseval), which
// is the variance times mean(w²); dividing by mean(w²) makes Σ_k P_k the channel variance.
// Each FFT bin covers a frequency area of 1/(W·H) cycles²/pixel², so the reported power is the
// density S = P_k·W·H = |F_k|² / (W·H·mean(w²)), averaged over the bin's FFT samples: white noise
// of variance σ² gives S = σ² in every bin at any image size, and Σ_k S_k / (W·H) = variance.
RadialPsd radial_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave) {
    if (width < 2 || height < 2 || plane.size() != std::size_t(width) * height)
        throw Error("radial_psd: plane of " + std::to_string(plane.size()) + " values does not match a " +
                    std::to_string(width) + "x" + std::to_string(height) + " image of at least 2x2");
    if (bins_per_octave < 1)
        throw Error("radial_psd: bins_per_octave must be at least 1, got " + std::to_string(bins_per_octave));

    double mean = 0;
    for (float v : plane) mean += v;
    mean /= double(plane.size());

    double window_x_mean_square = 0, window_y_mean_square = 0;
    const std::vector<double> window_x = hann_window(width, window_x_mean_square);
    const std::vector<double> window_y = hann_window(height, window_y_mean_square);

    std::vector<float> windowed(plane.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            windowed[i] = float((plane[i] - mean) * window_x[x] * window_y[y]);
        }
    const std::vector<std::complex<float>> spectrum = real_fft_2d(windowed, width, height);

    const int lowest_bin = radial_bin(1.0 / std::min(width, height), bins_per_octave);
    std::vector<double> power_sum(lowest_bin + 1, 0.0), sample_count(lowest_bin + 1, 0.0);
    const int spectrum_width = width / 2 + 1;
    for (int ky = 0; ky < height; ++ky) {
        const double fy = double(ky <= height / 2 ? ky : ky - height) / height;
        for (int kx = 0; kx < spectrum_width; ++kx) {
            const double frequency = std::hypot(double(kx) / width, fy);
            if (frequency == 0 || frequency > kNyquist) continue;  // DC; corners beyond Nyquist
            const int bin = radial_bin(frequency, bins_per_octave);
            if (bin > lowest_bin) continue;  // below 1/min(w,h) along the longer side
            // The r2c half-spectrum omits the mirror (−kx, −ky) of every column except kx = 0 and
            // kx = W/2, which are their own mirrors; the mirror has the same |F| and radius.
            const double multiplicity = (kx == 0 || 2 * kx == width) ? 1.0 : 2.0;
            power_sum[bin] += multiplicity * std::norm(spectrum[std::size_t(ky) * spectrum_width + kx]);
            sample_count[bin] += multiplicity;
        }
    }

    const double density_scale = 1.0 / (double(width) * height * window_x_mean_square * window_y_mean_square);
    RadialPsd psd;
    for (int bin = lowest_bin; bin >= 0; --bin) {  // ascending frequency
        if (sample_count[bin] == 0) continue;
        psd.frequency.push_back(radial_bin_centre(bin, bins_per_octave));
        psd.power.push_back(power_sum[bin] / sample_count[bin] * density_scale);
    }
    return psd;
}

double log_psd_distance_db(const RadialPsd& a, const RadialPsd& b) {
    // Both are sorted by ascending frequency; centres of shared bins are computed identically,
    // the tolerance only absorbs spectra that went through a file or another computation.
    double sum_squares = 0;
    int common_bins = 0;
    std::size_t i = 0, j = 0;
    while (i < a.frequency.size() && j < b.frequency.size()) {
        const double fa = a.frequency[i], fb = b.frequency[j];
        if (std::abs(fa - fb) <= 1e-9 * std::max(fa, fb)) {
            if (a.power[i] > 0 && b.power[j] > 0) {
                const double db = 10.0 * std::log10(a.power[i] / b.power[j]);
                sum_squares += db * db;
                ++common_bins;
            }
            ++i, ++j;
        } else if (fa < fb) {
            ++i;
        } else {
            ++j;
        }
    }
    if (common_bins == 0)
        throw Error("log_psd_distance_db: the spectra share no frequency bin where both have power "
                    "(a constant channel, or different bins_per_octave?)");
    return std::sqrt(sum_squares / common_bins);
}

double wasserstein1(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.empty() || b.empty()) throw Error("wasserstein1: a sample is empty");
    std::vector<double> sorted_a(a.begin(), a.end()), sorted_b(b.begin(), b.end());
    std::sort(sorted_a.begin(), sorted_a.end());
    std::sort(sorted_b.begin(), sorted_b.end());

    // W1 = ∫ |F_a(x) − F_b(x)| dx; both empirical CDFs are steps, constant between consecutive
    // values of the merged samples, so the integral is an exact sum over those intervals.
    const double inf = std::numeric_limits<double>::infinity();
    const std::size_t na = sorted_a.size(), nb = sorted_b.size();
    std::size_t ia = 0, ib = 0;  // samples ≤ the current x
    double x = std::min(sorted_a[0], sorted_b[0]), distance = 0;
    while (ia < na || ib < nb) {
        const double next = std::min(ia < na ? sorted_a[ia] : inf, ib < nb ? sorted_b[ib] : inf);
        distance += std::abs(double(ia) / na - double(ib) / nb) * (next - x);
        while (ia < na && sorted_a[ia] == next) ++ia;
        while (ib < nb && sorted_b[ib] == next) ++ib;
        x = next;
    }
    return distance;
}

std::array<double, 3> channel_means(const Image& rgb) {
    require_rgb(rgb, "channel_means:");
    std::array<double, 3> sum{};
    for (std::size_t i = 0; i < rgb.pixel_count(); ++i)
        for (int c = 0; c < 3; ++c) sum[c] += rgb.pixels[i * 3 + c];
    for (double& s : sum) s /= double(rgb.pixel_count());
    return sum;
}

/// Population covariance (divides by the pixel count): a texture is the whole population.
Matrix3 colour_covariance(const Image& rgb) {
    const std::array<double, 3> mean = channel_means(rgb);
    Matrix3 covariance{};
    for (std::size_t i = 0; i < rgb.pixel_count(); ++i) {
        double d[3];
        for (int c = 0; c < 3; ++c) d[c] = rgb.pixels[i * 3 + c] - mean[c];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) covariance[r][c] += d[r] * d[c];
    }
    for (auto& row : covariance)
        for (double& v : row) v /= double(rgb.pixel_count());
    return covariance;
}

double covariance_relative_error(const Image& reference, const Image& test) {
    return relative_frobenius_error(colour_covariance(reference), colour_covariance(test));
}

ComparisonReport compare_images(const Image& reference, const Image& test) {
    require_rgb(reference, "compare_images: reference");
    require_rgb(test, "compare_images: test");
    ComparisonReport report;
    report.mean_reference = channel_means(reference);
    report.mean_test = channel_means(test);
    const auto reference_covariance = colour_covariance(reference);
    const auto test_covariance = colour_covariance(test);
    report.covariance_error = relative_frobenius_error(reference_covariance, test_covariance);
    for (int c = 0; c < 3; ++c) {
        report.stddev_reference[c] = std::sqrt(reference_covariance[c][c]);
        report.stddev_test[c] = std::sqrt(test_covariance[c][c]);
        const std::vector<float> reference_plane = reference.channel(c), test_plane = test.channel(c);
        report.w1[c] = wasserstein1(reference_plane, test_plane);
        report.w1_relative[c] = report.w1[c] / report.stddev_reference[c];
        try {
            report.log_psd_db[c] = log_psd_distance_db(radial_psd(reference_plane, reference.width, reference.height),
                                                       radial_psd(test_plane, test.width, test.height));
        } catch (const Error& e) {
            throw Error(std::string("compare_images: channel ") + kChannelNames[c] + ": " + e.what());
        }
    }
    report.psd_reference_luma = radial_psd(luma_plane(reference), reference.width, reference.height);
    report.psd_test_luma = radial_psd(luma_plane(test), test.width, test.height);
    return report;
}

std::string format_report(const ComparisonReport& report) {
    std::string text;
    char line[160];
    std::snprintf(line, sizeof line, "%-14s %12s %12s %12s\n", "", kChannelNames[0], kChannelNames[1],
                  kChannelNames[2]);
    text += line;
    const auto add_row = [&](const char* label, const std::array<double, 3>& values) {
        std::snprintf(line, sizeof line, "%-14s %12.5g %12.5g %12.5g\n", label, values[0], values[1], values[2]);
        text += line;
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
    return text;
}

}  // namespace stochtex
