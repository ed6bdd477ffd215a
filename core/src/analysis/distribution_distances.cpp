// stochtex — the 1-Wasserstein distance between circular histograms
// (analysis/distribution_distances.h); that between samples is in numerics/wasserstein.cpp.
#include "analysis/distribution_distances.h"

#include <stochtex/error.h>
#include <stochtex/metrics.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace stochtex {

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

}  // namespace stochtex
