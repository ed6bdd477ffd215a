// Multiresolution wavelet noise by example (paper 000): the texture.
//
//   m_c(x) = Σ_j w_cj N(x · ppu · 2^-j + o_cj)        (eq. 1; j = 0 is the finest band)
// per decorrelated channel c, with per-band, per-channel random offsets o (shared across
// channels only in the rgb-shared colour mode), then ColourMapping. Solid textures use 3D
// bands with weights scaled by sqrt(σ_N²(2D) / σ_N²(3D)) so every band keeps the variance the
// photo gave it; a planar slice of a 3D band has the 3D band's variance (stationarity).
#pragma once

#include "colour_mapping.h"

#include <stochtex/texture.h>

#include <vector>

namespace stochtex {

/// σ_M of one channel (eq. 2): sqrt(σ_N² Σ_j w_j²), with this build's measured 2D σ_N².
double wavelet_channel_sigma(const std::vector<double>& band_weights);

class WaveletTexture final : public Texture {
public:
    explicit WaveletTexture(const TextureDescription& description);

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override;
    Rgb eval_solid(const SurfacePoint& point) const override;
    Rgb mean() const override { return colour_.mean(); }

    /// σ_M of each channel (eq. 2) with this build's measured σ_N².
    const std::array<double, 3>& sigma_m() const { return sigma_m_; }

private:
    struct Band {
        double weight;
        double frequency_scale;  // ppu · 2^-j: texture units → lattice units
        double offset[3];        // lattice units
    };
    template <class BandNoise>
    Rgb synthesize(double footprint_px, double gain, const BandNoise& band_noise) const;

    std::array<std::vector<Band>, 3> bands_;
    std::array<double, 3> sigma_m_{};
    double solid_gain_ = 1;
    ColourMapping colour_;
};

}  // namespace stochtex
