// stochtex - from decorrelated Gaussian channels to RGB in OSL: the core's ColourMapping
// (core/src/colour/colour_mapping.h), shared by the wavelet, gabor and tiling shaders.
//
// Channel c with a histogram map is f_c(z_c), or E[f_c(z_c + dropped_c Z)] (Gauss-Hermite) when
// filtering removed detail of standard deviation dropped_c (units of sigma_m); without a map it
// stays Gaussian, z_c sigma_m[c]. Then rgb = mean + basis y. Common subset of OSL and C++ (see
// stochtex_wavelet.h).
#ifndef STOCHTEX_COLOUR_H
#define STOCHTEX_COLOUR_H

#include "stochtex_subset.h"

#define STOCHTEX_MAX_KNOTS 64
#define STOCHTEX_GH_COUNT 12

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

// rgb = mean + basis y (basis row-major).
void stochtex_colour_basis(float y0, float y1, float y2, float mean[], float basis[],
                           STOCHTEX_OUT(float) r, STOCHTEX_OUT(float) g, STOCHTEX_OUT(float) b)
{
    r = mean[0] + basis[0] * y0 + basis[1] * y1 + basis[2] * y2;
    g = mean[1] + basis[3] * y0 + basis[4] * y1 + basis[5] * y2;
    b = mean[2] + basis[6] * y0 + basis[7] * y1 + basis[8] * y2;
}

#endif
