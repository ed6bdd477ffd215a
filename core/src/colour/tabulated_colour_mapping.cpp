#include "colour/tabulated_colour_mapping.h"

#include "colour/gaussian.h"
#include "colour/tabulated_colour_mapping_row.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

TabulatedColourMapping::TabulatedColourMapping(const TextureDescription& description, const std::array<double, 3>& sigma_m)
    : exact_(description, sigma_m)
{
    for (int c = 0; c < 3; ++c) {
        const HistogramMap& map = description.histograms[c];
        knot_range_[c] = map.enabled() ? std::array<double, 2>{map.z.front(), map.z.back()} : std::array<double, 2>{0, 0};
    }
}

void TabulatedColourMapping::build() const
{
    const GaussHermite& rule = GaussHermite::standard_normal();
    double reach = 0;
    for (double node : rule.node) reach = std::max(reach, std::abs(node));
    for (int c = 0; c < 3; ++c) {
        if (!exact_.has_map(c)) continue;
        Table& table = tables_[c];
        // Columns cover the knots ± the rule's reach at σ_max (beyond, every node clamps).
        const double margin = reach * sigma_max + step;
        table.z0 = std::floor((knot_range_[c][0] - margin) / step) * step;
        table.columns = int(std::ceil((knot_range_[c][1] + margin - table.z0) / step)) + 1;
        table.rows = int(std::lround(sigma_max / step)) + 1;
        table.values.resize(std::size_t(table.columns) * table.rows);
        tbb::parallel_for(0, table.rows, [&](int row) {
            for (int column = 0; column < table.columns; ++column)
                table.values[std::size_t(row) * table.columns + column] =
                    float(exact_.map_channel(c, table.z0 + column * step, row * step));
        });
    }
}

double TabulatedColourMapping::map_channel(int c, double z, double dropped_sigma) const
{
    if (!exact_.has_map(c) || dropped_sigma < 1e-4 || !(dropped_sigma < sigma_max)) return exact_.map_channel(c, z, dropped_sigma);
    ensure_built();
    return interpolate(tables_[c], z, dropped_sigma);
}

Rgb TabulatedColourMapping::to_rgb(const std::array<double, 3>& z, const std::array<double, 3>& dropped_sigma) const
{
    std::array<double, 3> y;
    for (int c = 0; c < 3; ++c) y[c] = map_channel(c, z[c], dropped_sigma[c]);
    exact_.condition(z[0], dropped_sigma[0], y);
    return exact_.combine(y);
}

void TabulatedColourMapping::to_rgb(const std::array<const double*, 3>& z, const std::array<const double*, 3>& dropped_sigma,
                                    std::size_t count, const RgbOutput& out, std::size_t first) const
{
    ensure_built();
    constexpr std::size_t block = 64;  // items per pass: the mapped values stay on the stack
    double y[3][block];
    for (std::size_t start = 0; start < count; start += block) {
        const std::size_t n = std::min(block, count - start);
        for (int c = 0; c < 3; ++c) {
            const double* zc = z[c] + start;
            const double* sc = dropped_sigma[c] + start;
            if (!exact_.has_map(c)) {
                for (std::size_t i = 0; i < n; ++i) y[c][i] = exact_.map_channel(c, zc[i], sc[i]);
                continue;
            }
            const Table& t = tables_[c];
            tabulated_row::interpolate({t.values.data(), t.z0, 1 / step, t.columns, t.rows}, zc, sc, n, y[c]);
            // map_channel()'s cases outside the table, item by item.
            for (std::size_t i = 0; i < n; ++i)
                if (sc[i] < 1e-4 || !(sc[i] < sigma_max)) y[c][i] = exact_.map_channel(c, zc[i], sc[i]);
        }
        if (exact_.conditions())
            for (std::size_t i = 0; i < n; ++i) {
                std::array<double, 3> yi{y[0][i], y[1][i], y[2][i]};
                exact_.condition(z[0][start + i], dropped_sigma[0][start + i], yi);
                y[1][i] = yi[1], y[2][i] = yi[2];
            }
        exact_.combine({y[0], y[1], y[2]}, out, first + start, n);
    }
}

}  // namespace stochtex
