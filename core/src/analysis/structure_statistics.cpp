#include "analysis/structure_statistics.h"

#include "spectra/fft.h"
#include "spectra/steerable_pyramid.h"
#include "numerics/constants.h"

#include <stochtex/error.h>

#include <cmath>
#include <complex>
#include <limits>
#include <random>

namespace stochtex {

namespace {

constexpr int kScales = 4, kOrientations = 4;
constexpr int kMinSide = 64;  // the coarsest band 8 px across: enough for its ±3-pixel lags
constexpr int kMaxLag = 3;    // P–S's 7×7 auto-correlation window
/// A group's distance from the photo to its random-phase version is the part's unit; where the
/// photo is itself nearly structureless in a group, this floor keeps that unit from shrinking to
/// noise (about the spread between two crops of one photo, from the calibration tests).
constexpr double kMinUnit = 0.02;

enum Group { kMarginals = 0, kAutocorrelation, kCrossOrientation, kCrossScale, kPhase };

/// Appends a group's statistics with the weight of the level they come from.
struct GroupWriter {
    std::vector<double>& values;
    std::vector<double>& weights;
    double weight;
    void push_back(double v) {
        values.push_back(v);
        weights.push_back(weight);
    }
};

double mean_of(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
}

/// Skewness and log(kurtosis / 3) (0 for a Gaussian) of a sample.
void add_skew_and_kurtosis(const std::vector<double>& sample, GroupWriter out) {
    const double mean = mean_of(sample);
    double m2 = 0, m3 = 0, m4 = 0;
    for (double x : sample) {
        const double d = x - mean, d2 = d * d;
        m2 += d2, m3 += d2 * d, m4 += d2 * d2;
    }
    m2 /= double(sample.size()), m3 /= double(sample.size()), m4 /= double(sample.size());
    if (!(m2 > 0)) {
        out.push_back(0);
        out.push_back(0);
        return;
    }
    out.push_back(m3 / std::pow(m2, 1.5));
    out.push_back(std::log(m4 / (m2 * m2) / 3));
}

std::vector<double> to_double(const std::vector<float>& v) { return std::vector<double>(v.begin(), v.end()); }

std::vector<double> amplitude(const std::vector<std::complex<float>>& band) {
    std::vector<double> out(band.size());
    for (std::size_t i = 0; i < band.size(); ++i) out[i] = std::abs(band[i]);
    return out;
}

void remove_mean(std::vector<double>& v) {
    const double m = mean_of(v);
    for (double& x : v) x -= m;
}

/// Pearson correlation of two zero-mean samples (0 where either is flat).
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) ab += a[i] * b[i], aa += a[i] * a[i], bb += b[i] * b[i];
    return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0;
}

/// The normalised circular auto-correlation of a zero-mean plane at the 24 lags of the upper half
/// of the 7×7 window (the other half mirrors them; lag 0 is 1).
void add_autocorrelation(const std::vector<double>& plane, int width, int height, GroupWriter out) {
    double variance = 0;
    for (double v : plane) variance += v * v;
    for (int dy = 0; dy <= kMaxLag; ++dy)
        for (int dx = -kMaxLag; dx <= kMaxLag; ++dx) {
            if (dy == 0 && dx <= 0) continue;
            double sum = 0;
            for (int y = 0; y < height; ++y) {
                const double* row = &plane[std::size_t(y) * width];
                const double* shifted = &plane[std::size_t((y + dy) % height) * width];
                // x + dx wraps at one place: two runs without a modulo in the loop.
                const int split = dx >= 0 ? width - dx : -dx;
                for (int x = 0; x < split; ++x) sum += row[x] * shifted[x + dx + (dx < 0 ? width : 0)];
                for (int x = split; x < width; ++x) sum += row[x] * shifted[x + dx - (dx >= 0 ? width : 0)];
            }
            out.push_back(variance > 0 ? sum / variance : 0);
        }
}

/// The parent band with its phase doubled (|p| e^{2i arg p}): it then oscillates at the child's
/// frequency, so an edge, whose phases align across scales, correlates with the child; a
/// Gaussian texture's do not.
std::vector<std::complex<double>> phase_doubled(const std::vector<std::complex<float>>& parent) {
    std::vector<std::complex<double>> out(parent.size());
    for (std::size_t i = 0; i < parent.size(); ++i) {
        const std::complex<double> p(parent[i]);
        const double m = std::abs(p);
        out[i] = m > 0 ? p * p / m : std::complex<double>(0);
    }
    return out;
}

Image centred_crop(const Image& rgb, int width, int height) {
    Image out(width, height, 3);
    const int x0 = (rgb.width - width) / 2, y0 = (rgb.height - height) / 2;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb.at(x0 + x, y0 + y, c);
    return out;
}

}  // namespace

const char* StructureDistance::part_name(int part) {
    static const char* names[kParts] = {"marginals", "auto-correlation", "cross-orientation", "cross-scale", "phase"};
    return part >= 0 && part < kParts ? names[part] : "?";
}

StructureStatistics structure_statistics(const Image& input) {
    if (input.channels != 3) throw Error("structure_statistics: the image is not RGB");
    StructureStatistics stats;
    const int step = 1 << kScales;
    const int width = input.width / step * step, height = input.height / step * step;
    if (std::min(width, height) < kMinSide) return stats;
    const Image rgb = centred_crop(input, width, height);
    std::vector<float> luma(std::size_t(width) * height);
    double mean = 0, variance = 0;
    for (std::size_t i = 0; i < luma.size(); ++i) {
        const float* p = &rgb.pixels[3 * i];
        luma[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        mean += luma[i];
    }
    mean /= double(luma.size());
    for (float v : luma) variance += (v - mean) * (v - mean);
    variance /= double(luma.size());
    if (!(variance > 0)) return stats;
    for (float& v : luma) v = float((v - mean) / std::sqrt(variance));
    const SteerablePyramid pyramid = build_steerable_pyramid(luma, width, height, kScales, kOrientations);

    const double pixels = double(width) * height;
    const auto writer = [&](Group group, double level_pixels) {
        return GroupWriter{stats.groups[group], stats.weights[group], level_pixels / pixels};
    };
    add_skew_and_kurtosis(to_double(luma), writer(kMarginals, pixels));
    for (int c = 0; c < 3; ++c) add_skew_and_kurtosis(to_double(rgb.channel(c)), writer(kMarginals, pixels));
    const auto add_lowpass = [&](const std::vector<float>& lowpass, int w, int h) {
        std::vector<double> plane = to_double(lowpass);
        add_skew_and_kurtosis(plane, writer(kMarginals, double(w) * h));
        remove_mean(plane);
        add_autocorrelation(plane, w, h, writer(kAutocorrelation, double(w) * h));
    };
    for (std::size_t s = 0; s < pyramid.levels.size(); ++s) {
        const SteerablePyramidLevel& level = pyramid.levels[s];
        const double level_pixels = double(level.width) * level.height;
        add_lowpass(level.lowpass, level.width, level.height);
        std::vector<std::vector<double>> amplitudes;
        for (const auto& band : level.bands) {
            std::vector<double> a = amplitude(band);
            // Sparsity: mean |b| over RMS |b|, against a complex Gaussian's √π/2 (log: 0 for noise,
            // negative where the energy sits in few places: edges, grains).
            double sum = 0, sum_squares = 0;
            for (double v : a) sum += v, sum_squares += v * v;
            const double n = double(a.size());
            writer(kMarginals, level_pixels)
                .push_back(sum_squares > 0 ? std::log(sum / n / std::sqrt(sum_squares / n) / (std::sqrt(kPi) / 2)) : 0);
            remove_mean(a);
            add_autocorrelation(a, level.width, level.height, writer(kAutocorrelation, level_pixels));
            amplitudes.push_back(std::move(a));
        }
        for (int k = 0; k < kOrientations; ++k)
            for (int j = k + 1; j < kOrientations; ++j)
                writer(kCrossOrientation, level_pixels).push_back(correlation(amplitudes[k], amplitudes[j]));
        // The parents vary at the coarser level's scale: as many independent samples as it has pixels.
        const double parent_pixels = level_pixels / 4;
        for (std::size_t j = 0; j < level.parent_bands.size(); ++j) {
            std::vector<double> parent_amplitude = amplitude(level.parent_bands[j]);
            remove_mean(parent_amplitude);
            const std::vector<std::complex<double>> doubled = phase_doubled(level.parent_bands[j]);
            std::vector<double> parent_real(doubled.size()), parent_imaginary(doubled.size());
            for (std::size_t i = 0; i < doubled.size(); ++i) parent_real[i] = doubled[i].real(), parent_imaginary[i] = doubled[i].imag();
            for (int k = 0; k < kOrientations; ++k) {
                writer(kCrossScale, parent_pixels).push_back(correlation(amplitudes[k], parent_amplitude));
                std::vector<double> child_real(level.bands[k].size());
                for (std::size_t i = 0; i < child_real.size(); ++i) child_real[i] = level.bands[k][i].real();
                writer(kPhase, parent_pixels).push_back(correlation(child_real, parent_real));
                writer(kPhase, parent_pixels).push_back(correlation(child_real, parent_imaginary));
            }
        }
    }
    add_lowpass(pyramid.residual_lowpass, pyramid.residual_width, pyramid.residual_height);
    stats.measurable = true;
    return stats;
}

std::array<double, StructureDistance::kParts> structure_group_rms(const StructureStatistics& a,
                                                                  const StructureStatistics& b) {
    std::array<double, StructureDistance::kParts> rms;
    for (int g = 0; g < StructureDistance::kParts; ++g) {
        if (!a.measurable || !b.measurable || a.groups[g].size() != b.groups[g].size()) {
            rms[g] = std::numeric_limits<double>::quiet_NaN();
            continue;
        }
        double sum = 0, weights = 0;
        for (std::size_t i = 0; i < a.groups[g].size(); ++i) {
            const double d = a.groups[g][i] - b.groups[g][i], w = a.weights[g][i];
            sum += w * d * d, weights += w;
        }
        rms[g] = std::sqrt(sum / weights);
    }
    return rms;
}

Image random_phase_image(const Image& rgb, unsigned seed) {
    if (rgb.channels != 3 || rgb.width <= 0 || rgb.height <= 0) throw Error("random_phase_image: the image is not RGB");
    const int width = rgb.width, height = rgb.height;
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal;
    std::vector<float> noise(std::size_t(width) * height);
    for (float& v : noise) v = normal(rng);
    // The DFT of white noise has uniformly random phases with the Hermitian symmetry of a real image.
    const std::vector<std::complex<float>> phases = real_fft_2d(noise, width, height);
    Image out(width, height, 3);
    const float scale = 1.0f / float(std::size_t(width) * height);
    for (int c = 0; c < 3; ++c) {
        std::vector<std::complex<float>> spectrum = periodic_component_fft_2d(rgb.channel(c), width, height);
        for (std::size_t i = 1; i < spectrum.size(); ++i) {  // bin 0 (the mean) keeps its value
            const float m = std::abs(phases[i]);
            spectrum[i] = m > 0 ? std::abs(spectrum[i]) * phases[i] / m : 0.0f;
        }
        const std::vector<float> plane = real_inverse_fft_2d(spectrum, width, height);
        for (std::size_t i = 0; i < plane.size(); ++i) out.pixels[3 * i + c] = plane[i] * scale;
    }
    return out;
}

StructureReference::StructureReference(const Image& reference) : reference_(structure_statistics(reference)) {
    if (!reference_.measurable) return;
    const auto unit = structure_group_rms(reference_, structure_statistics(random_phase_image(reference, 1)));
    for (int g = 0; g < StructureDistance::kParts; ++g) unit_[g] = std::max(kMinUnit, unit[g]);
}

StructureDistance StructureReference::distance_to(const Image& test) const {
    StructureDistance distance;
    const auto rms = structure_group_rms(reference_, structure_statistics(test));
    distance.total = 0;
    for (int g = 0; g < StructureDistance::kParts; ++g) {
        distance.parts[g] = rms[g] / unit_[g];
        distance.total += distance.parts[g] / StructureDistance::kParts;
    }
    return distance;
}

}  // namespace stochtex
