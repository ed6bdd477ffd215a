// stochtex/models/tiling.h: LEAN-filtered shading of a normal_map tiling texture.
#include <stochtex/models/tiling.h>

#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/models/tiling_parameters.h>

#include "models/tiling/normal_map_filter.h"
#include "models/tiling/tiling_texture.h"

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {

Direction unit(const std::array<double, 3>& v)
{
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(length > 0) || !std::isfinite(length)) throw Error("normal-map shading: light and view directions must be non-zero");
    return {v[0] / length, v[1] / length, v[2] / length};
}

class ShadedNormalMap final : public Texture {
public:
    ShadedNormalMap(const TextureDescription& description, const NormalMapShading& shading)
        : Texture(description), normals_(description), shading_(shading), light_(unit(shading.light)), view_(unit(shading.view))
    {
        if (!(shading.base_roughness > 0)) throw Error("normal-map shading: the base roughness must be positive");
        if (!(light_[2] > 0 && view_[2] > 0)) throw Error("normal-map shading: light and view must be above the surface (z > 0)");
        half_ = unit({light_[0] + view_[0], light_[1] + view_[1], light_[2] + view_[2]});
    }

    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override { return shade(normals_.moments(uv, footprint)); }
    Rgb eval_solid(const SurfacePoint&) const override
    {
        throw Error("normal-map shading is defined on the texture plane only (no solid form)");
    }
    Rgb mean() const override { return shade(normals_.noise().global()); }

private:
    Rgb shade(Moments slopes) const
    {
        if (!shading_.lean) slopes.moment(0, 0) = slopes.moment(0, 1) = slopes.moment(1, 0) = slopes.moment(1, 1) = 0;
        const Direction n = normal_from_slopes(slopes.mean[0], slopes.mean[1]);
        const double lambert = std::max(0.0, n[0] * light_[0] + n[1] * light_[1] + n[2] * light_[2]);
        // Microfacet specular with the Gaussian slope NDF (no Fresnel or masking: a comparison
        // of filters, not a material model); the geometric term uses the macro normal.
        const double ndf = lean_ndf(slopes, shading_.base_roughness * shading_.base_roughness, half_);
        const double value = shading_.albedo * lambert + shading_.specular * ndf / (4 * light_[2] * view_[2]) * light_[2];
        return {float(value), float(value), float(value)};
    }

    TilingTexture normals_;
    NormalMapShading shading_;
    Direction light_, view_, half_{};
};

}  // namespace

std::unique_ptr<Texture> make_shaded_normal_map(const TextureDescription& description, const NormalMapShading& shading)
{
    validate(description, "texture description");
    if (!description.parameters.holds<TilingParameters>() || description.parameters.get<TilingParameters>().output != TilingOutput::normal_map)
        throw Error("normal-map shading needs a tiling texture with output normal_map (stex tiling normal-map)");
    return std::make_unique<ShadedNormalMap>(description, shading);
}

}  // namespace stochtex
