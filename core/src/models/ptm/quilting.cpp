#include "models/ptm/quilting.h"

#include "models/ptm/patch_search.h"
#include "numerics/random.h"

#include <stochtex/error.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace stochtex {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

int wrap(int i, int n) { return ((i % n) + n) % n; }

/// Which sides of a block overlap texels that are already placed.
struct Sides {
    bool left = false, top = false, right = false, bottom = false;
    bool any() const { return left || top || right || bottom; }
};

/// The overlap strips of the present sides as disjoint rectangles: top and bottom strips span
/// the block, left and right strips the rows between them.
std::vector<BlockRect> overlap_rects(const Sides& sides, int block, int overlap)
{
    std::vector<BlockRect> rects;
    if (sides.top) rects.push_back({0, 0, block, overlap});
    if (sides.bottom) rects.push_back({0, block - overlap, block, overlap});
    const int first_row = sides.top ? overlap : 0, end_row = sides.bottom ? block - overlap : block;
    if (end_row > first_row) {
        if (sides.left) rects.push_back({0, first_row, overlap, end_row - first_row});
        if (sides.right) rects.push_back({block - overlap, first_row, overlap, end_row - first_row});
    }
    return rects;
}

/// The output being built: wraps around when tileable.
struct Canvas {
    Image image;
    std::vector<char> placed;
    bool periodic = false;
    std::size_t index(int x, int y) const
    {
        if (periodic) x = wrap(x, image.width), y = wrap(y, image.height);
        return std::size_t(y) * image.width + x;
    }
    float* texel(int x, int y) { return &image.pixels[index(x, y) * image.channels]; }
};

/// Minimum-error path down a strip of `length` rows and `breadth` columns (error[row][col]),
/// moving at most one column per row; returns the column of each row.
std::vector<int> minimum_cut(const std::vector<double>& error, int length, int breadth)
{
    std::vector<double> cost(error);
    for (int r = 1; r < length; ++r)
        for (int c = 0; c < breadth; ++c) {
            double best = cost[std::size_t(r - 1) * breadth + c];
            if (c > 0) best = std::min(best, cost[std::size_t(r - 1) * breadth + c - 1]);
            if (c + 1 < breadth) best = std::min(best, cost[std::size_t(r - 1) * breadth + c + 1]);
            cost[std::size_t(r) * breadth + c] += best;
        }
    std::vector<int> path(length);
    const double* last = &cost[std::size_t(length - 1) * breadth];
    path[length - 1] = int(std::min_element(last, last + breadth) - last);
    for (int r = length - 2; r >= 0; --r) {
        const int previous = path[r + 1];
        int chosen = previous;
        for (int c : {previous - 1, previous + 1})
            if (c >= 0 && c < breadth && cost[std::size_t(r) * breadth + c] < cost[std::size_t(r) * breadth + chosen]) chosen = c;
        path[r] = chosen;
    }
    return path;
}

/// Per texel of the block, the weight of the new block (1 outside the overlaps): 0 or 1 for a
/// cut, a ramp for a blend; the product over the sides.
std::vector<double> block_weights(const Sides& sides, int block, int overlap, SeamMode seam,
                                  const std::vector<double>& error /* block² squared differences */)
{
    std::vector<double> weight(std::size_t(block) * block, 1.0);
    // Each side seen as a strip along the block edge: `along` runs the edge's length, `across`
    // the overlap, from the placed side (0) towards the new block (overlap − 1).
    struct Side {
        bool present;
        bool vertical;  // strip along a vertical edge (left/right)
        bool far;       // right or bottom edge
    };
    const Side all[] = {{sides.left, true, false}, {sides.right, true, true}, {sides.top, false, false}, {sides.bottom, false, true}};
    for (const Side& side : all) {
        if (!side.present) continue;
        auto texel = [&](int along, int across) {
            const int offset = side.far ? block - 1 - across : across;
            return side.vertical ? std::size_t(along) * block + offset : std::size_t(offset) * block + along;
        };
        if (seam == SeamMode::blend) {
            for (int along = 0; along < block; ++along)
                for (int across = 0; across < overlap; ++across) weight[texel(along, across)] *= (across + 1.0) / (overlap + 1);
            continue;
        }
        std::vector<double> strip(std::size_t(block) * overlap);
        for (int along = 0; along < block; ++along)
            for (int across = 0; across < overlap; ++across) strip[std::size_t(along) * overlap + across] = error[texel(along, across)];
        const std::vector<int> cut = minimum_cut(strip, block, overlap);
        for (int along = 0; along < block; ++along)
            for (int across = 0; across < cut[along]; ++across) weight[texel(along, across)] = 0;
    }
    return weight;
}

}  // namespace

Image quilt(const Image& exemplar, int matched, const PtmSynthesisOptions& options, PtmSynthesisReport* report,
            const ProgressCallback& progress)
{
    const auto start = Clock::now();
    const int block = options.block, overlap = options.overlap;
    if (block < 4) throw Error("synthesis: the block must be at least 4 texels, got " + std::to_string(block));
    if (overlap < 1 || 2 * overlap > block)
        throw Error("synthesis: the overlap must be in [1, block/2] = [1, " + std::to_string(block / 2) + "], got " +
                    std::to_string(overlap));
    if (block > exemplar.width || block > exemplar.height)
        throw Error("synthesis: the " + std::to_string(block) + "-texel block does not fit the " +
                    std::to_string(exemplar.width) + "x" + std::to_string(exemplar.height) + " exemplar");
    if (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384)
        throw Error("synthesis: the output size must be 1 … 16384 texels a side");
    if (!(options.relative_tolerance >= 0) || !(options.absolute_tolerance >= 0))
        throw Error("synthesis: tolerances must not be negative");
    const int step = block - overlap;
    // Tileable: whole steps fill the period, and the last blocks overlap the first ones.
    auto block_count = [&](int size) {
        return options.tileable ? std::max(2, (size + step - 1) / step) : std::max(1, (size - overlap + step - 1) / step);
    };
    const int columns = block_count(options.width), rows = block_count(options.height);
    Canvas canvas;
    canvas.periodic = options.tileable;
    canvas.image = options.tileable ? Image(columns * step, rows * step, exemplar.channels)
                                    : Image(columns * step + overlap, rows * step + overlap, exemplar.channels);
    canvas.placed.assign(canvas.image.pixel_count(), 0);

    // σ²: the exemplar's per-texel variance over the compared channels, the scale of the
    // absolute tolerance.
    double variance = 0;
    for (int c = 0; c < matched; ++c) {
        double sum = 0, squares = 0;
        for (std::size_t i = 0; i < exemplar.pixel_count(); ++i) {
            const double v = exemplar.pixels[i * exemplar.channels + c];
            sum += v, squares += v * v;
        }
        const double mean = sum / double(exemplar.pixel_count());
        variance += std::max(0.0, squares / double(exemplar.pixel_count()) - mean * mean);
    }

    const PatchSearch search(exemplar, block, matched);
    SearchStatistics statistics;
    double search_seconds = 0;
    SplitMix64 random(mix_seed(options.seed, 0x9f7a));
    std::vector<double> error(std::size_t(block) * block);
    for (int by = 0; by < rows; ++by) {
        if (progress) progress(double(by) / rows, "synthesis");
        for (int bx = 0; bx < columns; ++bx) {
            const int ox = bx * step, oy = by * step;
            Sides sides;
            sides.left = bx > 0;
            sides.top = by > 0;
            sides.right = options.tileable && bx == columns - 1;
            sides.bottom = options.tileable && by == rows - 1;
            int sx = 0, sy = 0;
            if (!sides.any()) {
                sx = int(random.uniform() * (exemplar.width - block + 1));
                sy = int(random.uniform() * (exemplar.height - block + 1));
            } else {
                Neighbourhood neighbourhood;
                neighbourhood.rects = overlap_rects(sides, block, overlap);
                for (const BlockRect& r : neighbourhood.rects)
                    for (int j = 0; j < r.height; ++j)
                        for (int i = 0; i < r.width; ++i) {
                            if (!canvas.placed[canvas.index(ox + r.x + i, oy + r.y + j)])
                                throw Error("synthesis: internal error: a neighbourhood texel is not placed yet");
                            const float* texel = canvas.texel(ox + r.x + i, oy + r.y + j);
                            neighbourhood.values.insert(neighbourhood.values.end(), texel, texel + matched);
                        }
                Acceptance acceptance;
                acceptance.relative = 1 + options.relative_tolerance;
                acceptance.absolute = double(neighbourhood.texel_count()) * options.absolute_tolerance *
                                      options.absolute_tolerance * variance;
                const auto search_start = Clock::now();
                const std::vector<SearchCandidate> candidates =
                    options.brute_force ? search.exhaustive(neighbourhood, acceptance, statistics)
                                        : search.projection(neighbourhood, acceptance, statistics);
                search_seconds += seconds_since(search_start);
                const SearchCandidate& chosen =
                    candidates[std::min(candidates.size() - 1, std::size_t(random.uniform() * candidates.size()))];
                sx = chosen.x, sy = chosen.y;
            }
            // Squared ψ differences between the placed texels and the new block (cut costs).
            for (int j = 0; j < block; ++j)
                for (int i = 0; i < block; ++i) {
                    const float* placed = canvas.texel(ox + i, oy + j);
                    double sum = 0;
                    for (int c = 0; c < matched; ++c) {
                        const double d = double(placed[c]) - exemplar.at(sx + i, sy + j, c);
                        sum += d * d;
                    }
                    error[std::size_t(j) * block + i] = sum;
                }
            const std::vector<double> weight = block_weights(sides, block, overlap, options.seam, error);
            for (int j = 0; j < block; ++j)
                for (int i = 0; i < block; ++i) {
                    const std::size_t index = canvas.index(ox + i, oy + j);
                    float* out = canvas.texel(ox + i, oy + j);
                    const double w = canvas.placed[index] ? weight[std::size_t(j) * block + i] : 1.0;
                    for (int c = 0; c < exemplar.channels; ++c)
                        out[c] = float(w * exemplar.at(sx + i, sy + j, c) + (1 - w) * out[c]);
                    canvas.placed[index] = 1;
                }
        }
    }
    if (progress) progress(1.0, "synthesis");

    Image output = canvas.image;
    if (!options.tileable && (output.width != options.width || output.height != options.height)) {
        output = Image(options.width, options.height, exemplar.channels);
        for (int y = 0; y < options.height; ++y)
            std::copy_n(canvas.texel(0, y), std::size_t(options.width) * exemplar.channels,
                        &output.pixels[std::size_t(y) * options.width * exemplar.channels]);
    }
    if (report) {
        report->width = output.width;
        report->height = output.height;
        report->blocks = rows * columns;
        report->positions = statistics.positions;
        report->surviving = statistics.surviving;
        report->exact_distances = statistics.exact_distances;
        report->search_seconds = search_seconds;
        report->total_seconds = seconds_since(start);
    }
    return output;
}

}  // namespace stochtex
