#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <cmath>

#include "models/model.h"

namespace stochtex {

void Texture::eval_region(const RasterRegion& region, const RgbOutput& out) const
{
    for (int j = 0; j < region.height; ++j)
        for (int i = 0; i < region.width; ++i)
            out.set(std::size_t(j) * region.width + i, eval({region.u(i), region.v(j)}, region.footprint));
}

void Texture::eval_points(const PointBatch& points, const RgbOutput& out) const
{
    for (std::size_t k = 0; k < points.count; ++k) out.set(k, eval(points.uv[k], points.footprints[k]));
}

void Texture::eval_solid_region(const SolidRegion& region, const RgbOutput& out) const
{
    const RasterRegion& plane = region.plane;
    SurfacePoint point;  // normal +w: the plane's
    point.dpdx = {plane.footprint.dudx, plane.footprint.dvdx, 0};
    point.dpdy = {plane.footprint.dudy, plane.footprint.dvdy, 0};
    for (int j = 0; j < plane.height; ++j)
        for (int i = 0; i < plane.width; ++i) {
            point.p = {plane.u(i), plane.v(j), region.w};
            out.set(std::size_t(j) * plane.width + i, eval_solid(point));
        }
}

void Texture::eval_solid_points(const SurfaceBatch& points, const RgbOutput& out) const
{
    for (std::size_t k = 0; k < points.count; ++k) out.set(k, eval_solid(points.points[k]));
}

std::unique_ptr<Texture> make_texture(const TextureDescription& description)
{
    validate(description, "texture description");
    return model_of(description).make_texture(description);
}

std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description, const Vec2& period)
{
    validate(description, "texture description");
    for (double p : period)
        if (!(p > 0) || !std::isfinite(p)) throw Error("periodic texture: the period must be positive and finite");
    return model_of(description).make_periodic_texture(description, period);
}

}  // namespace stochtex
