// stochtex - from decorrelated Gaussian channels to RGB in OSL: the core's ColourMapping
// (core/src/colour/colour_mapping.h), shared by the wavelet, gabor and tiling shaders.
//
// Channel c with a histogram map is f_c(z_c), or E[f_c(z_c + dropped_c Z)] (Gauss-Hermite) when
// filtering removed detail of standard deviation dropped_c (units of sigma_m); without a map it
// stays Gaussian, z_c sigma_m[c]. With joint colour (core/src/colour/chroma_given_brightness.h)
// the chroma channels' values are residuals r_c and become location_c(z_0) + scale_c(z_0) r_c,
// each curve averaged over the dropped brightness detail as the maps are. Then
// rgb = mean + basis y. Common subset of OSL and C++ (see stochtex_wavelet.h).
#ifndef STOCHTEX_COLOUR_H
#define STOCHTEX_COLOUR_H

#include "stochtex_subset.h"

#define STOCHTEX_MAX_KNOTS 64
#define STOCHTEX_GH_COUNT 12
#define STOCHTEX_MAX_JOINT_KNOTS 64

// Channel c's histogram map f_c: the monotone cubic Hermite through its knots, clamped at the ends.
float stochtex_histogram_map(float z, int c, int n, float knot_z[], float knot_value[], float knot_slope[])
{
    int base = c * STOCHTEX_MAX_KNOTS;
    if (z <= knot_z[base])
        return knot_value[base];
    if (z >= knot_z[base + n - 1])
        return knot_value[base + n - 1];
    int i = 0;
    while (i + 2 < n && z >= knot_z[base + i + 1])
        i += 1;
    float h = knot_z[base + i + 1] - knot_z[base + i];
    float s = (z - knot_z[base + i]) / h;
    float s2 = s * s, s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * knot_value[base + i] + (s3 - 2.0 * s2 + s) * h * knot_slope[base + i] +
           (-2.0 * s3 + 3.0 * s2) * knot_value[base + i + 1] + (s3 - s2) * h * knot_slope[base + i + 1];
}

// Channel c's value y_c: z in units of sigma_m[c], dropped (same units) what filtering removed.
float stochtex_channel_value(float z, float dropped, int c, float sigma_m[], int knot_count[], float knot_z[],
                             float knot_value[], float knot_slope[], float gh_node[], float gh_weight[])
{
    if (knot_count[c] == 0)
        return z * sigma_m[c];
    if (dropped < 1e-4)
        return stochtex_histogram_map(z, c, knot_count[c], knot_z, knot_value, knot_slope);
    // E[f(z + sigma_d Z)]: the filtered value of a non-linear map (docs/models/wavelet.md).
    float sum = 0.0;
    for (int i = 0; i < STOCHTEX_GH_COUNT; ++i)
        sum += gh_weight[i] * stochtex_histogram_map(z + dropped * gh_node[i], c, knot_count[c], knot_z, knot_value, knot_slope);
    return sum;
}

// Joint colour's curve k (0, 1: location of chroma channel 1, 2; 2, 3: their scale) at brightness
// z: n uniform knots from `first`, 1 / spacing `inverse_step`, linear, constant beyond the ends.
float stochtex_joint_curve(float z, int k, int n, float first, float inverse_step, float joint_curve[])
{
    int base = k * STOCHTEX_MAX_JOINT_KNOTS;
    float position = (z - first) * inverse_step;
    if (!(position > 0.0))
        return joint_curve[base];
    if (position >= float(n - 1))
        return joint_curve[base + n - 1];
    int i = int(position);
    float s = position - float(i);
    return joint_curve[base + i] + s * (joint_curve[base + i + 1] - joint_curve[base + i]);
}

// Joint colour's curve k at brightness z0, or its expectation over the brightness detail
// filtering removed (dropped0, units of sigma_m[0]): E[curve(z0 + dropped0 Z)], Gauss-Hermite.
float stochtex_joint_curve_filtered(float z0, float dropped0, int k, int n, float first, float inverse_step,
                                    float joint_curve[], float gh_node[], float gh_weight[])
{
    if (dropped0 < 1e-4)
        return stochtex_joint_curve(z0, k, n, first, inverse_step, joint_curve);
    float sum = 0.0;
    for (int i = 0; i < STOCHTEX_GH_COUNT; ++i)
        sum += gh_weight[i] * stochtex_joint_curve(z0 + dropped0 * gh_node[i], k, n, first, inverse_step, joint_curve);
    return sum;
}

// rgb = mean + basis y (basis row-major).
void stochtex_colour_basis(float y0, float y1, float y2, float mean[], float basis[],
                           STOCHTEX_OUT(float) r, STOCHTEX_OUT(float) g, STOCHTEX_OUT(float) b)
{
    r = mean[0] + basis[0] * y0 + basis[1] * y1 + basis[2] * y2;
    g = mean[1] + basis[3] * y0 + basis[4] * y1 + basis[5] * y2;
    b = mean[2] + basis[6] * y0 + basis[7] * y1 + basis[8] * y2;
}

// The chroma channels' residuals y1, y2 made values at brightness z0 (joint_count knots; 0:
// independent channels, y unchanged), then rgb = mean + basis y: the core's ColourMapping after
// its histogram maps (condition(), combine()).
void stochtex_colour_joint(float y0, float y1, float y2, float z0, float dropped0, int joint_count, float joint_first,
                           float joint_inverse_step, float joint_curve[], float gh_node[], float gh_weight[],
                           float mean[], float basis[], STOCHTEX_OUT(float) r, STOCHTEX_OUT(float) g,
                           STOCHTEX_OUT(float) b)
{
    float v1 = y1, v2 = y2;
    if (joint_count > 0) {
        v1 = stochtex_joint_curve_filtered(z0, dropped0, 0, joint_count, joint_first, joint_inverse_step, joint_curve,
                                           gh_node, gh_weight) +
             stochtex_joint_curve_filtered(z0, dropped0, 2, joint_count, joint_first, joint_inverse_step, joint_curve,
                                           gh_node, gh_weight) * y1;
        v2 = stochtex_joint_curve_filtered(z0, dropped0, 1, joint_count, joint_first, joint_inverse_step, joint_curve,
                                           gh_node, gh_weight) +
             stochtex_joint_curve_filtered(z0, dropped0, 3, joint_count, joint_first, joint_inverse_step, joint_curve,
                                           gh_node, gh_weight) * y2;
    }
    stochtex_colour_basis(y0, v1, v2, mean, basis, r, g, b);
}

#endif
