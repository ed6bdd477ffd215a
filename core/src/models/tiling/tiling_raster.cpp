#include "models/tiling/tiling_raster.h"

#include "numerics/exact_rounding.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace stochtex {

namespace {

constexpr int record = PackedMomentPyramid::record;

using tiling_raster::chunk;  // pixels per pass of the address stage and the lookups

}  // namespace

PackedPairs packed_pairs(int channels)
{
    PackedPairs p{};
    auto fill = [&](auto pairs) {
        p.count = pairs.count;
        for (int k = 0; k < pairs.count; ++k) p.first[std::size_t(k)] = pairs.first[k], p.second[std::size_t(k)] = pairs.second[k];
    };
    switch (channels) {
    case 1: fill(tiling_raster::RecordPairs<1>{}); break;
    case 2: fill(tiling_raster::RecordPairs<2>{}); break;
    default: fill(tiling_raster::RecordPairs<3>{}); break;
    }
    return p;
}

PackedMomentPyramid::PackedMomentPyramid(const MomentPyramid& pyramid) : channels_(pyramid.channels())
{
    const PackedPairs pairs = packed_pairs(channels_);
    used_ = channels_ + pairs.count;
    const Moments global = pyramid.global();
    std::vector<std::size_t> offsets;
    std::size_t total = 0;
    for (int l = 0; l < pyramid.level_count(); ++l) {
        const int width = std::max(1, pyramid.width() >> l), height = std::max(1, pyramid.height() >> l);
        offsets.push_back(total);
        total += std::size_t(width + 1) * height * record;
    }
    data_.assign(total, 0.0f);
    for (int l = 0; l < pyramid.level_count(); ++l) {
        const int width = std::max(1, pyramid.width() >> l), height = std::max(1, pyramid.height() >> l);
        float* base = data_.data() + offsets[std::size_t(l)];
        const std::size_t row = std::size_t(width) + 1;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x <= width; ++x) {
                const Moments m = pyramid.texel(l, x, y);  // x = width wraps to the first texel
                float* out = base + (std::size_t(y) * row + std::size_t(x)) * record;
                for (int c = 0; c < channels_; ++c) out[c] = float(m.mean[std::size_t(c)] - global.mean[std::size_t(c)]);
                for (int p = 0; p < pairs.count; ++p) out[channels_ + p] = float(m.moment(pairs.first[std::size_t(p)], pairs.second[std::size_t(p)]));
            }
        levels_.push_back({base, row, width - 1, height - 1, double(width) / pyramid.width(), double(height) / pyramid.height()});
    }
}

TilingRaster::Workspace::Workspace(int bits_i, int bits_j)
    : slots_(std::size_t(1) << (bits_i + bits_j), Slot{INT64_MIN, INT64_MIN, 0, 0}),
      mask_i_((std::uint64_t(1) << bits_i) - 1), mask_j_((std::uint64_t(1) << bits_j) - 1), shift_j_(bits_i)
{
}

void TilingRaster::Workspace::invalidate()
{
    for (Slot& slot : slots_) slot.i = slot.j = INT64_MIN;
}

TilingRaster::TilingRaster(const TilingNoise& noise, const PackedMomentPyramid& pyramid)
    : noise_(noise), pyramid_(pyramid), pairs_(packed_pairs(pyramid.channels()))
{
}

namespace {
tiling_raster::LevelGeometry geometry(const PackedMomentPyramid::Level& l)
{
    return {l.scale_x, l.scale_y, double(l.mask_x + 1), double(l.mask_y + 1), std::int32_t(l.row)};
}
}  // namespace

TilingRaster::Plan TilingRaster::plan(const Footprint2D& footprint_px, const FootprintSampling& sampling) const
{
    Plan plan;
    plan.taps = noise_.plan(footprint_px, sampling);
    plan.lower = &pyramid_.level(plan.taps.choice.lower);
    plan.upper = plan.taps.choice.t > 0 ? &pyramid_.level(plan.taps.choice.lower + 1) : nullptr;
    plan.lower_geometry = geometry(*plan.lower);
    if (plan.upper) plan.upper_geometry = geometry(*plan.upper);
    plan.t = float(plan.taps.choice.t);
    const int taps = std::min(plan.taps.na * plan.taps.nb, TapPlan::max_planned_taps);
    for (int k = 0; k < taps; ++k) {
        plan.ratio[std::size_t(k)] = float(plan.taps.ratio[std::size_t(k)]);
        plan.scatter[std::size_t(k)] = float(plan.taps.scatter[std::size_t(k)]);
    }
    plan.weight = float(plan.taps.weight);
    plan.inverse_total = float(1 / plan.taps.total);
    return plan;
}

inline const double* TilingRaster::translation(std::int64_t i, std::int64_t j, Workspace& workspace) const
{
    Workspace::Slot& slot = workspace.slots_[std::size_t((std::uint64_t(i) & workspace.mask_i_) |
                                                         ((std::uint64_t(j) & workspace.mask_j_) << workspace.shift_j_))];
    if (slot.i != i || slot.j != j) fill(slot, i, j);
    return &slot.dx;
}

void TilingRaster::fill(Workspace::Slot& slot, std::int64_t i, std::int64_t j) const
{
    const std::array<double, 2> t = tile_position(noise_.grid().vertex(i, j), 0, 0, noise_.width(), noise_.height());
    slot = {i, j, t[0], t[1]};
}

namespace {

/// The blend contrast on a planned tap row: its three tiles' weights (w and w²) sharpened as
/// TilingGrid::blend sharpens them (sharpen_blend_weights). Outside the vectorised address stage,
/// which the default contrast keeps bit for bit; w is already B / ‖B‖, and the normalisation
/// makes B^γ and w^γ the same weights.
void sharpen_weights(const tiling_raster::TileReads& reads, std::size_t count, double contrast)
{
    using tiling_raster::chunk;
    float* fields[3];
    for (std::size_t k = 0; k < 3; ++k) fields[k] = reads.fractions + k * tiling_raster::fraction_fields * chunk;
    for (std::size_t i = 0; i < count; ++i) {
        std::array<double, 3> w;
        for (std::size_t k = 0; k < 3; ++k) w[k] = fields[k][tiling_raster::weight * chunk + i];
        sharpen_blend_weights(w, contrast);
        for (std::size_t k = 0; k < 3; ++k) {
            const float v = float(w[k]);
            fields[k][tiling_raster::weight * chunk + i] = v;
            fields[k][tiling_raster::weight_squared * chunk + i] = v * v;
        }
    }
}

}  // namespace

template <int Channels>
void TilingRaster::estimate_chunk(const double* x, std::size_t count, double y, const Plan& plan, Workspace& ws, float* out) const
{
    const TapPlan& taps = plan.taps;
    const int n_taps = taps.na * taps.nb;
    // Positions much farther apart than the triangles (a strongly minified row) would make the
    // translation tables span many unused vertex columns: split the run until they do not (a
    // position's values do not depend on the run it is in).
    if (count > 1 && std::abs(x[count - 1] - x[0]) * noise_.grid().inverse_edges()[0] > double(2 * count + 16)) {
        const std::size_t half = count / 2;
        estimate_chunk<Channels>(x, half, y, plan, ws, out);
        estimate_chunk<Channels>(x + half, count - half, y, plan, ws, out + half * record);
        return;
    }
    const std::size_t lanes = (count + tiling_raster::max_lanes - 1) / tiling_raster::max_lanes * tiling_raster::max_lanes;
    // Address-stage buffers (tiling_raster::OffsetField, FractionField): per tap and tile a
    // run of `chunk` per field, the first `lanes` used.
    const std::size_t runs = std::size_t(n_taps) * 3;
    ws.x_.resize(lanes);
    ws.offsets_.resize(runs * tiling_raster::offset_fields * chunk);
    ws.fractions_.resize(runs * tiling_raster::fraction_fields * chunk);
    const TilingGrid& grid = noise_.grid();
    static const double two_over_sqrt3 = 2 / std::sqrt(3.0);
    std::copy(x, x + count, ws.x_.begin());
    std::fill(ws.x_.begin() + std::ptrdiff_t(count), ws.x_.end(), x[count - 1]);  // padded with the last position
    tiling_raster::TapRow row{};  // what is the same for every tap, then each tap's
    row.x = ws.x_.data(), row.n = lanes, row.inverse_edge_x = grid.inverse_edges()[0];
    row.lower = plan.lower_geometry, row.upper = plan.upper_geometry, row.has_upper = plan.upper != nullptr;
    for (int j = 0, k = 0; j < taps.nb; ++j)
        for (int i = 0; i < taps.na; ++i, ++k) {
            // This tap of every position: x + offset on the line py (TilingGrid::triangle's row).
            const double a = taps.along_a[std::size_t(i)][0], b = taps.along_b[std::size_t(j)][0];
            const double py = y + taps.along_a[std::size_t(i)][1] + taps.along_b[std::size_t(j)][1];
            row.a = a, row.b = b, row.y = py;
            row.sy = (py * grid.inverse_edges()[1]) * two_over_sqrt3;
            const double cy = floor_exact(row.sy);
            row.fy = row.sy - cy;
            // The vertex columns the positions' triangles use (x is monotone: the ends bound them).
            const double c_first = floor_exact((x[0] + a + b) * row.inverse_edge_x - 0.5 * row.sy);
            const double c_last = floor_exact((x[count - 1] + a + b) * row.inverse_edge_x - 0.5 * row.sy);
            const double c_min = std::min(c_first, c_last), c_max = std::max(c_first, c_last);
            const std::size_t columns = std::size_t(c_max - c_min) + 2, entries = tiling_raster::vertex_entries(columns);
            // The vertex tables: entry r · columns + c for vertex (c_min + c, cy + r); x then y.
            ws.rows_.resize(2 * entries);
            double* rows = ws.rows_.data();
            std::fill(rows + 2 * columns, rows + entries, 0.0);  // the padding: read, never looked up
            std::fill(rows + entries + 2 * columns, rows + 2 * entries, 0.0);
            const std::int64_t vj = std::int64_t(cy), vi = std::int64_t(c_min);
            for (int r = 0; r < 2; ++r)
                for (std::size_t c = 0; c < columns; ++c) {
                    const double* t = translation(vi + std::int64_t(c), vj + r, ws);
                    rows[std::size_t(r) * columns + c] = t[0];
                    rows[entries + std::size_t(r) * columns + c] = t[1];
                }
            ws.vertex_fy_.resize(2 * entries);
            ws.vertex_rows_.resize(4 * entries);
            row.i_min = c_min, row.columns = columns;
            row.translation_x = rows, row.translation_y = rows + entries;
            row.vertex_fy = ws.vertex_fy_.data(), row.vertex_rows = ws.vertex_rows_.data();
            const tiling_raster::TileReads reads{ws.offsets_.data() + std::size_t(k) * 3 * tiling_raster::offset_fields * chunk,
                                                 ws.fractions_.data() + std::size_t(k) * 3 * tiling_raster::fraction_fields * chunk};
            tiling_raster::plan_tap_row(row, reads);
            if (grid.contrast() != 1) sharpen_weights(reads, lanes, grid.contrast());
        }
    // The lookups and the mixture, position by position.
    tiling_raster::TapSums sums{};
    sums.lower = plan.lower->data, sums.upper = plan.upper ? plan.upper->data : nullptr, sums.t = plan.t;
    sums.taps = n_taps, sums.channels = Channels;
    sums.offsets = ws.offsets_.data(), sums.fractions = ws.fractions_.data();
    sums.ratio = plan.ratio.data(), sums.scatter = plan.scatter.data(), sums.weight = plan.weight, sums.inverse_total = plan.inverse_total;
    tiling_raster::accumulate_taps(sums, count, out);
}

void TilingRaster::estimate_row(const double* x, std::size_t count, double y, const Plan& plan, Workspace& workspace, float* out) const
{
    for (std::size_t first = 0; first < count; first += chunk) {
        const std::size_t n = std::min(chunk, count - first);
        switch (pyramid_.channels()) {
        case 1: estimate_chunk<1>(x + first, n, y, plan, workspace, out + first * record); break;
        case 2: estimate_chunk<2>(x + first, n, y, plan, workspace, out + first * record); break;
        default: estimate_chunk<3>(x + first, n, y, plan, workspace, out + first * record); break;
        }
    }
}

Moments TilingRaster::unpack(const float* packed) const
{
    const Moments& global = noise_.global();
    Moments m;
    m.channels = global.channels;
    m.mean = global.mean;
    for (int c = 0; c < m.channels; ++c) m.mean[std::size_t(c)] += double(packed[c]);
    for (int p = 0; p < pairs_.count; ++p) {
        const double v = packed[m.channels + p];
        m.moment(pairs_.first[std::size_t(p)], pairs_.second[std::size_t(p)]) = v;
        m.moment(pairs_.second[std::size_t(p)], pairs_.first[std::size_t(p)]) = v;
    }
    return m;
}

}  // namespace stochtex
