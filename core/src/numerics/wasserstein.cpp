// stochtex — the 1-Wasserstein distance between samples (metrics.h, numerics/wasserstein.h):
// below the models, whose fits measure with it (tiling's exemplar score, ptm's truth comparison).
#include "numerics/wasserstein.h"

#include <stochtex/error.h>
#include <stochtex/metrics.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

}  // namespace stochtex
