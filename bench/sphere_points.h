// Scattered surface points, what a position-map bake evaluates (stex bake --positions, the
// Blender add-on's solid route): a size² map of a unit sphere's upper half seen from above,
// scaled to the photo's texel, each point's derivatives those of its texel. The Points3D
// benchmarks of wavelet_bench and gabor_bench evaluate it.
#pragma once

#include <stochtex/footprint.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace stochtex::bench {

inline std::vector<SurfacePoint> sphere_points(int size, double pixels_per_unit)
{
    const double radius = 0.5 * size / pixels_per_unit;  // texture units
    const double texel = 2 * radius / size;
    std::vector<SurfacePoint> points;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const double u = (x + 0.5) * texel - radius, v = (y + 0.5) * texel - radius;
            const double r2 = std::min(u * u + v * v, 0.999 * radius * radius);
            const double h = std::sqrt(radius * radius - r2);
            SurfacePoint point;
            point.p = {u, v, h};
            // dP/dx, dP/dy of the height field h(u, v): (texel, 0, −u/h·texel), (0, texel, −v/h·texel).
            point.dpdx = {texel, 0, -u / h * texel};
            point.dpdy = {0, texel, -v / h * texel};
            point.n = {u / radius, v / radius, h / radius};
            points.push_back(point);
        }
    return points;
}

/// The points evaluated row by row (`row` points a call, as bake.cpp does) into planes
/// (3·row floats): batch through the model's eval_solid_points, else through Texture's default
/// loop over eval_solid() (the scalar reference).
inline void eval_surface_rows(const Texture& texture, const std::vector<SurfacePoint>& points, std::size_t row, bool batch,
                              std::vector<float>& planes)
{
    planes.resize(3 * row);
    const RgbOutput out = RgbOutput::planar(planes.data(), planes.data() + row, planes.data() + 2 * row);
    for (std::size_t first = 0; first < points.size(); first += row) {
        const SurfaceBatch batch_of_row{points.data() + first, std::min(row, points.size() - first)};
        if (batch) texture.eval_solid_points(batch_of_row, out);
        else texture.Texture::eval_solid_points(batch_of_row, out);
    }
}

}  // namespace stochtex::bench
