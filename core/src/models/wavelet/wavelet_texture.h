// Multiresolution wavelet noise by example (paper 000): the texture.
//
//   m_c(x) = Σ_j w_cj N(x · ppu · 2^-j + o_cj)        (eq. 1; j = 0 is the finest band)
// per decorrelated channel c, with per-band, per-channel random offsets o (shared across
// channels only in the rgb-shared colour mode), then ColourMapping. Solid textures use 3D
// bands with weights scaled by sqrt(σ_N²(2D) / σ_N²(3D)) so every band keeps the variance the
// photo gave it; a planar slice of a 3D band has the 3D band's variance (stationarity).
//
// Periodic form (make_periodic_texture): each band's 2D lattice is stretched so that a whole
// number of tiles of a fitting period covers the requested period (see band_lattice()), and
// normalised by its tile's σ_N so the band keeps its weight's variance.
#pragma once

#include "colour/colour_mapping.h"
#include "models/wavelet/wavelet_noise.h"

#include <stochtex/texture.h>

#include <vector>

namespace stochtex {

/// σ_M of one channel (eq. 2): sqrt(σ_N² Σ_j w_j²), with this build's measured 2D σ_N².
double wavelet_channel_sigma(const std::vector<double>& band_weights);

class WaveletTexture final : public Texture {
public:
    explicit WaveletTexture(const TextureDescription& description);
    /// The periodic form: eval() repeats every period[0] in u and period[1] in v.
    WaveletTexture(const TextureDescription& description, const Vec2& period);

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override;
    using Texture::eval_region;
    void eval_region(const RasterRegion& region, const RgbOutput& out) const override;
    Rgb eval_solid(const SurfacePoint& point) const override;
    void eval_solid_region(const SolidRegion& region, const RgbOutput& out) const override;
    void eval_solid_points(const SurfaceBatch& points, const RgbOutput& out) const override;
    Rgb mean() const override { return colour_.mean(); }

    /// σ_M of each channel (eq. 2) with this build's measured σ_N².
    const std::array<double, 3>& sigma_m() const { return sigma_m_; }
    /// Band j of channel c as synthesised (weight, tile, lattice scales and offsets) and the
    /// solid gain: for exporters that re-implement synthesis elsewhere (wavelet_shader_data.h).
    const auto& band(int c, std::size_t j) const { return bands_[c][j]; }
    /// sqrt(σ_N²(2D) / σ_N²(3D)); builds the 3D tile on first use (2D textures never need it).
    static double solid_gain();

private:
    struct Band {
        double weight;
        const WaveletNoise2D* tile;  // the 2D noise (shared tile unless periodic)
        double gain;                 // σ_N(shared) / σ_N(tile): same variance for any tile
        double scale[2];             // 2D: texture units → lattice units, per axis (ppu · 2^-j)
        double solid_scale;          // 3D: texture units → lattice units (ppu · 2^-j)
        double offset[3];            // lattice units
    };
    WaveletTexture(const TextureDescription& description, const Vec2* period);
    static constexpr std::size_t max_bands = 24;  // validate() bounds the band count
    /// What a footprint keeps of each band (the same for every channel), and the standard
    /// deviation it removes from each channel in units of σ_M (for the histogram filter).
    struct Fades {
        float band[max_bands];
        std::array<double, 3> dropped_sigma;
    };
    Fades fades(double footprint_px) const;
    /// kept[c] = Σ_j fade_j w_cj N_j: to RGB through the colour mapping.
    Rgb finish(const std::array<double, 3>& kept, double gain, const Fades& fades) const;
    /// The per-thread scratch of the raster paths: `pixels` zeroed sums per channel, and room for
    /// `columns` column splines and `span` combined lattice columns.
    struct RasterScratch;
    static RasterScratch& raster_scratch(std::size_t pixels, std::size_t columns, std::size_t span);
    /// band_sum(c, band, fade · weight) for every band of every channel the fades keep, in
    /// synthesize()'s order (the raster paths).
    template <class BandSum>
    void for_each_kept_band(const Fades& fades, const BandSum& band_sum) const;
    template <class BandNoise>
    Rgb synthesize(double footprint_px, double gain, const BandNoise& band_noise) const;

    std::array<std::vector<Band>, 3> bands_;
    /// Bands [0, present_bands_) are synthesised; coarser ones do not fit a periodic texture's
    /// period and count as filtered away.
    std::size_t present_bands_ = 0;
    std::array<double, 3> sigma_m_{};
    ColourMapping colour_;
};

}  // namespace stochtex
