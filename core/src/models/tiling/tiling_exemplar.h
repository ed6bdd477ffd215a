// How a tiling texture's exemplar is made from image planes: a representative crop whose sides are
// powers of two (the moment pyramids need them), made periodic by Moisan's decomposition (tiles
// are cut anywhere in it, with wrap: a seam would show inside tiles, notes P2.7 #6), quantised.
#pragma once

#include <stochtex/texture_description.h>
#include <stochtex/models/tiling_parameters.h>

#include <stochtex/metrics.h>

#include "spectra/periodic_crop.h"

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace stochtex {

/// The largest power of two ≤ n (n ≥ 1).
int power_of_two_floor(int n);

/// A crop of a photo and how well it stands for the whole: its channels' value distributions
/// (W1 in σ, the worst channel) and its main channel's radial spectrum (log-PSD dB) against the
/// whole photo's, each in units of its fidelity target (stochtex/metrics.h, FidelityTargets).
struct RepresentativeCrop {
    CropOrigin origin;
    double w1_term = 0, spectrum_term = 0;
    /// Both on target: its statistics are the photo's to within what a synthesis is asked for.
    bool representative() const { return w1_term <= 1 && spectrum_term <= 1; }
    double total() const { return w1_term + spectrum_term; }
};

/// What crops are measured against, computed once per photo (not once per crop size tried):
/// each decorrelated channel's sorted values (sampled to about 64k) and σ, and the main
/// channel's radial spectrum.
struct PhotoStatistics {
    std::array<std::vector<double>, 3> sorted;
    std::array<double, 3> sigma{};
    RadialPsd main_psd;
};
PhotoStatistics photo_statistics(const std::array<std::vector<float>, 3>& channels, int width, int height);

/// The crop_width × crop_height crop of the decorrelated channels that best stands for the whole
/// photo (`whole`: photo_statistics of the same channels): of positions evenly spaced over it
/// (the centred one included, and kept on ties), the one with the lowest sum of the two terms.
/// A photo whose centre is lighter or smoother than the rest no longer gives a texture that is.
RepresentativeCrop representative_crop(const std::array<std::vector<float>, 3>& channels, int width, int height,
                                       int crop_width, int crop_height, const PhotoStatistics& whole);

/// fit_tiling_exemplar's max_side for "auto" (`--exemplar-size auto`, the default).
constexpr int automatic_exemplar_side = 0;

/// A crop size and its most representative crop.
struct SizedCrop {
    int width = 0, height = 0;
    RepresentativeCrop crop;
};

/// The crops automatic sizing chooses among, smallest first, each at its most representative
/// position: 256², then 512² and 1024² where the photo holds them twice along each axis (an
/// exemplar as large as its photo is a copy, not a sample), up to the first whose statistics
/// stand for the photo (representative()). A larger one is tried only where the smaller crops'
/// statistics miss the targets (karst rock's plates are larger than 256²): a photo a 256² crop
/// serves keeps its 4× smaller file without a render, as concrete's RGB exemplar does.
std::vector<SizedCrop> automatic_exemplar_candidates(const std::array<std::vector<float>, 3>& channels, int width,
                                                     int height);

/// Scores a candidate exemplar's parameters by its render against the photo (FitInput::score).
using TilingCandidateScore = std::function<ModelScore(const ModelParameters&, int max_side)>;
/// The index of the score to keep among the candidates' (FitInput::choose: `--model auto`'s rule).
using TilingCandidateChoice = std::function<std::size_t(const std::vector<ModelScore>& scores)>;

/// The colour-output parameters from the analysis's decorrelated channels of a width × height
/// photo, Gaussianised where the channel has a histogram map: the exemplar is their most
/// representative crop (representative_crop) of at most max_side² pixels, periodic, at `bits`
/// bits. max_side automatic_exemplar_side: of automatic_exemplar_candidates, the one whose render
/// `score` rates best by `choose`, `--model auto`'s rule (fidelity first, within its tolerance the
/// smallest file); a single candidate is taken unrendered. Crop statistics alone chose 512² for
/// rusted metal, whose RGB render is then 1.86 dB off in radial spectrum where 256²'s is 1.14 dB.
/// A channel with a map is stored in standard-normal units by the crop's own ranks (the map's
/// input), the others in channel units with the whole channel's mean and σ, so the texture's
/// histograms are the photo's and the texture passes stored values to ColourMapping unscaled.
TilingParameters fit_tiling_exemplar(const std::array<std::vector<float>, 3>& channels, int width, int height,
                                     const std::array<HistogramMap, 3>& histograms, int max_side, int bits,
                                     const TilingCandidateScore& score, const TilingCandidateChoice& choose);

}  // namespace stochtex
