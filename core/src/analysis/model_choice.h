// stochtex — `analyze --model auto`: fit every model that can analyse photos, score each render
// against the photo, keep the best (stochtex/analysis.h states the rule).
#pragma once

#include <stochtex/analysis.h>
#include <stochtex/metrics.h>

#include <cstddef>
#include <vector>

namespace stochtex {

/// The side the choice renders each candidate at, at most (the photo's own pixel scale, from the
/// texture's origin): large enough that the metrics see an octave below the features a 512²
/// photo holds, small enough that the slowest model renders it in a fraction of a second. The
/// photo itself is measured whole.
constexpr int max_scoring_side = 384;

/// A fitted description's score as the choice measures it: its render (at the photo's pixel
/// scale, at most max_side² pixels from the texture's origin, on one thread) against the whole
/// photo. Also what a model's fit uses to choose among its own candidates (FitInput::score).
ModelScore score_against_photo(const TextureDescription& description, const ComparisonReference& photo, int max_side,
                               const FidelityTargets& targets = {});

/// The rule: the index of the score to keep of `scores` (not empty), the lowest penalty or,
/// among those within model_choice_tolerance of it (differences the metrics' own noise makes),
/// the smallest file (a fit's variant counts as its fit's size), then the lower penalty, then the
/// first. Also what a model's fit keeps its own candidates by
/// (FitInput::choose).
std::size_t chosen_by_rule(const std::vector<ModelScore>& scores);

/// analyze() with options.model == automatic_model lands here.
TextureDescription analyze_choosing_model(const Image& photo, const AnalysisOptions& options,
                                          const ProgressCallback& progress);

/// analyze() of one named model (not automatic_model) whose fit scores its own candidates
/// (FitInput::score) against `prepared_photo`, the photo's side of the comparison already made by
/// the caller (the choice makes it once for every candidate); nullptr: made at the first score.
/// `prepared_photo` must be of `photo` itself.
TextureDescription analyze_one_model(const Image& photo, const AnalysisOptions& options,
                                     const ProgressCallback& progress, const ComparisonReference* prepared_photo);

}  // namespace stochtex
