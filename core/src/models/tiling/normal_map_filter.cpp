#include "models/tiling/normal_map_filter.h"

#include <cmath>

namespace stochtex {

Direction normal_from_slopes(double sx, double sy)
{
    const double length = std::sqrt(sx * sx + sy * sy + 1);
    return {-sx / length, -sy / length, 1 / length};
}

double lean_ndf(const Moments& slopes, double base_variance, const Direction& half)
{
    // The facet whose normal is h has slopes −(h_x, h_y) / h_z.
    const double dx = -half[0] / half[2] - slopes.mean[0], dy = -half[1] / half[2] - slopes.mean[1];
    const double a = slopes.moment(0, 0) + base_variance, b = slopes.moment(0, 1), c = slopes.moment(1, 1) + base_variance;
    const double det = a * c - b * b;
    const double exponent = (c * dx * dx - 2 * b * dx * dy + a * dy * dy) / det;
    // Slope-space Gaussian density → density per unit solid angle of normals (÷ cos⁴θ_h).
    const double cos2 = half[2] * half[2];
    return std::exp(-0.5 * exponent) / (2 * M_PI * std::sqrt(det) * cos2 * cos2);
}

double facet_ndf(double sx, double sy, double base_variance, const Direction& half)
{
    Moments facet;
    facet.channels = 2;
    facet.mean[0] = sx, facet.mean[1] = sy;
    return lean_ndf(facet, base_variance, half);
}

}  // namespace stochtex
