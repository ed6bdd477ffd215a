// The reference a benchmark measures a raster path against, in the same run: the texture's
// eval() once per pixel (Texture's default eval_region loops over the point method).
#pragma once

#include <stochtex/texture.h>

namespace stochtex::bench {

class PointByPoint final : public Texture {
public:
    explicit PointByPoint(const Texture& inner) : Texture(inner.description()), inner_(inner) {}
    Rgb eval(const Vec2& uv, const Footprint2D& footprint) const override { return inner_.eval(uv, footprint); }
    Rgb eval_solid(const SurfacePoint& point) const override { return inner_.eval_solid(point); }
    Rgb mean() const override { return inner_.mean(); }

private:
    const Texture& inner_;
};

}  // namespace stochtex::bench
