// stochtex — 1-Wasserstein distances between samples and between circular histograms
// (metrics.h and analysis/distribution_distances.h).
#include "analysis/distribution_distances.h"

#include <stochtex/error.h>
#include <stochtex/metrics.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace stochtex {

std::vector<double> sorted_doubles(const std::vector<float>& sample) {
    std::vector<double> sorted(sample.begin(), sample.end());
    std::sort(sorted.begin(), sorted.end());
    return sorted;
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
