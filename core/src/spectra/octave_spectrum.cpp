#include <stochtex/octave_spectrum.h>

#include <stochtex/error.h>

#include "numerics/nonnegative_least_squares.h"
#include "numerics/constants.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

double OctaveSpectrum::at(double log2_f) const
{
    const auto& l = log2_frequency;
    if (l.empty() || log2_f < l.front() || log2_f > l.back()) return 0;
    const std::size_t i = std::size_t(std::upper_bound(l.begin(), l.end(), log2_f) - l.begin());
    if (i == l.size()) return variance_per_octave.back();
    const double s = (log2_f - l[i - 1]) / (l[i] - l[i - 1]);
    return variance_per_octave[i - 1] + s * (variance_per_octave[i] - variance_per_octave[i - 1]);
}

double OctaveSpectrum::variance() const
{
    double sum = 0;
    for (std::size_t i = 0; i + 1 < log2_frequency.size(); ++i)
        sum += 0.5 * (variance_per_octave[i] + variance_per_octave[i + 1]) * (log2_frequency[i + 1] - log2_frequency[i]);
    return sum;
}

OctaveSpectrum octave_spectrum(const RadialPsd& psd, double samples_per_unit)
{
    if (!(samples_per_unit > 0)) throw Error("octave_spectrum: samples_per_unit must be positive");
    // An annulus of radius f and width df holds 2πf·df cycles²; df = f·ln2·dℓ.
    OctaveSpectrum spectrum;
    for (std::size_t i = 0; i < psd.frequency.size(); ++i) {
        const double f = psd.frequency[i];
        spectrum.log2_frequency.push_back(std::log2(f * samples_per_unit));
        spectrum.variance_per_octave.push_back(2 * kPi * f * f * std::log(2.0) * psd.power[i]);
    }
    return spectrum;
}

OctaveFit fit_octaves(const OctaveSpectrum& target, double target_variance, const OctaveSpectrum& basis,
                      double basis_variance, double finest_log2_frequency, int octave_count,
                      double shift_min, double shift_max)
{
    if (!(shift_min <= shift_max)) throw Error("fit_octaves: shift_min must not exceed shift_max");
    if (octave_count < 1) throw Error("fit_octaves: need at least one octave");
    if (!(basis_variance > 0) || basis.log2_frequency.empty()) throw Error("fit_octaves: the basis noise has no variance");
    const std::size_t n = target.log2_frequency.size();
    double peak = 0;
    for (double g : target.variance_per_octave) peak = std::max(peak, g);
    if (!(peak > 0) || !(target_variance > 0)) throw Error("fit_octaves: the target spectrum has no power");
    const double floor = 0.01 * peak;

    Eigen::VectorXd b(Eigen::Index(n), 1);
    for (std::size_t i = 0; i < n; ++i) {
        const double g = target.variance_per_octave[i];
        b[Eigen::Index(i)] = g / (g + floor);
    }
    auto design = [&](double shift) {
        Eigen::MatrixXd a(Eigen::Index(n), octave_count);
        for (std::size_t i = 0; i < n; ++i) {
            const double g = target.variance_per_octave[i];
            for (int k = 0; k < octave_count; ++k)
                a(Eigen::Index(i), k) = basis.at(target.log2_frequency[i] - (finest_log2_frequency + shift - k)) / (g + floor);
        }
        return a;
    };

    // The basis's shape is fixed, so only its position relative to the bands is free: scan it.
    double best_shift = 0, best_residual = INFINITY;
    Eigen::VectorXd best_power;
    for (double shift = shift_min; shift <= shift_max + 1e-9; shift += 1.0 / 16) {
        const Eigen::MatrixXd a = design(shift);
        const Eigen::VectorXd power = nonnegative_least_squares(a, b);
        const double residual = (a * power - b).squaredNorm();
        if (residual < best_residual) best_residual = residual, best_shift = shift, best_power = power;
    }

    // No finite residual at any shift: the spectra hold infinities or NaNs (values beyond float
    // range, e.g. a photo scaled by 1e18), so nothing can be fitted.
    if (best_power.size() != octave_count)
        throw Error("fit_octaves: no shift of the basis gives a finite fit (the spectrum is not finite)");
    OctaveFit fit;
    double fitted_variance = 0;
    for (int k = 0; k < octave_count; ++k) fitted_variance += best_power[k] * basis_variance;
    if (!(fitted_variance > 0)) throw Error("fit_octaves: no octave of the basis overlaps the target spectrum");
    const double scale = target_variance / fitted_variance;
    for (int k = 0; k < octave_count; ++k) {
        fit.log2_frequency.push_back(finest_log2_frequency + best_shift - k);
        fit.weight.push_back(std::sqrt(best_power[k] * scale));
    }
    double sum_squares = 0;
    int count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double g = target.variance_per_octave[i];
        if (g < floor) continue;
        double model = 0;
        for (int k = 0; k < octave_count; ++k)
            model += fit.weight[std::size_t(k)] * fit.weight[std::size_t(k)] *
                     basis.at(target.log2_frequency[i] - fit.log2_frequency[std::size_t(k)]);
        const double db = 10 * std::log10(std::max(model, 1e-30) / g);
        sum_squares += db * db;
        ++count;
    }
    fit.rms_error_db = count ? std::sqrt(sum_squares / count) : 0;
    return fit;
}

}  // namespace stochtex
