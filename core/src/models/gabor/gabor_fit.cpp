#include "models/gabor/gabor_fit.h"

#include "models/gabor/gabor_statistics.h"
#include "numerics/constants.h"
#include "spectra/power_spectrum.h"

#include <stochtex/error.h>
#include <stochtex/metrics.h>
#include <stochtex/octave_spectrum.h>
#include <stochtex/models/gabor_parameters.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {

/// Candidate bandwidths (a/F) for isotropic and hybrid fits: from narrow rings (0.5: octaves
/// show as separate bumps) to broad ones (2: octaves overlap, kernels are blobs).
constexpr double candidate_bandwidths[] = {0.5, 0.7, 1.0, 1.4, 2.0};
/// Anisotropic bandwidth from the photo's anisotropy is clamped to this range.
constexpr double min_anisotropic_bandwidth = 0.25, max_anisotropic_bandwidth = 2.0;
/// Oriented fractions below this are estimation noise (and cost a hash per impulse): set to 0.
constexpr double min_oriented_fraction = 0.15;
/// The periodogram's noise in |mean e^{2iθ}|²: about 4/n for n FFT samples (mirrors counted, so
/// n/2 independent exponential ones), widened 2.25× by the Hann window's correlation of
/// neighbouring samples.
constexpr double moment_noise_samples = 9;
/// The finest octave sits at 2^(finest_log2 + shift) cycles per pixel, the shift searched in
/// [shift_min, shift_max] by 1/16 octave: 0.125 … 0.35 cycles per pixel.
constexpr double finest_log2 = -2, shift_min = -1.0, shift_max = 0.5;

double variance_of(const std::vector<float>& values)
{
    double sum = 0, sum_sq = 0;
    for (float v : values) sum += v, sum_sq += double(v) * v;
    const double mean = sum / double(values.size());
    return std::max(0.0, sum_sq / double(values.size()) - mean * mean);
}

/// The variance per octave (octave_spectrum.h) of one octave's slice, sampled widely.
OctaveSpectrum sampled_octave_spectrum(const GaborNoiseParameters& octave)
{
    OctaveSpectrum spectrum;
    for (double l = -14; l <= 3 + 1e-9; l += 1.0 / 16) {
        const double rho = std::exp2(l);
        spectrum.log2_frequency.push_back(l);
        spectrum.variance_per_octave.push_back(2 * kPi * rho * rho * std::log(2.0) * gabor_slice_radial_psd(octave, rho));
    }
    return spectrum;
}

/// The variance per octave (octave_spectrum.h) of one octave at frequency 1, sampled widely:
/// as the renders show it (the slice w = const) or, without slice correction, as a 2D ring.
OctaveSpectrum unit_octave_spectrum(GaborKind kind, const Vec3& direction, double bandwidth, bool slice_correction)
{
    GaborNoiseParameters octave;
    octave.kind = kind;
    octave.direction = direction;
    octave.frequency = 1;
    octave.bandwidth = bandwidth;
    if (!slice_correction && kind == GaborKind::isotropic) octave.kind = GaborKind::hybrid;  // the ring
    return sampled_octave_spectrum(octave);
}

/// The frequency direction and the anisotropy of the channels' spectra, from the gradient
/// structure tensor: E[∇I ∇Iᵀ] = 4π² ∫ f fᵀ PSD(f) df (Parseval), so its major axis is the
/// spectrum's and its eigenvalue ratio the spectrum's (no FFT, hence no edge leak).
struct SpectralAxes {
    Vec3 direction{1, 0, 0};
    double minor_to_major = 1;
};

SpectralAxes spectral_axes(const std::array<std::vector<float>, 3>& channels, int width, int height)
{
    double xx = 0, xy = 0, yy = 0;
    for (const std::vector<float>& plane : channels)
        for (int y = 1; y + 1 < height; ++y)
            for (int x = 1; x + 1 < width; ++x) {
                const std::size_t i = std::size_t(y) * width + x;
                const double gx = 0.5 * (plane[i + 1] - plane[i - 1]), gy = 0.5 * (plane[i + width] - plane[i - width]);
                xx += gx * gx, xy += gx * gy, yy += gy * gy;
            }
    SpectralAxes axes;
    const double half_trace = 0.5 * (xx + yy), root = std::hypot(0.5 * (xx - yy), xy);
    const double major = half_trace + root, minor = half_trace - root;
    if (!(major > 0)) return axes;
    // Eigenvector of the major eigenvalue: (xy, major − xx), or (major − yy, xy) when that vanishes.
    double dx = xy, dy = major - xx;
    if (std::hypot(dx, dy) < 1e-12 * major) dx = major - yy, dy = xy;
    const double length = std::hypot(dx, dy);
    axes.direction = {dx / length, dy / length, 0};
    axes.minor_to_major = std::max(0.0, minor) / major;
    return axes;
}

/// |mean of e^{2iθ}| over one all-oriented octave's 2D spectrum (blobs exp(−2π|f ∓ ω|²/a²),
/// |ω| = F, a = βF) restricted to the octave's annulus [F/√2, F√2]: what a measured length is
/// divided by to give the oriented fraction. Scale-free, so F = 1.
double oriented_moment_length(double bandwidth)
{
    const double k = 2 * kPi / (bandwidth * bandwidth);
    double sum = 0, moment = 0;
    constexpr int radii = 64, angles = 180;
    for (int i = 0; i < radii; ++i) {
        const double rho = std::exp2(-0.5 + (i + 0.5) / radii);
        for (int j = 0; j < angles; ++j) {
            const double phi = kPi * ((j + 0.5) / angles - 0.5);
            const double x = rho * std::cos(phi), y = rho * std::sin(phi);
            const double power = std::exp(-k * ((x - 1) * (x - 1) + y * y)) + std::exp(-k * ((x + 1) * (x + 1) + y * y));
            sum += power * rho * rho;  // dA = ρ dρ dφ, and dρ ∝ ρ on the log grid
            moment += power * rho * rho * std::cos(2 * phi);
        }
    }
    return sum > 0 ? moment / sum : 0;
}

struct OctaveOrientation {
    double degrees = 0, fraction = 0;
};

/// Octave orientations and fractions (gabor_fit.h) from the channels' polar spectra.
std::vector<OctaveOrientation> octave_orientations(const std::vector<PolarPsd>& spectra,
                                                   const std::vector<double>& frequencies, double bandwidth)
{
    const double full = oriented_moment_length(bandwidth);
    std::vector<OctaveOrientation> result(frequencies.size());
    for (std::size_t k = 0; k < frequencies.size(); ++k) {
        double sum = 0, re = 0, im = 0, samples = 0;
        for (const PolarPsd& spectrum : spectra) {
            const int angles = spectrum.angle_bins;
            double channel_samples = 0;
            for (std::size_t r = 0; r < spectrum.frequency.size(); ++r) {
                const double f = spectrum.frequency[r];
                if (f < frequencies[k] * M_SQRT1_2 || f >= frequencies[k] * M_SQRT2) continue;
                for (int a = 0; a < angles; ++a) {
                    const std::size_t cell = r * std::size_t(angles) + std::size_t(a);
                    // Power in the cell: the mean density times its samples (of equal area).
                    const double power = spectrum.power[cell] * spectrum.samples[cell];
                    // polar_psd's θ turns from x towards y up; v grows down the photo's rows.
                    const double theta = -kPi * a / angles;
                    sum += power, re += power * std::cos(2 * theta), im += power * std::sin(2 * theta);
                    channel_samples += spectrum.samples[cell];
                }
            }
            samples = std::max(samples, channel_samples);
        }
        if (!(sum > 0) || !(samples > 0)) continue;
        const double length2 = (re * re + im * im) / (sum * sum) - moment_noise_samples / samples;
        const double fraction = length2 > 0 && full > 0 ? std::min(1.0, std::sqrt(length2) / full) : 0.0;
        result[k].degrees = 0.5 * std::atan2(im, re) * 180 / kPi;
        result[k].fraction = fraction >= min_oriented_fraction ? fraction : 0.0;
    }
    return result;
}

struct ChannelTarget {
    OctaveSpectrum spectrum;
    double variance = 0;
};

struct Fit {
    double residual = INFINITY;  // channel-variance-weighted RMS dB
    double bandwidth = 1, shift = 0;
    std::array<std::vector<double>, 3> weights;
};

/// Best common octave placement for one bandwidth: the shift is shared by the channels (their
/// octaves are the same noises), so it minimises the variance-weighted sum of their residuals.
Fit fit_bandwidth(const std::array<ChannelTarget, 3>& targets, const OctaveSpectrum& basis, double bandwidth, int octaves)
{
    Fit best;
    double total_variance = 0;
    for (const ChannelTarget& target : targets) total_variance += target.variance;
    for (double shift = shift_min; shift <= shift_max + 1e-9; shift += 1.0 / 16) {
        Fit fit;
        fit.bandwidth = bandwidth, fit.shift = shift, fit.residual = 0;
        for (int c = 0; c < 3; ++c) {
            if (!(targets[c].variance > 0)) {
                fit.weights[c].assign(std::size_t(octaves), 0.0);
                continue;
            }
            const OctaveFit octave_fit =
                fit_octaves(targets[c].spectrum, targets[c].variance, basis, 1.0, finest_log2, octaves, shift, shift);
            fit.weights[c] = octave_fit.weight;
            fit.residual += octave_fit.rms_error_db * targets[c].variance / total_variance;
        }
        if (fit.residual < best.residual) best = fit;
    }
    return best;
}

}  // namespace

GaborParameters fit_gabor_octaves(const std::array<std::vector<float>, 3>& channels, int width, int height,
                                  const GaborFitOptions& options)
{
    if (options.octaves < 1 || options.octaves > 24) throw Error("Gabor fit: octave count must be in [1, 24]");
    std::array<ChannelTarget, 3> targets;
    std::vector<PolarPsd> polar;  // the oriented kind's
    const bool oriented = options.kind == GaborKind::oriented;
    bool any_variance = false;
    for (int c = 0; c < 3; ++c) {
        targets[c].variance = variance_of(channels[c]);
        // A channel without variance (the chroma axes of a grey photo) gets zero weights.
        if (!(targets[c].variance > 1e-14)) {
            targets[c].variance = 0;
            continue;
        }
        any_variance = true;
        // Bins below 2 cycles per image are mostly the Hann window's main lobe: not fitted.
        RadialPsd psd = radial_psd(channels[c], width, height, 8);
        const double lowest = 2.0 / std::min(width, height);
        std::size_t first = 0;
        while (first < psd.frequency.size() && psd.frequency[first] < lowest) ++first;
        psd.frequency.erase(psd.frequency.begin(), psd.frequency.begin() + std::ptrdiff_t(first));
        psd.power.erase(psd.power.begin(), psd.power.begin() + std::ptrdiff_t(first));
        targets[c].spectrum = octave_spectrum(psd, 1.0);
        if (oriented) polar.push_back(polar_psd(channels[c], width, height, 8, 36));
    }

    GaborParameters parameters;
    // The oriented kind starts from the isotropic fit (its frequencies place the annuli).
    parameters.kind = oriented ? GaborKind::isotropic : options.kind;
    parameters.impulses_per_kernel = options.impulses_per_kernel;
    std::vector<double> bandwidths(std::begin(candidate_bandwidths), std::end(candidate_bandwidths));
    if (options.kind == GaborKind::anisotropic) {
        const SpectralAxes axes = spectral_axes(channels, width, height);
        parameters.direction = axes.direction;
        // One anisotropic octave's spectrum has second moments F²(1 + β²/4π) along ω and F²β²/4π
        // across, whatever the weights: match the photo's ratio.
        const double ratio = std::min(axes.minor_to_major, 0.99);
        bandwidths = {std::clamp(std::sqrt(4 * kPi * ratio / (1 - ratio)), min_anisotropic_bandwidth,
                                 max_anisotropic_bandwidth)};
    }
    if (options.bandwidth > 0) bandwidths = {options.bandwidth};

    Fit best;
    if (!any_variance) {
        best.bandwidth = bandwidths.front();
        for (auto& w : best.weights) w.assign(std::size_t(options.octaves), 0.0);
    }
    for (double bandwidth : any_variance ? bandwidths : std::vector<double>{}) {
        const OctaveSpectrum basis = unit_octave_spectrum(parameters.kind, parameters.direction, bandwidth,
                                                          options.slice_correction);
        const Fit fit = fit_bandwidth(targets, basis, bandwidth, options.octaves);
        if (fit.residual < best.residual) best = fit;
    }
    parameters.bandwidth = best.bandwidth;
    for (int k = 0; k < options.octaves; ++k) parameters.frequencies.push_back(std::exp2(finest_log2 + best.shift - k));
    parameters.weights = best.weights;
    if (!oriented || !any_variance) {
        if (oriented && !options.isotropic_if_unoriented) {
            parameters.kind = GaborKind::oriented;
            parameters.orientations.assign(parameters.frequencies.size(), 0.0);
            parameters.oriented_fractions.assign(parameters.frequencies.size(), 0.0);
        }
        return parameters;
    }

    const std::vector<OctaveOrientation> orientation = octave_orientations(polar, parameters.frequencies, best.bandwidth);
    double weighted = 0, total = 0;
    for (std::size_t k = 0; k < orientation.size(); ++k) {
        const double power = best.weights[0][k] * best.weights[0][k] + best.weights[1][k] * best.weights[1][k] +
                             best.weights[2][k] * best.weights[2][k];
        weighted += power * orientation[k].fraction, total += power;
    }
    if (!(weighted > 0) && options.isotropic_if_unoriented) return parameters;
    parameters.kind = GaborKind::oriented;
    for (const OctaveOrientation& octave : orientation) {
        parameters.orientations.push_back(octave.degrees);
        parameters.oriented_fractions.push_back(octave.fraction);
    }
    // The weights again, with the sliced spectrum of the octaves' mean mixture (an oriented
    // octave keeps its power at F; an isotropic one's slice spreads part of it below), the
    // placement kept. (A basis per octave, each with its own fraction, fitted palm_bark worse:
    // oriented coarse octaves leak nothing below, so NNLS fed the coarsest octave, whose
    // near-DC power then showed as mean errors of 0.1–0.2 σ in renders.)
    if (weighted > 0) {
        GaborNoiseParameters mixture;
        mixture.kind = GaborKind::oriented;
        mixture.direction = {1, 0, 0};
        mixture.oriented_fraction = weighted / total;
        mixture.frequency = 1;
        mixture.bandwidth = best.bandwidth;
        const OctaveSpectrum basis = sampled_octave_spectrum(mixture);
        for (int c = 0; c < 3; ++c)
            if (targets[c].variance > 0)
                parameters.weights[c] = fit_octaves(targets[c].spectrum, targets[c].variance, basis, 1.0, finest_log2,
                                                    options.octaves, best.shift, best.shift)
                                            .weight;
    }
    return parameters;
}

}  // namespace stochtex
