// Local random-phase noise by example (paper 003): the texture.
//
//   m_c(x) = n_R,c(x) + Σ_S n_S,c(x)      per decorrelated channel c, then ColourMapping
// (lrp_noise.h: the random-phase strata n_S; lrp_structure_noise.h: the fixed-phase structure
// n_R with random placement and turbulence). σ_M² = Σ_S σ_S,c² + Var(n_R,c); with histogram maps
// the variance a footprint filters away goes to ColourMapping, so minification converges to the
// texture's mean.
//
// Solid evaluation has no LRP form here (the paper's model is 2D; a 3D lattice would need a 3D
// spectrum the photo does not give): eval_solid returns the 2D texture at (u, v) = (p.x, p.y),
// filtered with the footprint's (u, v) part — a projection along w, documented as such.
#pragma once

#include "colour/colour_mapping.h"
#include "models/lrp/lrp_noise.h"
#include "models/lrp/lrp_structure_noise.h"

#include <stochtex/texture.h>

#include <optional>
#include <string>
#include <vector>

namespace stochtex {

/// Special-function calls per evaluation (paper §6.2): 9(J + s) counts 9 windows per stratum and
/// a cosine per term per window; placement blends and turbulence add their own.
struct LrpCost {
    double paper_calls = 0;   ///< 9 (J + s) over the random strata and the structure
    double total_calls = 0;   ///< including placement blends and turbulence
};

/// The lrp part of `stex info`: spectrum grid, strata, structure, cost, σ_M.
std::string describe_lrp(const TextureDescription& description);

class LrpTexture final : public Texture {
public:
    explicit LrpTexture(const TextureDescription& description);
    /// The periodic form: eval() repeats every period[0] in u and period[1] in v.
    LrpTexture(const TextureDescription& description, const Vec2& period);

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override;
    using Texture::eval_region;
    void eval_region(const RasterRegion& region, const RgbOutput& out) const override;
    Rgb eval_solid(const SurfacePoint& point) const override;
    using Texture::eval_solid_region;
    void eval_solid_region(const SolidRegion& region, const RgbOutput& out) const override;
    Rgb mean() const override { return colour_.mean(); }

    const std::array<double, 3>& sigma_m() const { return sigma_m_; }
    LrpCost cost() const;

private:
    LrpTexture(const TextureDescription& description, const Vec2* period);
    /// What filtering removed from each channel, in units of σ_M (for the histogram maps).
    std::array<double, 3> dropped_sigma(const LrpFilter& filter) const;
    Rgb finish(const float m[3], const std::array<double, 3>& dropped) const;

    std::vector<LrpStratumNoise> strata_;
    std::optional<LrpStructureNoise> structure_;
    std::array<double, 3> sigma_m_{};
    bool tracks_dropped_variance_ = false;
    ColourMapping colour_;
};

}  // namespace stochtex
