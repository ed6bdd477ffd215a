// stochtex — the samples the 1-Wasserstein distance compares (wasserstein1 and
// wasserstein1_of_sorted are public, metrics.h; defined in wasserstein.cpp).
#pragma once

#include <vector>

namespace stochtex {

/// A sample as doubles, sorted ascending (what W1 compares).
std::vector<double> sorted_doubles(const std::vector<float>& sample);

}  // namespace stochtex
