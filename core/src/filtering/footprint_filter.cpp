#include "filtering/footprint_filter.h"

namespace stochtex {

TangentFrame tangent_frame(const Vec3& normal, const Vec3& dpdx)
{
    TangentFrame frame;
    const double length = std::sqrt(dot3(normal, normal));
    if (!(length > 0)) return frame;  // no normal: the w = const plane of a 2D render
    frame.n = {normal[0] / length, normal[1] / length, normal[2] / length};
    const Vec3& n = frame.n;
    Vec3 t = dpdx;
    const double along = dot3(t, n);
    for (int i = 0; i < 3; ++i) t[i] -= along * n[i];
    double t_length = std::sqrt(dot3(t, t));
    if (!(t_length > 1e-12 * (1 + std::sqrt(dot3(dpdx, dpdx))))) {
        // Point sampling or dP/dx along n: any tangent does (the value does not depend on it).
        t = std::abs(n[0]) < 0.9 ? Vec3{0, -n[2], n[1]} : Vec3{-n[2], 0, n[0]};  // (1,0,0)×n or (0,1,0)×n
        t_length = std::sqrt(dot3(t, t));
    }
    frame.t = {t[0] / t_length, t[1] / t_length, t[2] / t_length};
    frame.b = {n[1] * frame.t[2] - n[2] * frame.t[1], n[2] * frame.t[0] - n[0] * frame.t[2],
               n[0] * frame.t[1] - n[1] * frame.t[0]};
    return frame;
}

Symmetric2 filter_covariance(double j00, double j01, double j10, double j11, double scale)
{
    const double s2 = pixel_filter_sigma * pixel_filter_sigma * scale * scale;
    Symmetric2 sigma{s2 * (j00 * j00 + j01 * j01), s2 * (j00 * j10 + j01 * j11), s2 * (j10 * j10 + j11 * j11)};
    const double major = sigma.largest_eigenvalue(), minor = sigma.smallest_eigenvalue();
    const double floor = major / (max_footprint_anisotropy * max_footprint_anisotropy);
    if (!(minor < floor)) return sigma;
    // Widen along the minor eigenvector: Σ + (floor − minor) v vᵀ.
    double vx = sigma.xy, vy = minor - sigma.xx;
    if (vx * vx + vy * vy < 1e-30 * (major * major + 1e-300)) vx = minor - sigma.yy, vy = sigma.xy;
    double norm2 = vx * vx + vy * vy;
    if (!(norm2 > 0)) vx = sigma.xx <= sigma.yy ? 1 : 0, vy = 1 - vx, norm2 = 1;
    const double extra = (floor - minor) / norm2;
    sigma.xx += extra * vx * vx;
    sigma.xy += extra * vx * vy;
    sigma.yy += extra * vy * vy;
    return sigma;
}

Symmetric2 without_isotropic_blur(const Symmetric2& sigma, double v)
{
    const double major = sigma.largest_eigenvalue(), minor = sigma.smallest_eigenvalue();
    if (minor >= v) return {sigma.xx - v, sigma.xy, sigma.yy - v};
    if (major <= v) return {};
    // Only the major axis keeps some blur: (major − v)·e eᵀ, e its unit eigenvector.
    double ex = sigma.xy, ey = major - sigma.xx;
    if (std::abs(ex) + std::abs(ey) < 1e-12 * major) ex = major - sigma.yy, ey = sigma.xy;
    const double norm2 = ex * ex + ey * ey, k = (major - v) / norm2;
    return {k * ex * ex, k * ex * ey, k * ey * ey};
}

}  // namespace stochtex
