// stochtex — progress reporting for long work (analysis, renders, bakes).
#pragma once

#include <functional>

namespace stochtex {

/// Called with the fraction done in [0, 1] and a short stage name. May be empty. Called from
/// the calling thread only, so front-ends need no locking.
using ProgressCallback = std::function<void(double fraction, const char* stage)>;

}  // namespace stochtex
