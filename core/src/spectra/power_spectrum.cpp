// stochtex — power spectra of a plane (metrics.h and spectra/power_spectrum.h): one windowed
// periodogram read as a radial, a polar and a centred spectrum, and the radial log-PSD distance.
// Here, below the models, because the models' fits measure with them (gabor's and tiling's fits,
// ptm's truth comparison); the 2D distances only compare_images uses are in analysis/.
#include "spectra/power_spectrum.h"

#include "spectra/fft.h"
#include "numerics/constants.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

namespace stochtex {
namespace {

constexpr double kNyquist = 0.5;  // cycles per pixel

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

}  // namespace

// Normalisation. With x' = (x − mean)·w (w the separable Hann window) and F its unnormalised
// DFT, the periodogram P_k = |F_k|² / (W·H)² sums over all bins to mean(x'²) (Parseval), which
// is the variance times mean(w²); dividing by mean(w²) makes Σ_k P_k the channel variance.
// Each FFT bin covers a frequency area of 1/(W·H) cycles²/pixel², so the reported power is the
// density S = P_k·W·H = |F_k|² / (W·H·mean(w²)), averaged over the bin's FFT samples: white noise
// of variance σ² gives S = σ² in every bin at any image size, and Σ_k S_k / (W·H) = variance.
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

namespace {

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

}  // namespace

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

RadialPsd radial_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave) {
    require_bins_per_octave(bins_per_octave, "radial_psd");
    return radial_psd_of(windowed_spectrum(plane, width, height, "radial_psd"), bins_per_octave);
}

PolarPsd polar_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave, int angle_bins) {
    require_bins_per_octave(bins_per_octave, "polar_psd");
    if (angle_bins < 1) throw Error("polar_psd: angle_bins must be at least 1, got " + std::to_string(angle_bins));
    return polar_psd_of(windowed_spectrum(plane, width, height, "polar_psd"), bins_per_octave, angle_bins);
}

CentredSpectrum centred_spectrum(const std::vector<float>& plane, int width, int height, int size) {
    if (size < 1) throw Error("centred_spectrum: size must be at least 1, got " + std::to_string(size));
    return centred_spectrum_of(windowed_spectrum(plane, width, height, "centred_spectrum"), size);
}

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

double log_psd_distance_db(const RadialPsd& a, const RadialPsd& b, int min_samples) {
    const double distance = log_psd_distance_or_nan(a, b, min_samples);
    if (std::isnan(distance))
        throw Error("log_psd_distance_db: no frequency bin where both spectra hold " + std::to_string(min_samples) +
                    " samples (images too small for the measure)");
    return distance;
}

}  // namespace stochtex
