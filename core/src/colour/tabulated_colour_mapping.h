// ColourMapping with its filtered histogram maps tabulated: F_c(z, σ) = E[f_c(z + σ Z)] on a
// grid over (z, σ), looked up bilinearly — 4 reads instead of the Gauss–Hermite rule's 12
// monotone-cubic evaluations per channel (the colour step of a filtered tiling pixel).
//
// The grid: σ in [0, σ_max] and z over the knots widened by the rule's reach at σ_max, both in
// steps of 1/32 (σ_M units); beyond the z range F is constant (every node clamps to an end
// value), so z is clamped. Outside the table — σ < 1e-4 (the unfiltered map) or σ > σ_max —
// the exact map_channel() is used. Interpolation error (tests/raster_paths_test.cpp, in σ of
// the mapped channel): ≤ 1e-3 σ of the rule's values, ≤ 1.5e-2 σ next to the map's end knots,
// where f has a kink that the rule's 12 nodes cross one by one — there the rule itself is up
// to ~0.2 σ from the true E[f(z + σZ)], and the table is never further from it than the rule
// (docs/architecture.md, "Evaluation").
//
// Built on first use (a few milliseconds, in parallel), so reading a .stex costs nothing.
#pragma once

#include "colour/colour_mapping.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace stochtex {

class TabulatedColourMapping {
public:
    static constexpr double step = 1.0 / 32;  ///< grid spacing in z and σ (σ_M units)
    static constexpr double sigma_max = 2.0;  ///< larger dropped σ use the exact rule

    TabulatedColourMapping(const TextureDescription& description, const std::array<double, 3>& sigma_m);

    /// ColourMapping::to_rgb with the tabulated channel maps.
    Rgb to_rgb(const std::array<double, 3>& z, const std::array<double, 3>& dropped_sigma) const;
    /// to_rgb() of `count` items (item i: z[c][i], dropped_sigma[c][i]) into out items first + i,
    /// bit-identical to to_rgb() item by item: the table is resolved once per row, not per value
    /// (the colour step of a tiling raster row).
    void to_rgb(const std::array<const double*, 3>& z, const std::array<const double*, 3>& dropped_sigma, std::size_t count,
                const RgbOutput& out, std::size_t first) const;
    /// Channel c's tabulated value (map_channel() outside the table).
    double map_channel(int c, double z, double dropped_sigma) const;
    const ColourMapping& exact() const { return exact_; }

private:
    struct Table {
        double z0 = 0;
        int columns = 0, rows = 0;
        std::vector<float> values;  // [row · columns + column]: F(z0 + column·step, row·step)
    };
    void build() const;
    /// Builds the tables once (before the first lookup that reads them).
    void ensure_built() const
    {
        if (!ready_.load(std::memory_order_acquire)) {
            std::call_once(built_, [this] { build(); });
            ready_.store(true, std::memory_order_release);
        }
    }
    /// map_channel()'s table lookup (dropped_sigma in [1e-4, σ_max)).
    static double interpolate(const Table& table, double z, double dropped_sigma)
    {
        const double s = dropped_sigma * (1 / step);
        const int row = std::min(int(s), table.rows - 2);
        const double fs = s - row;
        const double q = std::clamp((z - table.z0) * (1 / step), 0.0, double(table.columns - 1));
        const int column = std::min(int(q), table.columns - 2);
        const double fq = q - column;
        const float* low = &table.values[std::size_t(row) * table.columns + column];
        const float* high = low + table.columns;
        return (low[0] * (1 - fq) + low[1] * fq) * (1 - fs) + (high[0] * (1 - fq) + high[1] * fq) * fs;
    }

    ColourMapping exact_;
    std::array<double, 2> knot_range_[3];
    mutable std::once_flag built_;
    mutable std::atomic<bool> ready_{false};  // built_ done: skips call_once's library call per lookup
    mutable std::array<Table, 3> tables_;  // empty for a Gaussian channel
};

}  // namespace stochtex
