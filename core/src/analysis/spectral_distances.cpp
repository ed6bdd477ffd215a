// stochtex — texture statistics and distances (see metrics.h).
#include <stochtex/metrics.h>

#include <stochtex/error.h>

#include "analysis/structure_statistics.h"
#include "spectra/fft.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <iterator>
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

/// A sample as doubles, sorted ascending (what W1 compares).
std::vector<double> sorted_doubles(const std::vector<float>& sample) {
    std::vector<double> sorted(sample.begin(), sample.end());
    std::sort(sorted.begin(), sorted.end());
    return sorted;
}

}  // namespace

namespace {

// Normalisation. With x' = (x − mean)·w (w the separable Hann window) and F its unnormalised
// DFT, the periodogram P_k = |F_k|² / (W·H)² sums over all bins to mean(x'²) (Parseval), which
// is the variance times mean(w²); dividing by mean(w²) makes Σ_k P_k the channel variance.
// Each FFT bin covers a frequency area of 1/(W·H) cycles²/pixel², so the reported power is the
// density S = P_k·W·H = |F_k|² / (W·H·mean(w²)), averaged over the bin's FFT samples: white noise
// of variance σ² gives S = σ² in every bin at any image size, and Σ_k S_k / (W·H) = variance.
struct WindowedSpectrum {
    int width = 0, height = 0;
    std::vector<std::complex<float>> half;  ///< real_fft_2d layout
    double density_scale = 0;               ///< S = |F|²·density_scale
};

WindowedSpectrum windowed_spectrum(const std::vector<float>& plane, int width, int height, const char* caller) {
    if (width < 2 || height < 2 || plane.size() != std::size_t(width) * height)
        throw Error(std::string(caller) + ": plane of " + std::to_string(plane.size()) + " values does not match a " +
                    std::to_string(width) + "x" + std::to_string(height) + " image of at least 2x2");
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
    WindowedSpectrum spectrum;
    spectrum.width = width;
    spectrum.height = height;
    spectrum.half = real_fft_2d(windowed, width, height);
    spectrum.density_scale = 1.0 / (double(width) * height * window_x_mean_square * window_y_mean_square);
    return spectrum;
}

/// Calls visit(fx, fy, multiplicity, |F|²) for every sample of the half spectrum but DC; fx ≥ 0
/// and fy (towards row index, i.e. y down) in cycles per pixel. The r2c half-spectrum omits the
/// mirror (−fx, −fy) of every column except kx = 0 and kx = W/2, which are their own mirrors;
/// the mirror has the same |F| and radius, and its angle differs by 180°: multiplicity 2 stands for it.
template <class Visit>
void for_each_frequency(const WindowedSpectrum& spectrum, Visit&& visit) {
    const int width = spectrum.width, height = spectrum.height, spectrum_width = width / 2 + 1;
    for (int ky = 0; ky < height; ++ky) {
        const double fy = double(ky <= height / 2 ? ky : ky - height) / height;
        for (int kx = 0; kx < spectrum_width; ++kx) {
            if (kx == 0 && ky == 0) continue;  // DC: the mean, removed
            const double multiplicity = (kx == 0 || 2 * kx == width) ? 1.0 : 2.0;
            visit(double(kx) / width, fy, multiplicity, std::norm(spectrum.half[std::size_t(ky) * spectrum_width + kx]));
        }
    }
}

void require_bins_per_octave(int bins_per_octave, const char* caller) {
    if (bins_per_octave < 1)
        throw Error(std::string(caller) + ": bins_per_octave must be at least 1, got " + std::to_string(bins_per_octave));
}

RadialPsd radial_psd_of(const WindowedSpectrum& spectrum, int bins_per_octave) {
    const int lowest_bin = radial_bin(1.0 / std::min(spectrum.width, spectrum.height), bins_per_octave);
    std::vector<double> power_sum(lowest_bin + 1, 0.0), sample_count(lowest_bin + 1, 0.0);
    for_each_frequency(spectrum, [&](double fx, double fy, double multiplicity, double power) {
        const double frequency = std::hypot(fx, fy);
        if (frequency > kNyquist) return;  // corners beyond Nyquist
        const int bin = radial_bin(frequency, bins_per_octave);
        if (bin > lowest_bin) return;  // below 1/min(w,h) along the longer side
        power_sum[bin] += multiplicity * power;
        sample_count[bin] += multiplicity;
    });
    RadialPsd psd;
    for (int bin = lowest_bin; bin >= 0; --bin) {  // ascending frequency
        if (sample_count[bin] == 0) continue;
        psd.frequency.push_back(radial_bin_centre(bin, bins_per_octave));
        psd.power.push_back(power_sum[bin] / sample_count[bin] * spectrum.density_scale);
        psd.samples.push_back(sample_count[bin]);
    }
    return psd;
}

PolarPsd polar_psd_of(const WindowedSpectrum& spectrum, int bins_per_octave, int angle_bins) {
    const int lowest_bin = radial_bin(1.0 / std::min(spectrum.width, spectrum.height), bins_per_octave);
    const std::size_t cells = std::size_t(lowest_bin + 1) * angle_bins;
    std::vector<double> power_sum(cells, 0.0), sample_count(cells, 0.0);
    for_each_frequency(spectrum, [&](double fx, double fy_down, double multiplicity, double power) {
        const double frequency = std::hypot(fx, fy_down);
        if (frequency > kNyquist) return;
        const int bin = radial_bin(frequency, bins_per_octave);
        if (bin > lowest_bin) return;
        // θ mod 180° in units of cells, shifted half a cell so that cell 0 is centred on the x
        // axis: axis-aligned textures (common) put their power in cell centres, not on an edge.
        double angle = std::atan2(-fy_down, fx) / kPi * angle_bins + 0.5;
        angle -= angle_bins * std::floor(angle / angle_bins);
        const int cell = std::min(int(angle), angle_bins - 1);
        power_sum[std::size_t(bin) * angle_bins + cell] += multiplicity * power;
        sample_count[std::size_t(bin) * angle_bins + cell] += multiplicity;
    });
    PolarPsd psd;
    psd.bins_per_octave = bins_per_octave;
    psd.angle_bins = angle_bins;
    for (int bin = lowest_bin; bin >= 0; --bin) {  // ascending frequency, as radial_psd
        double bin_samples = 0;
        for (int a = 0; a < angle_bins; ++a) bin_samples += sample_count[std::size_t(bin) * angle_bins + a];
        if (bin_samples == 0) continue;
        psd.frequency.push_back(radial_bin_centre(bin, bins_per_octave));
        for (int a = 0; a < angle_bins; ++a) {
            const std::size_t i = std::size_t(bin) * angle_bins + a;
            psd.samples.push_back(sample_count[i]);
            psd.power.push_back(sample_count[i] > 0 ? power_sum[i] / sample_count[i] * spectrum.density_scale : 0.0);
        }
    }
    return psd;
}

CentredSpectrum centred_spectrum_of(const WindowedSpectrum& spectrum, int size) {
    CentredSpectrum centred;
    centred.size = size;
    centred.power.assign(std::size_t(size) * size, 0.0);
    std::vector<double> sample_count(centred.power.size(), 0.0);
    const auto add = [&](double fx, double fy_down, double power) {
        const int i = std::clamp(int(std::floor((fx + 0.5) * size)), 0, size - 1);
        const int j = std::clamp(int(std::floor((fy_down + 0.5) * size)), 0, size - 1);  // ½ − fy_up
        centred.power[std::size_t(j) * size + i] += power;
        sample_count[std::size_t(j) * size + i] += 1;
    };
    for_each_frequency(spectrum, [&](double fx, double fy_down, double multiplicity, double power) {
        add(fx, fy_down, power);
        if (multiplicity == 2) add(-fx, -fy_down, power);
    });
    for (std::size_t i = 0; i < centred.power.size(); ++i)
        if (sample_count[i] > 0) centred.power[i] *= spectrum.density_scale / sample_count[i];
    return centred;
}

/// polar_log_psd_distance_db and polar_log_psd_angular_db, or NaNs where no radius bin
/// qualifies (compare_images reports that as "n/a" rather than failing on small images the
/// other metrics handle).
struct PolarDistances {
    double total_db, angular_db;
};
PolarDistances polar_distances_or_nan(const PolarPsd& a, const PolarPsd& b, int min_samples) {
    if (a.bins_per_octave != b.bins_per_octave || a.angle_bins != b.angle_bins)
        throw Error("polar_log_psd_distance_db: the spectra use different grids (" + std::to_string(a.bins_per_octave) +
                    " vs " + std::to_string(b.bins_per_octave) + " bins per octave, " + std::to_string(a.angle_bins) +
                    " vs " + std::to_string(b.angle_bins) + " angle bins)");
    const int angle_bins = a.angle_bins;
    struct Sector {
        double power_a, power_b, weight;
        std::size_t radius;  ///< index of its radius bin among the kept ones
    };
    std::size_t kept_radii = 0;
    std::vector<Sector> sectors;
    std::size_t i = 0, j = 0;
    while (i < a.frequency.size() && j < b.frequency.size()) {
        const double fa = a.frequency[i], fb = b.frequency[j];
        if (std::abs(fa - fb) > 1e-9 * std::max(fa, fb)) {  // matched as log_psd_distance_db matches
            (fa < fb ? i : j) += 1;
            continue;
        }
        // Finest sectors first: d sectors of angle_bins/d consecutive cells each.
        for (int d = angle_bins; d >= 1; --d) {
            if (angle_bins % d != 0) continue;
            const int width = angle_bins / d;
            std::vector<Sector> candidate;
            bool enough = true;
            for (int s = 0; s < d && enough; ++s) {
                double sum_a = 0, count_a = 0, sum_b = 0, count_b = 0;
                for (int c = s * width; c < (s + 1) * width; ++c) {
                    const std::size_t ia = i * angle_bins + c, ib = j * angle_bins + c;
                    sum_a += a.power[ia] * a.samples[ia];
                    count_a += a.samples[ia];
                    sum_b += b.power[ib] * b.samples[ib];
                    count_b += b.samples[ib];
                }
                enough = count_a >= min_samples && count_b >= min_samples;
                candidate.push_back({sum_a / std::max(count_a, 1.0), sum_b / std::max(count_b, 1.0), 1.0 / d, kept_radii});
            }
            if (enough) {
                sectors.insert(sectors.end(), candidate.begin(), candidate.end());
                ++kept_radii;
                break;
            }
        }
        ++i, ++j;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (sectors.empty()) return {nan, nan};
    double strongest = 0;
    for (const Sector& s : sectors) strongest = std::max({strongest, s.power_a, s.power_b});
    if (strongest <= 0) return {nan, nan};  // both constant
    const double floor = strongest * 1e-6;  // 60 dB
    // The angular part compares each spectrum's sectors relative to its own mean power over the
    // radius bin (its radial PSD there), so a level error common to all directions drops out.
    // (Subtracting the mean dB difference instead would not: for a spectrum peaked in one
    // direction the mean of the logs sits far under the log of the mean, Jensen's inequality.)
    std::vector<double> radius_mean_a(kept_radii, 0.0), radius_mean_b(kept_radii, 0.0);
    for (const Sector& s : sectors) {
        radius_mean_a[s.radius] += s.weight * std::max(s.power_a, floor);
        radius_mean_b[s.radius] += s.weight * std::max(s.power_b, floor);
    }
    double sum_squares = 0, residual_squares = 0;
    for (const Sector& s : sectors) {
        const double pa = std::max(s.power_a, floor), pb = std::max(s.power_b, floor);
        const double db = 10.0 * std::log10(pa / pb);
        const double residual = db - 10.0 * std::log10(radius_mean_a[s.radius] / radius_mean_b[s.radius]);
        sum_squares += s.weight * db * db;
        residual_squares += s.weight * residual * residual;
    }
    return {std::sqrt(sum_squares / kept_radii), std::sqrt(residual_squares / kept_radii)};
}

}  // namespace

RadialPsd radial_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave) {
    require_bins_per_octave(bins_per_octave, "radial_psd");
    return radial_psd_of(windowed_spectrum(plane, width, height, "radial_psd"), bins_per_octave);
}

PolarPsd polar_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave, int angle_bins) {
    require_bins_per_octave(bins_per_octave, "polar_psd");
    if (angle_bins < 1) throw Error("polar_psd: angle_bins must be at least 1, got " + std::to_string(angle_bins));
    return polar_psd_of(windowed_spectrum(plane, width, height, "polar_psd"), bins_per_octave, angle_bins);
}

namespace {
PolarDistances polar_distances(const PolarPsd& a, const PolarPsd& b, int min_samples) {
    const PolarDistances distances = polar_distances_or_nan(a, b, min_samples);
    if (std::isnan(distances.total_db))
        throw Error("polar_log_psd_distance_db: no radius bin where both spectra hold " + std::to_string(min_samples) +
                    " samples with power (images too small, constant, or of different bins?)");
    return distances;
}
}  // namespace

double polar_log_psd_distance_db(const PolarPsd& a, const PolarPsd& b, int min_samples) {
    return polar_distances(a, b, min_samples).total_db;
}

double polar_log_psd_angular_db(const PolarPsd& a, const PolarPsd& b, int min_samples) {
    return polar_distances(a, b, min_samples).angular_db;
}

CentredSpectrum centred_spectrum(const std::vector<float>& plane, int width, int height, int size) {
    if (size < 1) throw Error("centred_spectrum: size must be at least 1, got " + std::to_string(size));
    return centred_spectrum_of(windowed_spectrum(plane, width, height, "centred_spectrum"), size);
}

namespace {
/// log_psd_distance_db, or NaN where the spectra share bins with power but none that both
/// resolve (images too small for the measure: compare_images reports "n/a", as for the 2D one).
double log_psd_distance_or_nan(const RadialPsd& a, const RadialPsd& b, int min_samples) {
    const auto resolved = [min_samples](const RadialPsd& psd, std::size_t bin) {
        return psd.samples.empty() || psd.samples[bin] >= min_samples;
    };
    // Both are sorted by ascending frequency; centres of shared bins are computed identically,
    // the tolerance only absorbs spectra that went through a file or another computation.
    double sum_squares = 0;
    int powered_bins = 0, common_bins = 0;
    std::size_t i = 0, j = 0;
    while (i < a.frequency.size() && j < b.frequency.size()) {
        const double fa = a.frequency[i], fb = b.frequency[j];
        if (std::abs(fa - fb) <= 1e-9 * std::max(fa, fb)) {
            if (a.power[i] > 0 && b.power[j] > 0) {
                ++powered_bins;
                if (resolved(a, i) && resolved(b, j)) {
                    const double db = 10.0 * std::log10(a.power[i] / b.power[j]);
                    sum_squares += db * db;
                    ++common_bins;
                }
            }
            ++i, ++j;
        } else if (fa < fb) {
            ++i;
        } else {
            ++j;
        }
    }
    if (powered_bins == 0)
        throw Error("log_psd_distance_db: the spectra share no frequency bin where both have power "
                    "(a constant channel, or different bins_per_octave?)");
    if (common_bins == 0) return std::numeric_limits<double>::quiet_NaN();
    return std::sqrt(sum_squares / common_bins);
}
}  // namespace

double log_psd_distance_db(const RadialPsd& a, const RadialPsd& b, int min_samples) {
    const double distance = log_psd_distance_or_nan(a, b, min_samples);
    if (std::isnan(distance))
        throw Error("log_psd_distance_db: no frequency bin where both spectra hold " + std::to_string(min_samples) +
                    " samples (images too small for the measure)");
    return distance;
}

double wasserstein1(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.empty() || b.empty()) throw Error("wasserstein1: a sample is empty");
    return wasserstein1_of_sorted(sorted_doubles(a), sorted_doubles(b));
}

double wasserstein1_of_sorted(const std::vector<double>& sorted_a, const std::vector<double>& sorted_b) {
    if (sorted_a.empty() || sorted_b.empty()) throw Error("wasserstein1: a sample is empty");
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

GradientStatistics gradient_statistics(const std::vector<float>& plane, int width, int height, int orientation_bins) {
    if (width < 3 || height < 3 || plane.size() != std::size_t(width) * height)
        throw Error("gradient_statistics: plane of " + std::to_string(plane.size()) + " values does not match a " +
                    std::to_string(width) + "x" + std::to_string(height) + " image of at least 3x3");
    if (orientation_bins < 1)
        throw Error("gradient_statistics: orientation_bins must be at least 1, got " + std::to_string(orientation_bins));
    double mean = 0, mean_square = 0;
    for (float v : plane) mean += v, mean_square += double(v) * v;
    mean /= double(plane.size());
    const double sigma = std::sqrt(std::max(0.0, mean_square / double(plane.size()) - mean * mean));
    if (!(sigma > 0)) throw Error("gradient_statistics: the plane is constant (no gradient to describe)");

    GradientStatistics statistics;
    statistics.orientation.assign(orientation_bins, 0.0);
    statistics.magnitude_over_sigma.reserve(std::size_t(width - 2) * (height - 2));
    const auto at = [&](int x, int y) { return double(plane[std::size_t(y) * width + x]); };
    double total = 0;
    for (int y = 1; y < height - 1; ++y)
        for (int x = 1; x < width - 1; ++x) {
            const double gx = 0.5 * (at(x + 1, y) - at(x - 1, y));
            const double gy = 0.5 * (at(x, y - 1) - at(x, y + 1));  // y up, as spectral_orientation
            const double magnitude = std::hypot(gx, gy);
            statistics.magnitude_over_sigma.push_back(float(magnitude / sigma));
            if (magnitude == 0) continue;
            double position = std::atan2(gy, gx) / kPi * orientation_bins;  // in bins, centres at integers
            position -= orientation_bins * std::floor(position / orientation_bins);
            const int lower = std::min(int(position), orientation_bins - 1);
            const double upper_share = position - lower;
            statistics.orientation[lower] += magnitude * (1 - upper_share);
            statistics.orientation[(lower + 1) % orientation_bins] += magnitude * upper_share;
            total += magnitude;
        }
    for (double& h : statistics.orientation) h /= total;
    return statistics;
}

double circular_wasserstein1_degrees(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size() || a.empty())
        throw Error("circular_wasserstein1_degrees: histograms of " + std::to_string(a.size()) + " and " +
                    std::to_string(b.size()) + " bins (need the same non-zero count)");
    double total_a = 0, total_b = 0;
    for (std::size_t k = 0; k < a.size(); ++k) total_a += a[k], total_b += b[k];
    if (!(total_a > 0) || !(total_b > 0)) throw Error("circular_wasserstein1_degrees: a histogram is empty");
    // On a circle the flow across the cut before bin 0 is free: W1 = min_c Σ|d_k − c|·Δ with
    // d_k the CDF difference, minimised by c = the median of the d_k (Werman, Peleg & Rosenfeld 1985).
    std::vector<double> cdf_difference(a.size());
    double running = 0;
    for (std::size_t k = 0; k < a.size(); ++k) cdf_difference[k] = running += a[k] / total_a - b[k] / total_b;
    std::vector<double> sorted = cdf_difference;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    double distance = 0;
    for (double d : cdf_difference) distance += std::abs(d - median);
    return distance * 180.0 / double(a.size());
}

std::array<double, 2> cielab_chroma(float r, float g, float b) {
    // Linear Rec.709 → XYZ (D65), relative to the white point; then CIE 1976 L*a*b*'s f, whose
    // linear toe handles dark and negative (out-of-gamut render) values without a cube root of < 0.
    const double x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
    const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
    const auto f = [](double t) {
        constexpr double delta = 6.0 / 29.0;
        return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0;
    };
    return {500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

namespace {

// ΔE*ab ≈ 2.3 is one just-noticeable difference (Sharma 2003): a bin is one JND wide, so the
// one-bin dilation forgives a chroma within about a JND of one the photo has.
constexpr double kChromaBin = 2.3, kChromaLow = -128.0;
constexpr int kChromaBins = 112;  // ⌈256 / 2.3⌉: a*, b* ∈ [−128, 128) (outliers clamp to the edge)
constexpr double kChromaHeld = 0.995;

int chroma_bin_of(const float* p) {
    const std::array<double, 2> chroma = cielab_chroma(p[0], p[1], p[2]);
    const int i = std::clamp(int(std::floor((chroma[0] - kChromaLow) / kChromaBin)), 0, kChromaBins - 1);
    const int j = std::clamp(int(std::floor((chroma[1] - kChromaLow) / kChromaBin)), 0, kChromaBins - 1);
    return j * kChromaBins + i;
}

/// The a*b* bins a test pixel may fall in without counting as false colour: the densest bins
/// holding kChromaHeld of the reference's pixels, dilated by one bin.
std::vector<char> held_chroma_region(const Image& reference) {
    std::vector<double> counts(kChromaBins * kChromaBins, 0.0);
    for (std::size_t p = 0; p < reference.pixel_count(); ++p) counts[chroma_bin_of(&reference.pixels[p * 3])] += 1;
    std::vector<int> order(counts.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::sort(order.begin(), order.end(), [&](int u, int v) { return counts[u] > counts[v]; });
    std::vector<char> held(counts.size(), 0), region(counts.size(), 0);
    double cumulative = 0;
    for (int bin : order) {
        if (cumulative >= kChromaHeld * double(reference.pixel_count())) break;
        held[bin] = 1;
        cumulative += counts[bin];
    }
    for (int j = 0; j < kChromaBins; ++j)
        for (int i = 0; i < kChromaBins; ++i) {
            if (!held[j * kChromaBins + i]) continue;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int u = i + di, v = j + dj;
                    if (u >= 0 && v >= 0 && u < kChromaBins && v < kChromaBins) region[v * kChromaBins + u] = 1;
                }
        }
    return region;
}

double outside_region_rate(const std::vector<char>& region, const Image& test) {
    std::size_t outside = 0;
    for (std::size_t p = 0; p < test.pixel_count(); ++p) outside += !region[chroma_bin_of(&test.pixels[p * 3])];
    return double(outside) / double(test.pixel_count());
}

}  // namespace

double false_colour_rate(const Image& reference, const Image& test) {
    require_rgb(reference, "false_colour_rate: reference");
    require_rgb(test, "false_colour_rate: test");
    return outside_region_rate(held_chroma_region(reference), test);
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
