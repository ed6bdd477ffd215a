// stochtex — `analyze --model auto`: fit every model that can analyse photos, score each render
// against the photo, keep the best (stochtex/analysis.h states the rule).
#pragma once

#include <stochtex/analysis.h>
#include <stochtex/metrics.h>

#include <cstddef>
#include <functional>
#include <vector>

namespace stochtex {

/// The side the choice renders each candidate at, at most (the photo's own pixel scale, from the
/// texture's origin): large enough that the metrics see an octave below the features a 512²
/// photo holds, small enough that the slowest model renders it in a fraction of a second. The
/// photo itself is measured whole.
constexpr int max_scoring_side = 384;

/// A fitted description's score as the choice measures it: its render (at the photo's pixel
/// scale, at most max_side² pixels from the texture's origin, on `threads` threads: 1 where
/// candidates run side by side, 0 for all; the render does not depend on it) against the whole
/// photo. Also what a model's fit uses to choose among its own candidates (FitInput::score).
ModelScore score_against_photo(const TextureDescription& description, const ComparisonReference& photo, int max_side,
                               const FidelityTargets& targets = {}, int threads = 1);

/// The rule: the index of the score to keep of `scores` (not empty), the lowest penalty or,
/// among those within model_choice_tolerance of it (differences the metrics' own noise makes),
/// the smallest file (a fit's variant counts as its fit's size), then the lower penalty, then the
/// first. Also what a model's fit keeps its own candidates by
/// (FitInput::choose).
std::size_t chosen_by_rule(const std::vector<ModelScore>& scores);

/// The rule where structure is scored (`--choice-structure`; issue 33): first the default's
/// choice, chosen_by_rule over the fits without a variant by `penalties_without_structure` (the
/// six-term penalties, one per score); then chosen_by_rule, by the scores' own (seven-term)
/// penalties, over that choice and every row no worse than it on the six existing targets —
/// each metric on its target where the default's is, else within model_choice_tolerance of the
/// default's, and the 2D distance within model_choice_tolerance of the closest plain fit's
/// among those on the W1 and false-colour targets (or no further than the default's). So the
/// structure term decides only among textures that keep what the default's keeps. Where
/// `at_full_size` is given (the row's score on a render of the photo's whole size), the default's
/// choice and the max_full_size_checks rows the seven-term penalty ranks first are scored there;
/// those no worse than the default's choice there (its 2D distance within model_choice_tolerance
/// of the default's) stay, and chosen_by_rule decides among them by their full-size scores.
using ScoreAtFullSize = std::function<ModelScore(std::size_t row)>;
constexpr int max_full_size_checks = 3;
std::size_t chosen_weighing_structure(const std::vector<ModelScore>& scores,
                                      const std::vector<double>& penalties_without_structure,
                                      const FidelityTargets& targets, const ScoreAtFullSize& at_full_size = {});

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
