#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <cmath>

#include "models/model.h"
#include "schema/parameter_schema.h"

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
    for (int j = 0; j < plane.height; ++j)
        for (int i = 0; i < plane.width; ++i) out.set(std::size_t(j) * plane.width + i, eval_solid(region.point(i, j)));
}

void Texture::eval_solid_points(const SurfaceBatch& points, const RgbOutput& out) const
{
    for (std::size_t k = 0; k < points.count; ++k) out.set(k, eval_solid(points.points[k]));
}

bool position_in_range(double position, double pixels_per_unit)
{
    return std::isfinite(position) && std::abs(position) * pixels_per_unit <= max_position_pixels;
}

void check_position(double position, double pixels_per_unit, const std::string& name)
{
    if (position_in_range(position, pixels_per_unit)) return;
    if (!std::isfinite(position)) throw Error(name + ": must be a finite number, got " + number_text(position));
    throw Error(name + ": " + number_text(position) + " texture units is out of range: positions must be within ±" +
                number_text(max_position_pixels / pixels_per_unit) + " texture units (2^45 exemplar pixels at " +
                number_text(pixels_per_unit) + " pixels per unit)");
}

std::unique_ptr<Texture> make_texture(const TextureDescription& description)
{
    validate(description, "texture description");
    return model_of(description).make_texture(description);
}

std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description, const Vec2& period)
{
    validate(description, "texture description");
    for (double p : period) {
        if (!(p > 0) || !std::isfinite(p)) throw Error("periodic texture: the period must be positive and finite");
        check_position(p, description.pixels_per_unit, "periodic texture: period");
    }
    return model_of(description).make_periodic_texture(description, period);
}

}  // namespace stochtex
