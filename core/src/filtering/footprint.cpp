#include <stochtex/footprint.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {
/// Largest singular value of the 2×2 or (projected) 3×2 Jacobian with Gram matrix [[a, b], [b, c]].
double major_axis_from_gram(double a, double b, double c)
{
    const double half_trace = 0.5 * (a + c);
    const double discriminant = std::sqrt(std::max(0.0, 0.25 * (a - c) * (a - c) + b * b));
    return std::sqrt(std::max(0.0, half_trace + discriminant));
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
}  // namespace

double Footprint2D::major_axis() const
{
    // Columns of J are the derivatives along screen x and y.
    return major_axis_from_gram(dudx * dudx + dvdx * dvdx, dudx * dudy + dvdx * dvdy, dudy * dudy + dvdy * dvdy);
}

double SurfacePoint::major_axis() const
{
    // Only the footprint's extent within the tangent plane filters a surface texture.
    const double length = std::sqrt(dot(n, n));
    const Vec3 unit = length > 0 ? Vec3{n[0] / length, n[1] / length, n[2] / length} : Vec3{0, 0, 0};
    auto tangential = [&](const Vec3& d) {
        const double along = dot(d, unit);
        return Vec3{d[0] - along * unit[0], d[1] - along * unit[1], d[2] - along * unit[2]};
    };
    const Vec3 tx = tangential(dpdx), ty = tangential(dpdy);
    return major_axis_from_gram(dot(tx, tx), dot(tx, ty), dot(ty, ty));
}

}  // namespace stochtex
