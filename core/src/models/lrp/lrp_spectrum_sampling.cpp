#include "models/lrp/lrp_spectrum_sampling.h"

#include "models/lrp/lrp_parameters.h"
#include "models/lrp/lrp_window.h"
#include "numerics/random.h"

#include <stochtex/error.h>
#include <stochtex/models/lrp_parameters.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace stochtex {

namespace {

/// Energy left out with the weakest bins (see the header).
constexpr double left_out_tail = 1e-3;
/// Share of the scaled window's energy the erosion radius holds (paper §4.3, "empirical").
constexpr double erosion_energy = 0.75;
/// k-means runs on at most this many bins (a random subset); all bins are assigned at the end.
constexpr std::size_t kmeans_sample_limit = 20000;
constexpr int kmeans_iterations = 30;

struct Point {
    double x, y;
    double weight = 1;
};

double distance2(const Point& a, const Point& b) { return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y); }

std::size_t nearest(const std::vector<Point>& centres, const Point& p)
{
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::max();
    for (std::size_t c = 0; c < centres.size(); ++c) {
        const double d = distance2(centres[c], p);
        if (d < best_d) best_d = d, best = c;
    }
    return best;
}

/// Lloyd's k-means with k-means++ seeding (the paper's "random seeding", made robust); k ≤ the
/// number of points. Returns each point's cluster.
std::vector<std::size_t> kmeans(const std::vector<Point>& points, std::size_t k, SplitMix64& rng)
{
    std::vector<Point> sample = points;
    if (sample.size() > kmeans_sample_limit) {
        for (std::size_t i = 0; i < kmeans_sample_limit; ++i)
            std::swap(sample[i], sample[i + std::size_t(rng.uniform() * double(sample.size() - i))]);
        sample.resize(kmeans_sample_limit);
    }
    std::vector<Point> centres{sample[std::size_t(rng.uniform() * double(sample.size()))]};
    std::vector<double> d2(sample.size());
    while (centres.size() < k) {
        double sum = 0;
        for (std::size_t i = 0; i < sample.size(); ++i)
            sum += d2[i] = sample[i].weight * distance2(sample[i], centres[nearest(centres, sample[i])]);
        if (!(sum > 0)) break;  // fewer distinct points than k
        double pick = rng.uniform() * sum;
        std::size_t chosen = 0;
        while (chosen + 1 < sample.size() && (pick -= d2[chosen]) > 0) ++chosen;
        centres.push_back(sample[chosen]);
    }
    std::vector<std::size_t> assignment(sample.size(), 0);
    for (int iteration = 0; iteration < kmeans_iterations; ++iteration) {
        bool changed = iteration == 0;
        for (std::size_t i = 0; i < sample.size(); ++i) {
            const std::size_t c = nearest(centres, sample[i]);
            changed |= c != assignment[i];
            assignment[i] = c;
        }
        if (!changed) break;
        std::vector<Point> sum(centres.size(), Point{0, 0, 0});
        for (std::size_t i = 0; i < sample.size(); ++i) {
            Point& s = sum[assignment[i]];
            s.x += sample[i].weight * sample[i].x, s.y += sample[i].weight * sample[i].y, s.weight += sample[i].weight;
        }
        for (std::size_t c = 0; c < centres.size(); ++c)
            if (sum[c].weight > 0) centres[c] = {sum[c].x / sum[c].weight, sum[c].y / sum[c].weight};
    }
    std::vector<std::size_t> result(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) result[i] = nearest(centres, points[i]);
    return result;
}

/// Squared Euclidean distance transform in 1D (Felzenszwalb–Huttenlocher): f holds 0 outside the
/// set and +∞ inside; on return, each entry's squared distance to the nearest outside sample.
void distance_transform_1d(std::vector<double>& f)
{
    const std::size_t n = f.size();
    std::vector<double> result(n), z(n + 1);
    std::vector<std::size_t> v(n);
    std::size_t k = 0;
    std::size_t first = 0;
    while (first < n && !std::isfinite(f[first])) ++first;
    if (first == n) return;  // nothing outside on this line: leave +∞
    v[0] = first;
    z[0] = -std::numeric_limits<double>::infinity();
    z[1] = std::numeric_limits<double>::infinity();
    for (std::size_t q = first + 1; q < n; ++q) {
        if (!std::isfinite(f[q])) continue;
        double s;
        while (true) {
            const double p = double(v[k]);
            s = ((f[q] + double(q) * double(q)) - (f[v[k]] + p * p)) / (2.0 * (double(q) - p));
            if (s <= z[k] && k > 0) {
                --k;
                continue;
            }
            break;
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = std::numeric_limits<double>::infinity();
    }
    k = 0;
    for (std::size_t q = 0; q < n; ++q) {
        while (z[k + 1] < double(q)) ++k;
        const double d = double(q) - double(v[k]);
        result[q] = d * d + f[v[k]];
    }
    f = result;
}

/// Distance of every bin of `mask` (a size² grid) to the nearest bin outside it; the grid's
/// surroundings count as outside (nothing lies beyond Nyquist).
std::vector<double> distance_to_outside(const std::vector<char>& mask, int size)
{
    const int padded = size + 2;
    std::vector<double> grid(std::size_t(padded) * padded, 0.0);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            if (mask[std::size_t(y) * size + x]) grid[std::size_t(y + 1) * padded + x + 1] = std::numeric_limits<double>::infinity();
    std::vector<double> line(padded);
    for (int y = 0; y < padded; ++y) {
        for (int x = 0; x < padded; ++x) line[x] = grid[std::size_t(y) * padded + x];
        distance_transform_1d(line);
        for (int x = 0; x < padded; ++x) grid[std::size_t(y) * padded + x] = line[x];
    }
    for (int x = 0; x < padded; ++x) {
        for (int y = 0; y < padded; ++y) line[y] = grid[std::size_t(y) * padded + x];
        distance_transform_1d(line);
        for (int y = 0; y < padded; ++y) grid[std::size_t(y) * padded + x] = line[y];
    }
    std::vector<double> distance(std::size_t(size) * size, 0.0);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) distance[std::size_t(y) * size + x] = std::sqrt(grid[std::size_t(y + 1) * padded + x + 1]);
    return distance;
}

/// The paper's erosion, "modified so that strata smaller than δ are not completely swept out":
/// per 8-connected component, keep the bins at distance ≥ min(δ, the component's deepest bin).
std::vector<char> erode(const std::vector<char>& mask, int size, double delta)
{
    const std::vector<double> distance = distance_to_outside(mask, size);
    std::vector<char> kept(mask.size(), 0);
    std::vector<int> component(mask.size(), -1);
    std::vector<std::size_t> members, stack;
    int next_component = 0;
    for (std::size_t start = 0; start < mask.size(); ++start) {
        if (!mask[start] || component[start] >= 0) continue;
        members.clear();
        stack.assign(1, start);
        component[start] = next_component;
        double deepest = 0;
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            members.push_back(i);
            deepest = std::max(deepest, distance[i]);
            const int x = int(i % std::size_t(size)), y = int(i / std::size_t(size));
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
                    const std::size_t j = std::size_t(ny) * size + nx;
                    if (mask[j] && component[j] < 0) component[j] = next_component, stack.push_back(j);
                }
        }
        ++next_component;
        const double threshold = std::min(delta, deepest);
        for (std::size_t i : members) kept[i] = distance[i] >= threshold;
    }
    return kept;
}

/// Energy share below the frequency a stratum's window must resolve (LrpSamplingOptions::resolve).
constexpr double resolved_quantile = 0.1;
/// The lowest octave's stratum: bins nearer DC than this (LrpSamplingOptions::resolve).
constexpr double lowest_octave_bins = 2;

/// A half-plane representative bin (a bin whose index is not below its mirror's).
struct Bin {
    int kx, ky;
    double power;  // density of the partition spectrum
    double multiplicity;
};

/// Quantile of a stratum's energy (from below) and of its bins (from above) between which its
/// radial extent is measured (LrpSamplingOptions::octave_span).
constexpr double extent_quantile = 0.1;

/// The octave [T/4, T/2) of bins: the top one (floor(log2 |k|) of its bins).
int top_octave(int size) { return int(std::log2(size / 4.0)); }

double log2_radius(const Bin& bin) { return std::log2(std::hypot(bin.kx, bin.ky)); }

/// The octave of a bin, floor(log2 |k|), the corners past Nyquist with the top one.
int octave_of(const Bin& bin, int size) { return std::clamp(int(std::floor(log2_radius(bin))), 0, top_octave(size)); }

/// log2 |k| where a stratum's energy begins (its extent_quantile of energy from below) and
/// where its bins end (their 1 − extent_quantile by count): the cosines (power-weighted k-means)
/// sit near the first, the window (sized by the bin count) must cover up to the second.
std::pair<double, double> octave_extent(const std::vector<const Bin*>& stratum)
{
    std::vector<std::pair<double, double>> radius;  // log2 |k|, energy
    double energy = 0;
    for (const Bin* bin : stratum) {
        radius.emplace_back(log2_radius(*bin), bin->power * bin->multiplicity);
        energy += radius.back().second;
    }
    std::sort(radius.begin(), radius.end());
    double below = 0, low = radius.front().first;
    for (const auto& [r, e] : radius)
        if ((below += e) >= extent_quantile * energy) {
            low = r;
            break;
        }
    const double high = radius[std::min(radius.size() - 1, std::size_t((1 - extent_quantile) * double(radius.size())))].first;
    return {low, high};
}

/// LrpSamplingOptions::octave_span: each stratum whose extent exceeds `span` octaves and whose
/// bins reach the top two octaves (|k| ≥ T/8: small windows, whose spread covers most of the
/// plane) becomes one stratum per octave of |k| it touches (lowest first, in its place), the
/// weakest strata first. Within `max_count` strata: where the pieces would exceed it, the lowest
/// pieces merge (the top octaves, which the split is for, stay apart). (Splitting the wide
/// low-frequency strata too, 4–22 bins on concrete, left a piece at 0.43 of its energy target.)
void split_wide_strata(std::vector<std::vector<const Bin*>>& members, int size, double span, int max_count)
{
    int count = int(members.size());
    const double top_two_octaves = std::log2(size / 8.0);
    for (std::size_t s = members.size(); s-- > 0;) {
        const auto [low, high] = octave_extent(members[s]);
        if (!(high - low > span && high >= top_two_octaves)) continue;
        std::vector<std::vector<const Bin*>> pieces(std::size_t(top_octave(size)) + 1);
        for (const Bin* bin : members[s]) pieces[std::size_t(octave_of(*bin, size))].push_back(bin);
        pieces.erase(std::remove_if(pieces.begin(), pieces.end(), [](const auto& p) { return p.empty(); }), pieces.end());
        while (pieces.size() > 1 && count + int(pieces.size()) - 1 > max_count) {
            pieces[1].insert(pieces[1].end(), pieces[0].begin(), pieces[0].end());
            pieces.erase(pieces.begin());
        }
        if (pieces.size() < 2) continue;  // no room: the stratum stays as it was (its bins in density order)
        count += int(pieces.size()) - 1;
        members.erase(members.begin() + std::ptrdiff_t(s));
        members.insert(members.begin() + std::ptrdiff_t(s), std::make_move_iterator(pieces.begin()),
                       std::make_move_iterator(pieces.end()));
    }
}

double window_spacing(int size, int terms, std::size_t bins, double low_frequency, const LrpSamplingOptions& options)
{
    if (options.spacing > 0) return options.spacing;
    const double coverage = size * std::sqrt(options.coverage * terms / double(bins));
    const double resolving = options.resolve > 0 && low_frequency > 0 ? options.resolve / low_frequency : 0;
    return std::clamp(std::max(coverage, resolving), 1.0, double(size));
}

/// The spectrum's half-plane representative bins (a bin whose index is not below its mirror's)
/// with power, strongest first, without the weakest tail (left_out_tail of the energy).
struct RankedBins {
    std::vector<Bin> bins;
    double total = 0;        ///< the energy of every bin, the tail's included
    double kept_energy = 0;  ///< that of `bins`
};

RankedBins ranked_bins(const DiscreteSpectrum& partition, const std::vector<char>& excluded)
{
    const int size = partition.size;
    RankedBins ranked;
    std::vector<Bin>& bins = ranked.bins;
    double& total = ranked.total;
    for (int ky = -size / 2; ky < size / 2; ++ky)
        for (int kx = -size / 2; kx < size / 2; ++kx) {
            if (kx == 0 && ky == 0) continue;
            const std::size_t i = partition.index(kx, ky), m = partition.index(mirror_bin(kx, size), mirror_bin(ky, size));
            if (i < m || (!excluded.empty() && excluded[i])) continue;
            const double multiplicity = i == m ? 1 : 2;
            const double power = partition.power[i];
            if (!(power > 0)) continue;
            bins.push_back({kx, ky, power, multiplicity});
            total += power * multiplicity;
        }
    if (!(total > 0)) return ranked;
    std::sort(bins.begin(), bins.end(), [](const Bin& a, const Bin& b) { return a.power > b.power; });
    double tail = 0;
    while (!bins.empty() && tail + bins.back().power * bins.back().multiplicity <= left_out_tail * total) {
        tail += bins.back().power * bins.back().multiplicity;
        bins.pop_back();
    }
    ranked.kept_energy = total - tail;
    return ranked;
}

/// Equal-energy strata over the sorted densities (§4.2): a bin goes where the middle of its
/// energy falls, so a peak holding more than 1/L of the energy empties the next stratum. With
/// `low_apart`, the lowest octave's bins keep their place in the split (the L strata keep their
/// boundaries) but go to their own stratum (not returned). Empty strata are left out.
std::vector<std::vector<const Bin*>> equal_energy_strata(const std::vector<Bin>& bins, double kept_energy,
                                                         int equal_strata, bool low_apart)
{
    std::vector<std::vector<const Bin*>> members(static_cast<std::size_t>(equal_strata));
    double cumulative = 0;
    for (const Bin& bin : bins) {
        const double energy = bin.power * bin.multiplicity;
        const int s = std::min(equal_strata - 1, int(equal_strata * (cumulative + 0.5 * energy) / kept_energy));
        if (!(low_apart && std::hypot(bin.kx, bin.ky) < lowest_octave_bins)) members[std::size_t(s)].push_back(&bin);
        cumulative += energy;
    }
    members.erase(std::remove_if(members.begin(), members.end(), [](const auto& m) { return m.empty(); }), members.end());
    return members;
}

/// A stratum's low frequency: the energy-weighted resolved_quantile of |f| (cycles per pixel).
double low_frequency_of(const std::vector<const Bin*>& stratum, int size)
{
    std::vector<std::pair<double, double>> radius;  // |f|, energy
    double energy = 0;
    for (const Bin* bin : stratum) {
        radius.emplace_back(std::hypot(bin->kx, bin->ky) / size, bin->power * bin->multiplicity);
        energy += radius.back().second;
    }
    std::sort(radius.begin(), radius.end());
    double below = 0;
    for (const auto& [f, e] : radius)
        if ((below += e) >= resolved_quantile * energy) return f;
    return 0;
}

/// At most `count` bins of a substratum standing for it: all of them if there are no more,
/// else the bins nearest the centres of a small k-means (spread out over the substratum).
std::vector<Point> representatives_of(const std::vector<Point>& substratum, int count, SplitMix64& rng)
{
    if (substratum.size() <= std::size_t(count)) return substratum;
    std::vector<Point> chosen;
    const std::vector<std::size_t> part = kmeans(substratum, std::size_t(count), rng);
    for (std::size_t r = 0; r < std::size_t(count); ++r) {
        Point centre{0, 0, 0};
        for (std::size_t i = 0; i < substratum.size(); ++i)
            if (part[i] == r) {
                const Point& p = substratum[i];
                centre.x += p.weight * p.x, centre.y += p.weight * p.y, centre.weight += p.weight;
            }
        if (!(centre.weight > 0)) continue;
        centre = {centre.x / centre.weight, centre.y / centre.weight};
        chosen.push_back(substratum[nearest(substratum, centre)]);
    }
    return chosen;
}

/// Stratum s (its bins `stratum`, sampled by `terms` cosines; `lowest`: the lowest octave's)
/// as stored: its σ per channel, window spacing and substrata of representative bins. Labels the
/// stratum's bins (and mirrors) `label` in `labels`.
LrpStratum sample_stratum(const std::vector<const Bin*>& stratum, int s, int terms, bool lowest,
                          const DiscreteSpectrum& partition, const std::array<const DiscreteSpectrum*, 3>& channels,
                          const LrpSamplingOptions& options, int label, std::vector<int>& labels)
{
    const int size = partition.size;
    LrpStratum out;
    std::vector<char> mask(partition.power.size(), 0);
    for (const Bin* bin : stratum) {
        const std::size_t i = partition.index(bin->kx, bin->ky);
        mask[i] = mask[partition.index(mirror_bin(bin->kx, size), mirror_bin(bin->ky, size))] = 1;
        labels[i] = labels[partition.index(mirror_bin(bin->kx, size), mirror_bin(bin->ky, size))] = label;
        for (int c = 0; c < 3; ++c)
            if (channels[c]) out.sigma[c] += channels[c]->power[i] * bin->multiplicity;
    }
    for (double& sigma : out.sigma) sigma = std::sqrt(sigma);
    const double low_frequency = lowest ? low_frequency_of(stratum, size) : 0;

    // Shrink (§4.3) so that the windows' spectra stay inside the stratum, then k-means.
    const double erosion_radius = lrp_window_spread_1d(erosion_energy);  // cycles per spacing
    const double spacing = window_spacing(size, terms, stratum.size(), low_frequency, options);
    const std::vector<char> kept = erode(mask, size, erosion_radius * size / spacing);
    std::vector<Point> points;
    for (const Bin* bin : stratum)
        if (kept[partition.index(bin->kx, bin->ky)])
            // The row −T/2 is the aliased +T/2: placed there it neighbours its half-plane.
            points.push_back({double(bin->kx), double(bin->ky == -size / 2 ? size / 2 : bin->ky),
                              options.power_weighted ? bin->power : 1.0});
    terms = std::min<int>(terms, int(points.size()));
    out.spacing = window_spacing(size, terms, stratum.size(), low_frequency, options);
    SplitMix64 rng(mix_seed(options.seed, std::uint64_t(s), 0x1a2b));
    const std::vector<std::size_t> cluster = kmeans(points, std::size_t(terms), rng);
    std::vector<std::vector<Point>> substrata(static_cast<std::size_t>(terms));
    for (std::size_t i = 0; i < points.size(); ++i) substrata[cluster[i]].push_back(points[i]);
    for (std::vector<Point>& substratum : substrata) {
        if (substratum.empty()) continue;
        std::vector<int> flat;
        for (const Point& p : representatives_of(substratum, options.representatives, rng)) {
            // Fold the row +T/2 back onto −T/2, its stored name.
            flat.push_back(int(p.x));
            flat.push_back(int(p.y) == size / 2 ? -size / 2 : int(p.y));
        }
        out.substrata.push_back(std::move(flat));
    }
    return out;
}

}  // namespace

StratifiedSpectrum stratify_spectrum(const DiscreteSpectrum& partition,
                                     const std::array<const DiscreteSpectrum*, 3>& channels,
                                     const std::vector<char>& excluded, const LrpSamplingOptions& options)
{
    const int size = partition.size;
    if (options.strata < 1 || options.cosines < 1 || options.representatives < 1)
        throw Error("stratify_spectrum: strata, cosines and representatives must be positive");
    for (const DiscreteSpectrum* channel : channels)
        if (channel && channel->size != size) throw Error("stratify_spectrum: channel spectra differ in size");

    const RankedBins ranked = ranked_bins(partition, excluded);
    StratifiedSpectrum result;
    result.label.assign(partition.power.size(), -1);
    if (!(ranked.total > 0)) return result;
    const std::vector<Bin>& bins = ranked.bins;

    // The lowest octave (|k| < 2 bins) as a stratum of its own before the L (LrpSamplingOptions::
    // resolve): its window is as wide as those wavelengths need, its bins one cosine each. (Taking
    // it out of the L instead measured worse: 1.73/1.48/0.44 → 2.40/1.78/0.65 dB on concrete, dirt
    // and gravel, LrpByExample.SpectrumAndStrataEnergyOnThreePhotos; splitting only the rest into
    // L: 1.92/1.46/0.78.)
    std::vector<const Bin*> low;
    if (options.resolve > 0)
        for (const Bin& bin : bins)
            if (std::hypot(bin.kx, bin.ky) < lowest_octave_bins) low.push_back(&bin);
    const int low_terms = std::min<int>(int(low.size()), options.cosines / 2);
    // The file holds max_lrp_strata strata in all: with the lowest octave's, at most one fewer
    // of equal energy (L = 16 gives 15 and the lowest octave's).
    const int equal_strata = std::min(options.strata, max_lrp_strata - (low_terms > 0 ? 1 : 0));
    std::vector<std::vector<const Bin*>> members = equal_energy_strata(bins, ranked.kept_energy, equal_strata, low_terms > 0);
    // Equal energy puts almost no stratum where a steep spectrum holds little energy over many
    // octaves: the weakest stratum then spans them all with one tiny window whose nearly white
    // spectrum the leakage solve cannot shape (sand dunes: 10–30 dB weak over the upper half of
    // the frequencies, docs/models/lrp.md). Such strata are split by octave.
    if (options.octave_span > 0)
        split_wide_strata(members, size, options.octave_span, max_lrp_strata - (low_terms > 0 ? 1 : 0));
    if (low_terms > 0) members.insert(members.begin(), std::move(low));

    // The cosines shared out: the lowest octave's first, the rest as evenly as they go.
    const int count = int(members.size());
    const int shared_count = count - (low_terms > 0 ? 1 : 0), shared_cosines = options.cosines - low_terms;
    for (int s = 0; s < count; ++s) {
        const bool lowest = low_terms > 0 && s == 0;
        const int k = s - (low_terms > 0 ? 1 : 0);
        const int terms = lowest ? low_terms : shared_cosines / shared_count + (k < shared_cosines % shared_count ? 1 : 0);
        if (terms < 1) continue;  // more strata than cosines: the weakest go unsampled
        result.strata.push_back(sample_stratum(members[std::size_t(s)], s, terms, lowest, partition, channels, options,
                                               int(result.strata.size()), result.label));
    }
    return result;
}

}  // namespace stochtex
