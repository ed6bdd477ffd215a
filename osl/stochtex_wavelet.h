// stochtex - the wavelet model's synthesis in OSL (docs/osl.md).
//
// A transcription of the core's WaveletTexture::eval / eval_solid (core/src/wavelet_texture.cpp)
// with the numbers of core/include/stochtex/models/wavelet_shader_data.h: band clamping (band_fade),
// the quadratic B-spline over the Cook-DeRose coefficient tile, the histogram map's
// Gauss-Hermite filter, the colour basis. The coefficient tiles are small images read with
// closest-texel texture() lookups, so each coefficient is the core's float exactly and the
// B-spline is evaluated here, in the shader, exactly as the core does.
//
// Written in the common subset of OSL and C++: tests/osl_shader_test.cpp compiles this very
// file as C++ (with a texture() that reads the tiles) and compares it with the core, which is
// how the maths is checked on machines without oslc. So: float and int only, arrays passed
// whole, results through STOCHTEX_OUT parameters, no OSL-only syntax below.
#ifndef STOCHTEX_WAVELET_H
#define STOCHTEX_WAVELET_H

#include "stochtex_subset.h"

#include "stochtex_colour.h"

#define STOCHTEX_MAX_BANDS 24

// Band clamping (core/src/band_filter.h): band j is kept whole while the footprint is at most
// 2^j exemplar pixels, removed from 2^(j+1), faded by a smoothstep in log2 in between.
float stochtex_band_fade(int band, float footprint_px)
{
    if (footprint_px <= pow(2.0, float(band)))
        return 1.0;
    float t = log2(footprint_px) - float(band);
    if (t >= 1.0)
        return 0.0;
    return 1.0 - t * t * (3.0 - 2.0 * t);
}

int stochtex_wrap(int i, int n)
{
    return ((i % n) + n) % n;
}

// Coefficient (i, j) of a size x size tile stored as an image of that size (rows as the host
// runs them: stochtex_subset.h).
float stochtex_tile2(string tile, int size, int rows_bottom_up, int i, int j)
{
    float x = float(stochtex_wrap(i, size)), y = float(stochtex_wrap(j, size));
    float c = texture(tile, (x + 0.5) / float(size), stochtex_row_t((y + 0.5) / float(size), rows_bottom_up), "interp",
                      "closest", "width", 0.0, "wrap", "periodic");
    return c;
}

// Coefficient (i, j, k) of a size^3 tile stored as an atlas image of per_row x per_row slices
// (slice k at column k mod per_row, row k / per_row).
float stochtex_tile3(string tile, int size, int per_row, int rows_bottom_up, int i, int j, int k)
{
    int z = stochtex_wrap(k, size);
    float x = float(stochtex_wrap(i, size) + size * (z % per_row));
    float y = float(stochtex_wrap(j, size) + size * (z / per_row));
    float atlas = float(size * per_row);
    float c = texture(tile, (x + 0.5) / atlas, stochtex_row_t((y + 0.5) / atlas, rows_bottom_up), "interp", "closest",
                      "width", 0.0, "wrap", "periodic");
    return c;
}

// The quadratic B-spline weights at lattice coordinate x; returns the first of the three cells.
int stochtex_spline(float x, STOCHTEX_OUT(float) w0, STOCHTEX_OUT(float) w1, STOCHTEX_OUT(float) w2)
{
    float shifted = x - 0.5;
    float base = floor(shifted);
    float t = shifted - base;
    w0 = 0.5 * (1.0 - t) * (1.0 - t);
    w2 = 0.5 * t * t;
    w1 = 1.0 - w0 - w2;
    return int(base);
}

float stochtex_noise2(string tile, int size, int rows_bottom_up, float x, float y)
{
    float wx0 = 0.0, wx1 = 0.0, wx2 = 0.0, wy0 = 0.0, wy1 = 0.0, wy2 = 0.0;
    int i = stochtex_spline(x, wx0, wx1, wx2);
    int j = stochtex_spline(y, wy0, wy1, wy2);
    float sum = 0.0;
    for (int r = 0; r < 3; ++r) {
        float wy = r == 0 ? wy0 : (r == 1 ? wy1 : wy2);
        float row = wx0 * stochtex_tile2(tile, size, rows_bottom_up, i, j + r) +
                    wx1 * stochtex_tile2(tile, size, rows_bottom_up, i + 1, j + r) +
                    wx2 * stochtex_tile2(tile, size, rows_bottom_up, i + 2, j + r);
        sum += wy * row;
    }
    return sum;
}

float stochtex_noise3(string tile, int size, int per_row, int rows_bottom_up, float x, float y, float z)
{
    float wx0 = 0.0, wx1 = 0.0, wx2 = 0.0, wy0 = 0.0, wy1 = 0.0, wy2 = 0.0, wz0 = 0.0, wz1 = 0.0, wz2 = 0.0;
    int i = stochtex_spline(x, wx0, wx1, wx2);
    int j = stochtex_spline(y, wy0, wy1, wy2);
    int k = stochtex_spline(z, wz0, wz1, wz2);
    float sum = 0.0;
    for (int p = 0; p < 3; ++p) {
        float wz = p == 0 ? wz0 : (p == 1 ? wz1 : wz2);
        float plane = 0.0;
        for (int r = 0; r < 3; ++r) {
            float wy = r == 0 ? wy0 : (r == 1 ? wy1 : wy2);
            float row = wx0 * stochtex_tile3(tile, size, per_row, rows_bottom_up, i, j + r, k + p) +
                        wx1 * stochtex_tile3(tile, size, per_row, rows_bottom_up, i + 1, j + r, k + p) +
                        wx2 * stochtex_tile3(tile, size, per_row, rows_bottom_up, i + 2, j + r, k + p);
            plane += wy * row;
        }
        sum += wz * plane;
    }
    return sum;
}

// Largest singular value of the Jacobian with Gram matrix [[a, b], [b, c]]
// (core/src/footprint.cpp): the footprint's longest axis.
float stochtex_major_axis_from_gram(float a, float b, float c)
{
    float half_trace = 0.5 * (a + c);
    float discriminant = sqrt(max(0.0, 0.25 * (a - c) * (a - c) + b * b));
    return sqrt(max(0.0, half_trace + discriminant));
}

float stochtex_major_axis_2d(float dudx, float dvdx, float dudy, float dvdy)
{
    return stochtex_major_axis_from_gram(dudx * dudx + dvdx * dvdx, dudx * dudy + dvdx * dvdy,
                                         dudy * dudy + dvdy * dvdy);
}

// The footprint (dP/dx, dP/dy) projected on the tangent plane of unit normal n.
float stochtex_major_axis_3d(float nx, float ny, float nz, float ax, float ay, float az, float bx, float by, float bz)
{
    float along_a = ax * nx + ay * ny + az * nz, along_b = bx * nx + by * ny + bz * nz;
    float tax = ax - along_a * nx, tay = ay - along_a * ny, taz = az - along_a * nz;
    float tbx = bx - along_b * nx, tby = by - along_b * ny, tbz = bz - along_b * nz;
    return stochtex_major_axis_from_gram(tax * tax + tay * tay + taz * taz, tax * tbx + tay * tby + taz * tbz,
                                         tbx * tbx + tby * tby + tbz * tbz);
}

// The texture at point (x, y, z) in texture units (2D: z unused), footprint_px exemplar pixels
// wide. Arrays are flattened: weight[c * MAX_BANDS + j], offset[(c * MAX_BANDS + j) * 3 + axis],
// knots[c * MAX_KNOTS + k] with knot_count[c] knots (0: no histogram map); the tiles read with
// rows as the host runs them (stochtex_rows_bottom_up).
void stochtex_wavelet(int solid, float x, float y, float z, float footprint_px,
                      int band_count, float scale[], float weight[], float offset[],
                      float sigma_m[], float sigma_n2, float solid_gain,
                      int knot_count[], float knot_z[], float knot_value[], float knot_slope[],
                      float gh_node[], float gh_weight[],
                      int joint_count, float joint_first, float joint_inverse_step, float joint_curve[],
                      float mean[], float basis[],
                      string tile_2d, int size_2d, string tile_3d, int size_3d, int per_row_3d, int rows_bottom_up,
                      STOCHTEX_OUT(float) r, STOCHTEX_OUT(float) g, STOCHTEX_OUT(float) b)
{
    float fade[STOCHTEX_MAX_BANDS];
    for (int j = 0; j < band_count; ++j)
        fade[j] = stochtex_band_fade(j, footprint_px);
    float gain = solid ? solid_gain : 1.0;
    float y_channel[3], z_channel[3], dropped_channel[3];
    for (int c = 0; c < 3; ++c) {
        float kept = 0.0, dropped_variance = 0.0;
        for (int j = 0; j < band_count; ++j) {
            float w = weight[c * STOCHTEX_MAX_BANDS + j];
            if (fade[j] < 1.0)
                dropped_variance += (1.0 - fade[j] * fade[j]) * w * w;
            if (fade[j] > 0.0 && w != 0.0) {
                int o = (c * STOCHTEX_MAX_BANDS + j) * 3;
                float s = scale[j];
                float n = solid ? stochtex_noise3(tile_3d, size_3d, per_row_3d, rows_bottom_up, x * s + offset[o],
                                                  y * s + offset[o + 1], z * s + offset[o + 2])
                                : stochtex_noise2(tile_2d, size_2d, rows_bottom_up, x * s + offset[o], y * s + offset[o + 1]);
                kept += fade[j] * w * n;
            }
        }
        float sigma = sigma_m[c];
        float zc = sigma > 0.0 ? gain * kept / sigma : 0.0;
        float dropped = sigma > 0.0 ? sqrt(dropped_variance * sigma_n2) / sigma : 0.0;
        y_channel[c] = stochtex_channel_value(zc, dropped, c, sigma_m, knot_count, knot_z, knot_value, knot_slope,
                                              gh_node, gh_weight);
        z_channel[c] = zc;
        dropped_channel[c] = dropped;
    }
    stochtex_colour_joint(y_channel[0], y_channel[1], y_channel[2], z_channel[0], dropped_channel[0], joint_count,
                          joint_first, joint_inverse_step, joint_curve, gh_node, gh_weight, mean, basis, r, g, b);
}

#endif
