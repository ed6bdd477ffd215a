// stochtex — `analyze --model auto`: fit every model that can analyse photos, score each render
// against the photo, keep the best (stochtex/analysis.h states the rule).
#pragma once

#include <stochtex/analysis.h>

namespace stochtex {

/// analyze() with options.model == automatic_model lands here.
TextureDescription analyze_choosing_model(const Image& photo, const AnalysisOptions& options,
                                          const ProgressCallback& progress);

}  // namespace stochtex
