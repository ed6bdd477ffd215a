// The ptm model as a texture: the coefficient maps, MIP-mapped, lit by the description's light.
//
// The maps are converted once to three functions per texel (R, G, B; an lrgb texel's luminance
// function times its chroma — exact) and box-filtered into a MIP pyramid of coefficients.
// Radiance is linear in the coefficients, so a filtered lookup of coefficients followed by
// evaluation at the light is the filtered radiance for any light — what a renderer that relights
// per shading point needs — up to the clamp of negative radiance, applied after filtering.
// A lookup is trilinear: bilinear in the two levels around log2(footprint in texels), wrapping.
//
// One texture unit is pixels_per_unit texels (the maps' width, as written by stex); the texture
// repeats with the maps' size. The periodic form stretches the maps so that a whole number of
// repeats fills the period (no change when the period is a multiple of the maps' size).
// eval_solid() projects on the (u, v) = (x, y) plane.
#pragma once

#include "legendre_basis.h"

#include <stochtex/texture.h>

#include <array>
#include <string>
#include <vector>

namespace stochtex {

/// `stex info` lines for a ptm description: colour model, maps, light, file.
std::string describe_ptm(const TextureDescription& description);

class PtmTexture final : public Texture {
public:
    explicit PtmTexture(const TextureDescription& description);
    PtmTexture(const TextureDescription& description, const Vec2& period);

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override;
    Rgb eval_solid(const SurfacePoint& point) const override;
    Rgb mean() const override { return mean_; }

    /// The filtered R, G, B reflectance functions at uv (Legendre coefficients): for relighting
    /// with any light direction after one lookup.
    std::array<legendre::Terms, 3> functions(const Vec2& uv, double footprint_units) const;
    int level_count() const { return int(levels_.size()); }

private:
    PtmTexture(const TextureDescription& description, const Vec2* period);
    struct Level {
        int width, height;
        std::vector<float> functions;  // 18 floats per texel: R, G, B × b0 … b5
    };
    static constexpr int floats_per_texel = 18;
    void add_texel(const Level& level, int x, int y, double weight, double* sum) const;
    void bilinear(const Level& level, double x, double y, double* sum, double weight) const;
    Rgb lit(const std::array<legendre::Terms, 3>& functions) const;

    std::vector<Level> levels_;
    legendre::Terms basis_{};
    double texels_per_unit_[2] = {1, 1};  // level-0 texels per texture unit, per axis
    Rgb mean_{};
};

}  // namespace stochtex
