// stochtex — the distribution distance only compare_images and the tests call: W1 of
// orientation histograms on the circle. W1 of samples (wasserstein1 and wasserstein1_of_sorted,
// public in metrics.h, which the fits use) and the sorted samples compare_images makes of each
// photo once (sorted_doubles) are below the models, in numerics/wasserstein.h.
#pragma once

#include "numerics/wasserstein.h"

#include <vector>

namespace stochtex {

/// 1-Wasserstein distance on the circle of circumference 180° between two orientation
/// histograms of the same bin count, in degrees: the mean angle the gradient energy of one must
/// turn to become the other (0 … 45° for mass moved by at most 90°). Werman et al.: with the
/// CDF differences d_k, min over c of Σ|d_k − c|·Δ, c the (weighted) median of d_k.
double circular_wasserstein1_degrees(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace stochtex
