#include "models/tiling/tiling_exemplar.h"

#include "colour/histogram_map.h"

#include "spectra/periodic_crop.h"
#include "schema/quantised_image.h"
#include "models/tiling/tiling_parameters.h"

#include <stochtex/error.h>
#include <stochtex/metrics.h>
#include <stochtex/models/tiling_parameters.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

int power_of_two_floor(int n)
{
    int p = 1;
    while (p <= n / 2) p *= 2;
    return p;
}

namespace {

/// Every step-th value of every step-th row of a plane's region, sorted (a distribution's
/// sample: W1 to within a few thousandths of σ at 16k values).
std::vector<double> sorted_sample(const std::vector<float>& plane, int width, int x0, int y0, int w, int h, int step)
{
    std::vector<double> sample;
    sample.reserve(std::size_t(w / step + 1) * (h / step + 1));
    for (int y = y0; y < y0 + h; y += step)
        for (int x = x0; x < x0 + w; x += step) sample.push_back(plane[std::size_t(y) * width + x]);
    std::sort(sample.begin(), sample.end());
    return sample;
}

/// At most this many crop positions per axis are tried, evenly spaced from edge to edge.
constexpr int crop_positions_per_axis = 5;
/// The spectrum is compared for this many of the positions whose value distributions match best.
constexpr int crops_with_spectrum_compared = 3;

}  // namespace

PhotoStatistics photo_statistics(const std::array<std::vector<float>, 3>& channels, int width, int height)
{
    PhotoStatistics whole;
    const int step = std::max(1, int(std::sqrt(double(width) * height / 65536.0)));
    for (int c = 0; c < 3; ++c) {
        whole.sorted[c] = sorted_sample(channels[c], width, 0, 0, width, height, step);
        double sum = 0, sum2 = 0;
        for (double v : whole.sorted[c]) sum += v, sum2 += v * v;
        const double n = double(whole.sorted[c].size());
        whole.sigma[c] = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
    }
    whole.main_psd = radial_psd(channels[0], width, height);
    return whole;
}

RepresentativeCrop representative_crop(const std::array<std::vector<float>, 3>& channels, int width, int height,
                                       int crop_width, int crop_height, const PhotoStatistics& whole)
{
    const CropOrigin centred{(width - crop_width) / 2, (height - crop_height) / 2};
    if (crop_width == width && crop_height == height) return {centred, 0, 0};
    const FidelityTargets targets;
    // The crops' distributions are sampled to about 16k values.
    const int crop_step = std::max(1, int(std::sqrt(double(crop_width) * crop_height / 16384.0)));
    // Mean, σ and histogram at once: each channel's W1 to the whole photo's, in its σ (the
    // decorrelated channels are uncorrelated over the photo; a crop's own correlation shows in
    // the channels' distributions of the rendered colours, which this sees through each axis).
    std::vector<RepresentativeCrop> scored;
    const auto positions = [](int free, int count) {
        std::vector<int> result;
        for (int i = 0; i < count; ++i) result.push_back(count == 1 ? free / 2 : int(std::lround(double(free) * i / (count - 1))));
        return result;
    };
    const int nx = width > crop_width ? crop_positions_per_axis : 1, ny = height > crop_height ? crop_positions_per_axis : 1;
    std::vector<CropOrigin> origins{centred};  // first: it wins ties
    for (int y0 : positions(height - crop_height, ny))
        for (int x0 : positions(width - crop_width, nx))
            if (x0 != centred.x || y0 != centred.y) origins.push_back({x0, y0});
    for (const CropOrigin& origin : origins) {
        double w1 = 0;
        for (int c = 0; c < 3; ++c)
            if (whole.sigma[c] > 0)
                w1 = std::max(w1, wasserstein1_of_sorted(sorted_sample(channels[c], width, origin.x, origin.y, crop_width,
                                                                       crop_height, crop_step),
                                                         whole.sorted[c]) / whole.sigma[c]);
        scored.push_back({origin, w1 / targets.w1_sigma, 0});
    }
    // Then the spectrum of the main channel (the first: PCA's largest variance) for the best few,
    // each term in units of its fidelity target, as the automatic model choice weighs them.
    std::stable_sort(scored.begin(), scored.end(), [](const RepresentativeCrop& a, const RepresentativeCrop& b) { return a.w1_term < b.w1_term; });
    scored.resize(std::min<std::size_t>(scored.size(), crops_with_spectrum_compared));
    for (RepresentativeCrop& s : scored) {
        const RadialPsd crop_psd = radial_psd(plane_region(channels[0], width, s.origin.x, s.origin.y, crop_width, crop_height),
                                              crop_width, crop_height);
        s.spectrum_term = log_psd_distance_db(crop_psd, whole.main_psd) / targets.radial_log_psd_db;
    }
    return *std::min_element(scored.begin(), scored.end(),
                             [](const RepresentativeCrop& a, const RepresentativeCrop& b) { return a.total() < b.total(); });
}

namespace {

/// The exemplar sides automatic sizing tries, smallest first; a file grows 4× a step.
constexpr int automatic_exemplar_sides[] = {256, 512, 1024};
/// Automatic sizing renders each candidate at the photo's size, up to this side: `--model auto`'s
/// 384² render holds less than one 512² exemplar and cannot see it repeat (it rated rusted
/// metal's 512² RGB exemplar best, whose full-size render is 1.86 dB off in radial spectrum
/// where the 256² one's is 1.14 dB).
constexpr int exemplar_scoring_side = 1024;

/// The crop sides (powers of two) of an exemplar of at most `side` in a width × height photo.
std::array<int, 2> crop_sides(int width, int height, int side)
{
    return {power_of_two_floor(std::min(width, side)), power_of_two_floor(std::min(height, side))};
}

}  // namespace

std::vector<SizedCrop> automatic_exemplar_candidates(const std::array<std::vector<float>, 3>& channels, int width,
                                                     int height)
{
    const PhotoStatistics whole = photo_statistics(channels, width, height);
    std::vector<SizedCrop> candidates;
    for (int side : automatic_exemplar_sides) {
        if (side != automatic_exemplar_sides[0] && 2 * side > std::min(width, height)) break;
        const std::array<int, 2> sides = crop_sides(width, height, side);
        candidates.push_back({sides[0], sides[1], representative_crop(channels, width, height, sides[0], sides[1], whole)});
        if (candidates.back().crop.representative()) break;
    }
    return candidates;
}

namespace {

/// The parameters of one candidate crop (fit_tiling_exemplar's units).
TilingParameters exemplar_of(const std::array<std::vector<float>, 3>& channels, int width, int height,
                             const std::array<HistogramMap, 3>& histograms, const SizedCrop& chosen, int bits)
{
    const int crop_width = chosen.width, crop_height = chosen.height;
    const CropOrigin origin = chosen.crop.origin;
    std::vector<std::vector<float>> planes;
    for (int c = 0; c < 3; ++c) {
        std::vector<float>& plane = planes.emplace_back(periodic_crop(channels[c], width, height, crop_width, crop_height, origin));
        // Even the most representative crop holds less of the photo's large-scale variation than
        // the whole photo does (and the periodic component removes a little more): its values
        // are given the whole photo's distribution, so the texture's histogram and contrast are
        // the photo's and the crop keeps its structure (its ranks, hence its spectrum's shape).
        const EmpiricalDistribution crop_distribution(plane);
        if (!(crop_distribution.stddev() > 0)) continue;
        if (histograms[c].enabled()) {
            // The map's input: standard-normal by the crop's own ranks (Heitz–Neyret's T).
            gaussianize(plane, crop_distribution);
            const double scale = 1 / crop_distribution.stddev();
            for (float& v : plane) v = float(v * scale);
        } else {
            // A Gaussian channel: the whole channel's mean and σ.
            const EmpiricalDistribution whole(channels[c]);
            const double scale = whole.stddev() / crop_distribution.stddev();
            for (float& v : plane) v = float(whole.mean() + (v - crop_distribution.mean()) * scale);
        }
    }
    TilingParameters parameters;
    parameters.output = TilingOutput::colour;
    parameters.exemplar = quantise(planes, crop_width, crop_height, bits);
    return parameters;
}

}  // namespace

TilingParameters fit_tiling_exemplar(const std::array<std::vector<float>, 3>& channels, int width, int height,
                                     const std::array<HistogramMap, 3>& histograms, int max_side, int bits,
                                     const TilingCandidateScore& score, const TilingCandidateChoice& choose)
{
    if (max_side != automatic_exemplar_side && (max_side < min_tiling_exemplar_side || max_side > max_tiling_exemplar_side))
        throw Error("tiling exemplar size must be in [" + std::to_string(min_tiling_exemplar_side) + ", " +
                    std::to_string(max_tiling_exemplar_side) + "], got " + std::to_string(max_side));
    if (bits != 8 && bits != 16) throw Error("tiling exemplar bits must be 8 or 16, got " + std::to_string(bits));
    const std::array<int, 2> sides = crop_sides(width, height, max_side == automatic_exemplar_side ? automatic_exemplar_sides[0] : max_side);
    if (sides[0] < min_tiling_exemplar_side || sides[1] < min_tiling_exemplar_side)
        throw Error("image is " + std::to_string(width) + "x" + std::to_string(height) + ", too small for a tiling exemplar (at least " +
                    std::to_string(min_tiling_exemplar_side) + "x" + std::to_string(min_tiling_exemplar_side) + ")");
    if (max_side != automatic_exemplar_side) {
        const SizedCrop crop{sides[0], sides[1],
                             representative_crop(channels, width, height, sides[0], sides[1], photo_statistics(channels, width, height))};
        return exemplar_of(channels, width, height, histograms, crop, bits);
    }
    // Automatic: each candidate fitted, rendered and scored as `--model auto` scores models,
    // and kept by its rule (the smaller exemplar where the renders are as faithful).
    const std::vector<SizedCrop> candidates = automatic_exemplar_candidates(channels, width, height);
    if (candidates.size() == 1) return exemplar_of(channels, width, height, histograms, candidates[0], bits);
    std::vector<TilingParameters> fitted;
    std::vector<ModelScore> scores;
    for (const SizedCrop& candidate : candidates) {
        fitted.push_back(exemplar_of(channels, width, height, histograms, candidate, bits));
        scores.push_back(score(ModelParameters(fitted.back()), exemplar_scoring_side));
    }
    return fitted[choose(scores)];
}

}  // namespace stochtex
