// From decorrelated Gaussian channels to RGB: histogram maps, then the colour basis and mean
// (paper 000, §7 synthesis steps 2–4). Shared by every model whose channels are Gaussian noises.
//
// Filtering meets a non-linear histogram map here. A model that removes detail under
// minification passes the standard deviation (in units of σ_M) of what it removed; the map
// then returns E[f(z + σ_d Z)], Z ~ N(0, 1) (Gauss–Hermite), the correctly filtered value, so
// minification converges to the texture's true mean rather than to the median f(0).
//
// With joint colour (chroma_given_brightness.h) the chroma channels' values then become
// location(z_0) + scale(z_0) · y_c, filtered the same way.
#pragma once

#include "colour/chroma_given_brightness.h"
#include "colour/histogram_map.h"

#include <stochtex/texture.h>

#include <array>

namespace stochtex {

class ColourMapping {
public:
    /// sigma_m: each decorrelated channel's standard deviation (σ_M, eq. 2) before mapping.
    ColourMapping(const TextureDescription& description, const std::array<double, 3>& sigma_m);

    /// z: each channel's kept noise in units of σ_M; dropped_sigma: what filtering removed,
    /// in the same units (0 when nothing was removed).
    Rgb to_rgb(const std::array<double, 3>& z, const std::array<double, 3>& dropped_sigma) const;

    /// to_rgb() for `count` items sharing one dropped_sigma (a raster region): item i has
    /// z[c] = gain · kept[c][i] / σ_M[c] and goes to out item first + i. Bit-identical to
    /// to_rgb() (colour_mapping_batch.cpp: vectorised, the same operations in the same order).
    void to_rgb(const std::array<const double*, 3>& kept, double gain, const std::array<double, 3>& dropped_sigma,
                const RgbOutput& out, std::size_t first, std::size_t count) const;
    /// The same for items each with their own dropped σ (scattered points, each its own
    /// footprint): item i's is dropped_sigma[c][i]. Bit-identical to to_rgb() too.
    void to_rgb(const std::array<const double*, 3>& kept, double gain,
                const std::array<const double*, 3>& dropped_sigma, const RgbOutput& out, std::size_t first,
                std::size_t count) const;

    /// The expected value of the texture (everything filtered away).
    Rgb mean() const { return to_rgb({0, 0, 0}, {1, 1, 1}); }

    /// Channel c's filtered value E[f_c(z + σ_d Z)] (to_rgb's first step).
    double map_channel(int c, double z, double dropped_sigma) const;
    /// Whether channel c has a histogram map (else it stays Gaussian: map_channel is linear).
    bool has_map(int c) const { return !maps_[c].empty(); }
    /// to_rgb's second step: the chroma channels given brightness z0 (filtered by dropped0), when
    /// the description has joint colour; y unchanged otherwise.
    void condition(double z0, double dropped0, std::array<double, 3>& y) const
    {
        if (chroma_.enabled()) chroma_.apply(z0, dropped0, y[1], y[2]);
    }
    /// Whether condition() changes anything (the description has joint colour).
    bool conditions() const { return chroma_.enabled(); }
    /// to_rgb's last step: the colour of mapped channel values y.
    Rgb combine(const std::array<double, 3>& y) const;
    /// combine() of `count` items (item i: y[c][i]) into out items first + i, vectorised
    /// (colour_mapping_batch.cpp), bit-identical to combine() item by item.
    void combine(const std::array<const double*, 3>& y, const RgbOutput& out, std::size_t first, std::size_t count) const;

private:
    /// The batch to_rgb()s' common body, in blocks: z from kept, `map_block(c, z, y, start, n)`
    /// maps channel c's block (to_rgb's first step, with the caller's σ), `sigma0(i)` is the
    /// brightness channel's dropped σ of item i (the conditioning's), then the colour basis.
    template <class MapBlock, class Sigma0>
    void to_rgb_blocks(const std::array<const double*, 3>& kept, double gain, const MapBlock& map_block,
                       const Sigma0& sigma0, const RgbOutput& out, std::size_t first, std::size_t count) const;

    std::array<double, 3> sigma_m_;
    std::array<MonotoneCubic, 3> maps_;  // empty: channel stays Gaussian
    ChromaConditioning chroma_;          // disabled: independent channels
    std::array<double, 3> mean_;
    std::array<std::array<double, 3>, 3> basis_;
};

}  // namespace stochtex
