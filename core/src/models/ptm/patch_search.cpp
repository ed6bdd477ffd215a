#include "models/ptm/patch_search.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {

/// One refinement step of the bounds: a cell of the previous level cut in two halves a and b.
/// Adding the halves' indicators to the kernels adds exactly the energy of the difference
/// kernel, (Δ_a·n_b − Δ_b·n_a)² / (n_a n_b (n_a + n_b)) with Δ_b = Δ_parent − Δ_a: one window
/// sum per split instead of two, and the previous level's work is reused.
struct Split {
    std::size_t parent;  // the cell of the previous level
    BlockRect half;      // the half a (b is the rest of the parent)
    double area_a, area_b;
};

/// Level 0 is the neighbourhood's rectangles; each next level cuts every cell of more than one
/// texel in half across its longer side. Cells of level k are, in order, the halves a and b of
/// each split (and unsplit cells carried over as splits with an empty half b).
std::vector<std::vector<Split>> nested_splits(const std::vector<BlockRect>& rects, int levels)
{
    std::vector<std::vector<Split>> splits(levels);
    std::vector<BlockRect> cells = rects;
    for (int level = 1; level < levels; ++level) {
        std::vector<BlockRect> next;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            const BlockRect cell = cells[i];
            BlockRect a = cell, b = cell;
            if (cell.width >= cell.height && cell.width > 1) {
                a.width = cell.width / 2;
                b.x += a.width, b.width -= a.width;
            } else if (cell.height > 1) {
                a.height = cell.height / 2;
                b.y += a.height, b.height -= a.height;
            } else {
                b.width = b.height = 0;  // a single texel: nothing to cut
            }
            splits[level].push_back({i, a, double(a.width) * a.height, double(b.width) * b.height});
            next.push_back(a);
            if (b.width > 0) next.push_back(b);
        }
        cells = std::move(next);
    }
    return splits;
}

}  // namespace

std::size_t Neighbourhood::texel_count() const
{
    std::size_t count = 0;
    for (const BlockRect& r : rects) count += std::size_t(r.width) * r.height;
    return count;
}

PatchSearch::PatchSearch(const Image& source, int block, int channels)
    : source_(source), block_(block), channels_(channels)
{
    if (channels < 1 || channels > source.channels) throw Error("patch search: bad channel count");
    if (block < 2 || block > source.width || block > source.height)
        throw Error("patch search: blocks of " + std::to_string(block) + " texels do not fit the " +
                    std::to_string(source.width) + "x" + std::to_string(source.height) + " exemplar");
    positions_x_ = source.width - block + 1;
    positions_y_ = source.height - block + 1;
    const int w = source.width, h = source.height;
    table_.assign(std::size_t(w + 1) * (h + 1) * channels, 0.0);
    double largest = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) {
                auto at = [&](int i, int j) -> double& { return table_[(std::size_t(j) * (w + 1) + i) * channels + c]; };
                at(x + 1, y + 1) = source.at(x, y, c) + at(x, y + 1) + at(x + 1, y) - at(x, y);
                largest = std::max(largest, std::fabs(at(x + 1, y + 1)));
            }
    // Each table entry and the four-term window sum carry a relative error of a few ε per
    // addition along the way; this bounds it generously (the guard on rejections).
    rounding_ = 64.0 * (w + h) * std::numeric_limits<double>::epsilon() * std::max(largest, 1.0);
}

void PatchSearch::window_sums(int x, int y, int w, int h, double* sums) const
{
    const std::size_t stride = (std::size_t(source_.width) + 1) * channels_;
    const double* top = &table_[std::size_t(y) * stride + std::size_t(x) * channels_];
    const double* bottom = top + std::size_t(h) * stride;
    const std::size_t right = std::size_t(w) * channels_;
    for (int c = 0; c < channels_; ++c) sums[c] = bottom[right + c] - bottom[c] - top[right + c] + top[c];
}

double PatchSearch::distance(const Neighbourhood& neighbourhood, int x, int y, double stop) const
{
    double sum = 0;
    const float* query = neighbourhood.values.data();
    for (const BlockRect& r : neighbourhood.rects)
        for (int j = 0; j < r.height; ++j) {
            const float* row = &source_.pixels[(std::size_t(y + r.y + j) * source_.width + x + r.x) * source_.channels];
            for (int i = 0; i < r.width; ++i, query += channels_) {
                const float* texel = row + std::size_t(i) * source_.channels;
                for (int c = 0; c < channels_; ++c) {
                    const double difference = double(query[c]) - texel[c];
                    sum += difference * difference;
                }
            }
            if (sum > stop) return sum;  // a row at a time: the check costs little
        }
    return sum;
}

std::vector<SearchCandidate> PatchSearch::exhaustive(const Neighbourhood& neighbourhood, const Acceptance& acceptance,
                                                     SearchStatistics& statistics) const
{
    std::vector<SearchCandidate> all;
    all.reserve(std::size_t(positions_x_) * positions_y_);
    double best = std::numeric_limits<double>::infinity();
    for (int y = 0; y < positions_y_; ++y)
        for (int x = 0; x < positions_x_; ++x) {
            all.push_back({x, y, distance(neighbourhood, x, y)});
            best = std::min(best, all.back().distance);
        }
    statistics.positions += all.size();
    statistics.exact_distances += all.size();
    const double threshold = acceptance.threshold(best);
    std::vector<SearchCandidate> accepted;
    for (const SearchCandidate& candidate : all)
        if (candidate.distance <= threshold) accepted.push_back(candidate);
    return accepted;
}

std::vector<SearchCandidate> PatchSearch::projection(const Neighbourhood& neighbourhood, const Acceptance& acceptance,
                                                     SearchStatistics& statistics) const
{
    const std::vector<std::vector<Split>> splits = nested_splits(neighbourhood.rects, bound_levels);
    // The query's sums over the same rectangles (its projections U·N, times √n), from its values:
    // a neighbourhood laid out as a block-sized image of its rectangles' texels.
    std::vector<double> query_image(std::size_t(block_) * block_ * channels_, 0.0);
    {
        const float* value = neighbourhood.values.data();
        for (const BlockRect& r : neighbourhood.rects)
            for (int j = 0; j < r.height; ++j)
                for (int i = 0; i < r.width; ++i, value += channels_)
                    std::copy(value, value + channels_, &query_image[(std::size_t(r.y + j) * block_ + r.x + i) * channels_]);
    }
    auto query_sums = [&](const BlockRect& r) {
        std::vector<double> sums(channels_, 0.0);
        for (int j = 0; j < r.height; ++j)
            for (int i = 0; i < r.width; ++i)
                for (int c = 0; c < channels_; ++c) sums[c] += query_image[(std::size_t(r.y + j) * block_ + r.x + i) * channels_ + c];
        return sums;
    };
    std::vector<double> rect_query, half_query;  // per rectangle / per split, times channels
    for (const BlockRect& r : neighbourhood.rects)
        for (double sum : query_sums(r)) rect_query.push_back(sum);
    std::vector<std::size_t> split_offset{0};  // first split of each level in half_query
    for (int level = 1; level < bound_levels; ++level) {
        for (const Split& split : splits[level])
            for (double sum : query_sums(split.half)) half_query.push_back(sum);
        split_offset.push_back(half_query.size() / channels_);
    }

    // Per candidate: the differences Δ = S_N − S_W of the current level's cells, and the bound.
    std::vector<double> delta, next_delta, window(channels_);
    std::size_t largest_level = neighbourhood.rects.size();
    for (const auto& level : splits) largest_level = std::max(largest_level, 2 * level.size());
    delta.reserve(largest_level * channels_);
    next_delta.reserve(largest_level * channels_);
    auto first_bound = [&](int x, int y) {
        delta.clear();
        double sum = 0;
        for (std::size_t r = 0; r < neighbourhood.rects.size(); ++r) {
            const BlockRect& rect = neighbourhood.rects[r];
            window_sums(x + rect.x, y + rect.y, rect.width, rect.height, window.data());
            const double area = double(rect.width) * rect.height;
            for (int c = 0; c < channels_; ++c) {
                const double d = rect_query[r * channels_ + c] - window[c];
                delta.push_back(d);
                sum += d * d / area;
            }
        }
        return sum;
    };
    auto refine = [&](int level, int x, int y) {  // the bound's growth from level − 1 to level
        next_delta.clear();
        double growth = 0;
        const double* query = &half_query[split_offset[level - 1] * channels_];
        for (const Split& split : splits[level]) {
            const double* parent = &delta[split.parent * channels_];
            if (split.area_b == 0) {
                next_delta.insert(next_delta.end(), parent, parent + channels_);
                query += channels_;
                continue;
            }
            window_sums(x + split.half.x, y + split.half.y, split.half.width, split.half.height, window.data());
            const std::size_t b = next_delta.size() + channels_;
            next_delta.resize(next_delta.size() + 2 * channels_);
            for (int c = 0; c < channels_; ++c) {
                const double da = query[c] - window[c], db = parent[c] - da;
                next_delta[b - channels_ + c] = da;
                next_delta[b + c] = db;
                const double kernel = da * split.area_b - db * split.area_a;
                growth += kernel * kernel / (split.area_a * split.area_b * (split.area_a + split.area_b));
            }
            query += channels_;
        }
        std::swap(delta, next_delta);
        return growth;
    };
    // Rounding can lift a bound slightly above a distance it equals (e.g. 0 for an exact
    // continuation); reject only beyond that margin, so no true candidate is ever lost.
    const double terms = double(largest_level) * channels_ * bound_levels;
    auto rejects = [&](double bound_value, double threshold) {
        const double margin = terms * (4 * rounding_ * std::sqrt(std::max(threshold, 0.0)) + 4 * rounding_ * rounding_);
        return bound_value > threshold + margin;
    };

    const std::size_t count = std::size_t(positions_x_) * positions_y_;
    statistics.positions += count;
    if (statistics.surviving.size() < std::size_t(bound_levels)) statistics.surviving.resize(bound_levels, 0);
    std::vector<double> first_bounds(count);
    for (int y = 0; y < positions_y_; ++y)
        for (int x = 0; x < positions_x_; ++x) first_bounds[std::size_t(y) * positions_x_ + x] = first_bound(x, y);

    // A good threshold early rejects most candidates at the first level: start from the exact
    // distances of the few candidates with the lowest first bounds.
    constexpr std::size_t seeds = 8;
    std::vector<std::size_t> order(count);
    for (std::size_t i = 0; i < count; ++i) order[i] = i;
    const std::size_t seed_count = std::min(seeds, count);
    std::nth_element(order.begin(), order.begin() + (seed_count - 1), order.end(),
                     [&](std::size_t a, std::size_t b) { return first_bounds[a] < first_bounds[b]; });
    double best = std::numeric_limits<double>::infinity();
    std::vector<char> evaluated(count, 0);
    std::vector<double> distances(count, 0.0);
    for (std::size_t s = 0; s < seed_count; ++s) {
        const std::size_t i = order[s];
        distances[i] = distance(neighbourhood, int(i % positions_x_), int(i / positions_x_));
        evaluated[i] = 1;
        best = std::min(best, distances[i]);
        ++statistics.exact_distances;
    }

    std::vector<SearchCandidate> kept;  // d ≤ the threshold at the time: a superset of the answer
    for (std::size_t i = 0; i < count; ++i) {
        const int x = int(i % positions_x_), y = int(i / positions_x_);
        double threshold = acceptance.threshold(best);
        if (!evaluated[i]) {
            bool rejected = rejects(first_bounds[i], threshold);
            if (!rejected) {
                ++statistics.surviving[0];
                double bound = first_bound(x, y);  // again, to hold its differences
                for (int level = 1; level < bound_levels && !rejected; ++level) {
                    bound += refine(level, x, y);
                    rejected = rejects(bound, threshold);
                    if (!rejected) ++statistics.surviving[level];
                }
            }
            if (rejected) continue;
            distances[i] = distance(neighbourhood, x, y, threshold);
            ++statistics.exact_distances;
            if (distances[i] > threshold) continue;
            best = std::min(best, distances[i]);
            threshold = acceptance.threshold(best);
        }
        if (distances[i] <= threshold) kept.push_back({x, y, distances[i]});
    }
    const double threshold = acceptance.threshold(best);
    std::vector<SearchCandidate> accepted;
    for (const SearchCandidate& candidate : kept)
        if (candidate.distance <= threshold) accepted.push_back(candidate);
    return accepted;
}

}  // namespace stochtex
