// stochtex — what the 1-Wasserstein distances share with compare_images, which sorts each
// photo's samples once (wasserstein1 and wasserstein1_of_sorted are in metrics.h).
#pragma once

#include <vector>

namespace stochtex {

/// A sample as doubles, sorted ascending (what W1 compares).
std::vector<double> sorted_doubles(const std::vector<float>& sample);

}  // namespace stochtex
