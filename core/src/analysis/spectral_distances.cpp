// stochtex — the 2D log-PSD distances between polar spectra (analysis/spectral_distances.h);
// the spectra themselves are in spectra/power_spectrum.cpp.
#include "analysis/spectral_distances.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace stochtex {

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

}  // namespace stochtex
