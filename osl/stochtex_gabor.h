// stochtex - the gabor model's synthesis in OSL (docs/osl.md).
//
// A transcription of the core's GaborTexture::eval / eval_solid (core/src/models/gabor/) with the
// numbers of core/include/stochtex/models/gabor_shader_data.h:
//   - the footprint (dP/dx, dP/dy) becomes the pixel Gaussian's covariance, anisotropy clamped,
//     less the exemplar pixel's own blur (filtering/footprint_filter.h);
//   - per octave, the A-form filter A = I + 2 pi a^2 Sigma_f of every kernel (gabor_kernel.h), the
//     octave's fade by the filtered support's area, and - with histogram maps - the variance the
//     filter removed (gabor_statistics.h) for the Gauss-Hermite histogram filter;
//   - the sparse convolution over a jittered grid of impulses (gabor_noise.h): the cells, their
//     impulse positions, frequencies and phases - and, kind oriented, each impulse's choice of
//     the octave's orientation or an isotropic frequency - are the core's, bit for bit
//     (SplitMix64 in 16-bit limbs, stochtex_u64.h), and the cells visited follow the same
//     ellipse row spans;
//   - the solid noise sliced by the tangent plane (eq. 6), in the frame the core builds.
// Everything else runs in float where the core uses double: the measured difference is in
// docs/osl.md. The isotropic retained-variance table (E over the sphere, 97 x 97) is an image
// read with closest-texel texture() lookups and interpolated here as the core does.
//
// Common subset of OSL and C++ (see stochtex_wavelet.h); tests/osl_gabor_test.cpp compiles it.
#ifndef STOCHTEX_GABOR_H
#define STOCHTEX_GABOR_H

#include "stochtex_subset.h"

#include "stochtex_colour.h"
#include "stochtex_u64.h"

#define STOCHTEX_GABOR_MAX_OCTAVES 24
// octave[k * STRIDE + field]: the fields of gabor_shader_data.h's GaborShaderOctave. Cell sides
// come as hi + lo, hi of at most 8 significant bits: i * hi is then exact in float for
// |i| < 2^16 cells, so an impulse's offset from the point, x - (i + f) * side, is as accurate as
// the core's double (a float side would be off by 1e-4 px at 1500 px, enough to move kernels
// across the 5 % edge of their support now and then).
#define STOCHTEX_GABOR_STRIDE 16
#define STOCHTEX_GABOR_FREQUENCY 0
#define STOCHTEX_GABOR_BANDWIDTH 1
#define STOCHTEX_GABOR_RADIUS 2
#define STOCHTEX_GABOR_CELL_2D 3
#define STOCHTEX_GABOR_CELL_2D_LO 4
#define STOCHTEX_GABOR_CELL_3D 5
#define STOCHTEX_GABOR_CELL_3D_LO 6
#define STOCHTEX_GABOR_GAIN_2D 7
#define STOCHTEX_GABOR_GAIN_3D 8
#define STOCHTEX_GABOR_WEIGHT 9
// Kind oriented: the share p_k of oriented impulses and their omega / F (x, y, z); 0 otherwise.
#define STOCHTEX_GABOR_ORIENTED_SHARE 12
#define STOCHTEX_GABOR_ORIENTATION 13
// kind: GaborKind's order.
#define STOCHTEX_GABOR_ISOTROPIC 0
#define STOCHTEX_GABOR_ANISOTROPIC 1
#define STOCHTEX_GABOR_HYBRID 2
#define STOCHTEX_GABOR_ORIENTED 3
// The filter of one kernel bandwidth: filter[0..2] A (xx, xy, yy), [3..5] A^-1, [6..8] the
// damping 2 pi^2 A^-1 Sigma_f, [9] |A|^-1/2, [10] 1 when Sigma_f = 0 (point sampling).
#define STOCHTEX_GABOR_FILTER_SIZE 11

float stochtex_quadratic_form(float xx, float xy, float yy, float x, float y)
{
    return xx * x * x + 2.0 * xy * x * y + yy * y * y;
}

float stochtex_largest_eigenvalue(float xx, float xy, float yy)
{
    float half_trace = 0.5 * (xx + yy);
    return half_trace + sqrt(max(0.0, 0.25 * (xx - yy) * (xx - yy) + xy * xy));
}

float stochtex_smallest_eigenvalue(float xx, float xy, float yy)
{
    float half_trace = 0.5 * (xx + yy);
    return half_trace - sqrt(max(0.0, 0.25 * (xx - yy) * (xx - yy) + xy * xy));
}

// filter_covariance (filtering/footprint_filter.cpp): sigma^2 J J^T of the half-pixel Gaussian, J's
// columns the derivatives along screen x (dudx, dvdx) and y (dudy, dvdy), times scale^2; axes
// clamped to an anisotropy of 8.
void stochtex_filter_covariance(float dudx, float dvdx, float dudy, float dvdy, float scale,
                                STOCHTEX_OUT(float) sxx, STOCHTEX_OUT(float) sxy, STOCHTEX_OUT(float) syy)
{
    float s2 = 0.25 * scale * scale;
    sxx = s2 * (dudx * dudx + dudy * dudy);
    sxy = s2 * (dudx * dvdx + dudy * dvdy);
    syy = s2 * (dvdx * dvdx + dvdy * dvdy);
    float major = stochtex_largest_eigenvalue(sxx, sxy, syy), minor = stochtex_smallest_eigenvalue(sxx, sxy, syy);
    float floor_value = major / 64.0;
    if (!(minor < floor_value))
        return;
    float vx = sxy, vy = minor - sxx;
    if (vx * vx + vy * vy < 1e-30 * (major * major)) {
        vx = minor - syy;
        vy = sxy;
    }
    float norm2 = vx * vx + vy * vy;
    if (!(norm2 > 0.0)) {
        vx = sxx <= syy ? 1.0 : 0.0;
        vy = 1.0 - vx;
        norm2 = 1.0;
    }
    float extra = (floor_value - minor) / norm2;
    sxx += extra * vx * vx;
    sxy += extra * vx * vy;
    syy += extra * vy * vy;
}

// without_isotropic_blur: Sigma - v I, negative eigenvalues clamped to 0.
void stochtex_without_isotropic_blur(float v, STOCHTEX_OUT(float) sxx, STOCHTEX_OUT(float) sxy, STOCHTEX_OUT(float) syy)
{
    float major = stochtex_largest_eigenvalue(sxx, sxy, syy), minor = stochtex_smallest_eigenvalue(sxx, sxy, syy);
    if (minor >= v) {
        sxx -= v;
        syy -= v;
        return;
    }
    if (major <= v) {
        sxx = 0.0;
        sxy = 0.0;
        syy = 0.0;
        return;
    }
    float ex = sxy, ey = major - sxx;
    if (abs(ex) + abs(ey) < 1e-12 * major) {
        ex = major - syy;
        ey = sxy;
    }
    float k = (major - v) / (ex * ex + ey * ey);
    sxx = k * ex * ex;
    sxy = k * ex * ey;
    syy = k * ey * ey;
}

// GaborFilter (gabor_kernel.cpp): the A-form filter of bandwidth a by Sigma_f.
void stochtex_gabor_filter(float a, float sxx, float sxy, float syy, STOCHTEX_OUT_ARRAY(float) filter[STOCHTEX_GABOR_FILTER_SIZE])
{
    for (int i = 0; i < STOCHTEX_GABOR_FILTER_SIZE; ++i)
        filter[i] = 0.0;
    filter[0] = 1.0;
    filter[2] = 1.0;
    filter[3] = 1.0;
    filter[5] = 1.0;
    filter[9] = 1.0;
    if (sxx == 0.0 && sxy == 0.0 && syy == 0.0) {
        filter[10] = 1.0;
        return;
    }
    float k = 2.0 * M_PI * a * a;
    float mxx = 1.0 + k * sxx, mxy = k * sxy, myy = 1.0 + k * syy;
    float det = mxx * myy - mxy * mxy;
    float ixx = myy / det, ixy = -mxy / det, iyy = mxx / det;
    float c = 2.0 * M_PI * M_PI;
    filter[0] = mxx;
    filter[1] = mxy;
    filter[2] = myy;
    filter[3] = ixx;
    filter[4] = ixy;
    filter[5] = iyy;
    filter[6] = c * (ixx * sxx + ixy * sxy);
    filter[7] = c * (ixx * sxy + ixy * syy);
    filter[8] = c * (ixy * sxy + iyy * syy);
    filter[9] = 1.0 / sqrt(det);
}

// The octave's fade by its filtered support's spread (gabor_texture.cpp): whole to 8, gone at 32.
float stochtex_gabor_fade(float spread)
{
    if (spread <= 8.0)
        return 1.0;
    if (spread >= 32.0)
        return 0.0;
    float t = log2(spread / 8.0) / 2.0;
    return 1.0 - t * t * (3.0 - 2.0 * t);
}

// tangent_frame (filtering/footprint_filter.cpp): n normalised, t along dP/dx's tangential part.
void stochtex_tangent_frame(float nrm[3], float dpdx[3], STOCHTEX_OUT_ARRAY(float) t[3], STOCHTEX_OUT_ARRAY(float) b[3],
                            STOCHTEX_OUT_ARRAY(float) n[3])
{
    t[0] = 1.0;
    t[1] = 0.0;
    t[2] = 0.0;
    b[0] = 0.0;
    b[1] = 1.0;
    b[2] = 0.0;
    n[0] = 0.0;
    n[1] = 0.0;
    n[2] = 1.0;
    float norm_length = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (!(norm_length > 0.0))
        return;
    for (int i = 0; i < 3; ++i)
        n[i] = nrm[i] / norm_length;
    float along = dpdx[0] * n[0] + dpdx[1] * n[1] + dpdx[2] * n[2];
    float tt[3];
    for (int i = 0; i < 3; ++i)
        tt[i] = dpdx[i] - along * n[i];
    float t_length = sqrt(tt[0] * tt[0] + tt[1] * tt[1] + tt[2] * tt[2]);
    if (!(t_length > 1e-12 * (1.0 + sqrt(dpdx[0] * dpdx[0] + dpdx[1] * dpdx[1] + dpdx[2] * dpdx[2])))) {
        if (abs(n[0]) < 0.9) {
            tt[0] = 0.0;
            tt[1] = -n[2];
            tt[2] = n[1];
        } else {
            tt[0] = -n[2];
            tt[1] = 0.0;
            tt[2] = n[0];
        }
        t_length = sqrt(tt[0] * tt[0] + tt[1] * tt[1] + tt[2] * tt[2]);
    }
    for (int i = 0; i < 3; ++i)
        t[i] = tt[i] / t_length;
    b[0] = n[1] * t[2] - n[2] * t[1];
    b[1] = n[2] * t[0] - n[0] * t[2];
    b[2] = n[0] * t[1] - n[1] * t[0];
}

// ---- Impulses: the core's bits ---------------------------------------------------------------

// key + i * step_i + j * step_j (+ k * step_k): GaborNoise::cell_key_2d / _3d (not periodic).
void stochtex_gabor_cell_key(int key[4], int dimensions, int i, int j, int k, STOCHTEX_OUT_ARRAY(int) r[4])
{
    int step_i[4] = { 60675, 53650, 18994, 53685 };  // 0xd1b54a32d192ed03
    int step_j[4] = { 62169, 4238, 29954, 44785 };   // 0xaef17502108ef2d9
    int step_k[4] = { 51253, 23789, 49248, 62364 };  // 0xf39cc0605cedc835
    int index[4], term[4], sum[4];
    stochtex_u64_copy(key, sum);
    stochtex_u64_from_int(i, index);
    stochtex_u64_mul(index, step_i, term);
    stochtex_u64_add(sum, term, sum);
    stochtex_u64_from_int(j, index);
    stochtex_u64_mul(index, step_j, term);
    stochtex_u64_add(sum, term, sum);
    if (dimensions == 3) {
        stochtex_u64_from_int(k, index);
        stochtex_u64_mul(index, step_k, term);
        stochtex_u64_add(sum, term, sum);
    }
    stochtex_u64_copy(sum, r);
}

// The impulse's attribute word: mix64(key + 0x9e3779b97f4a7c15).
void stochtex_gabor_attributes(int key[4], STOCHTEX_OUT_ARRAY(int) r[4])
{
    int offset[4] = { 31765, 32586, 31161, 40503 };
    int t[4];
    stochtex_u64_add(key, offset, t);
    stochtex_mix64(t, r);
}

// Cell-relative impulse coordinate: 21 bits at their sub-cell's centre (position_fraction).
float stochtex_gabor_fraction(int bits[4], int shift)
{
    return (float(stochtex_u64_bits(bits, shift, 21)) + 0.5) / 2097152.0;
}

// Phase index of channel c (10 bits each), as an angle.
float stochtex_gabor_phase(int attributes[4], int c)
{
    return 2.0 * M_PI * float(stochtex_u64_bits(attributes, 10 * c, 10)) / 1024.0;
}

// Kind oriented: 1 if the impulse of cell `cell` is oriented - its own draw, the top 53 bits of
// mix64(key + 0x632be59bd9b4e019), below the octave's bound `below` (p_k 2^53, 4 limbs).
int stochtex_gabor_is_oriented(int cell[4], int below[4])
{
    int offset[4] = { 57369, 55732, 58779, 25387 };
    int t[4];
    stochtex_u64_add(cell, offset, t);
    stochtex_mix64(t, t);
    stochtex_u64_shift_right(t, 11, t);
    return stochtex_u64_less(t, below);
}

// GaborNoise::frequency_of: the impulse's frequency (3D). Kind oriented: omega = f * orientation
// for an oriented impulse (stochtex_gabor_is_oriented), else the isotropic kind's draw.
void stochtex_gabor_frequency(int kind, float f, float direction[3], float direction_length, float e1[3], float e2[3],
                              float orientation[3], int below[4], int cell[4], int attributes[4],
                              STOCHTEX_OUT_ARRAY(float) omega[3])
{
    if (kind == STOCHTEX_GABOR_ORIENTED && stochtex_gabor_is_oriented(cell, below)) {
        for (int i = 0; i < 3; ++i)
            omega[i] = f * orientation[i];
        return;
    }
    if (kind == STOCHTEX_GABOR_ANISOTROPIC) {
        for (int i = 0; i < 3; ++i)
            omega[i] = f * direction[i] / direction_length;
        return;
    }
    float azimuth = 2.0 * M_PI * float(stochtex_u64_bits(attributes, 30, 10)) / 1024.0;
    float c = cos(azimuth), s = sin(azimuth);
    if (kind == STOCHTEX_GABOR_HYBRID) {
        for (int i = 0; i < 3; ++i)
            omega[i] = f * (c * e1[i] + s * e2[i]);
        return;
    }
    float z = 2.0 * ((float(stochtex_u64_bits(attributes, 40, 24)) + 0.5) / 16777216.0) - 1.0;
    float rho = sqrt(max(0.0, 1.0 - z * z));
    omega[0] = f * rho * c;
    omega[1] = f * rho * s;
    omega[2] = f * z;
}

// ---- The noise of one octave -----------------------------------------------------------------

// row_span_2d: the x-extent [lo, hi] of the ellipse d^T Q d <= r2 over the row d_y in [y0, y1].
int stochtex_row_span_2d(float qxx, float qxy, float qyy, float r2, float y0, float y1, STOCHTEX_OUT(float) lo,
                         STOCHTEX_OUT(float) hi)
{
    float schur = (qxx * qyy - qxy * qxy) / qxx;
    float nearest = y0 > 0.0 ? y0 : (y1 < 0.0 ? y1 : 0.0);
    float w2 = (r2 - schur * nearest * nearest) / qxx;
    if (w2 < 0.0)
        return 0;
    float w = sqrt(w2), c0 = -qxy / qxx * y0, c1 = -qxy / qxx * y1;
    lo = min(c0, c1) - w;
    hi = max(c0, c1) + w;
    return 1;
}

// One kernel's filtered values added to sum[0..2]: d the in-plane offset x - x_i, h the height
// above the plane (2D: 0), omega the impulse's frequency (2D: projected; sliced: omega^s = (st, sb)
// with normal component wn).
void stochtex_gabor_kernel(float filter[STOCHTEX_GABOR_FILTER_SIZE], float a, float q, float du, float dv, float h,
                           float st, float sb, float wn, int attributes[4], int channels,
                           STOCHTEX_OUT_ARRAY(float) sum[3])
{
    float wx = filter[3] * st + filter[4] * sb, wy = filter[4] * st + filter[5] * sb;
    float damp = stochtex_quadratic_form(filter[6], filter[7], filter[8], st, sb);
    float envelope = exp(max(-M_PI * a * a * q - damp, -87.0));
    float turns = wx * du + wy * dv + h * wn;
    float angle = 2.0 * M_PI * (turns - floor(turns));
    for (int c = 0; c < channels; ++c)
        sum[c] += envelope * cos(angle + stochtex_gabor_phase(attributes, c));
}

// GaborNoise::eval_2d at (x, y) exemplar pixels; out0..2 the channels' noises (unit variance unfiltered).
void stochtex_gabor_noise_2d(float x, float y, float filter[STOCHTEX_GABOR_FILTER_SIZE], int kind, float octave[], int k,
                             int key[], int oriented_below[], float direction[3], float direction_length, float e1[3],
                             float e2[3], int channels, STOCHTEX_OUT_ARRAY(float) value[3])
{
    int o = k * STOCHTEX_GABOR_STRIDE;
    float f = octave[o + STOCHTEX_GABOR_FREQUENCY], a = octave[o + STOCHTEX_GABOR_BANDWIDTH];
    float radius = octave[o + STOCHTEX_GABOR_RADIUS];
    float s_hi = octave[o + STOCHTEX_GABOR_CELL_2D], s_lo = octave[o + STOCHTEX_GABOR_CELL_2D_LO];
    float s = s_hi + s_lo;
    float r2 = radius * radius;
    int seed[4], below[4];
    for (int l = 0; l < 4; ++l) {
        seed[l] = key[4 * k + l];
        below[l] = oriented_below[4 * k + l];
    }
    float orientation[3];
    for (int e = 0; e < 3; ++e)
        orientation[e] = octave[o + STOCHTEX_GABOR_ORIENTATION + e];
    float sum[3] = { 0.0, 0.0, 0.0 };
    float extent_y = radius * sqrt(filter[2]);
    int j0 = int(floor((y - extent_y) / s)), j1 = int(floor((y + extent_y) / s));
    for (int j = j0; j <= j1; ++j) {
        float cell_dy = (float(j) * s_hi - y) + float(j) * s_lo;  // the row's lower edge relative to the point
        float lo = 0.0, hi = 0.0;
        if (stochtex_row_span_2d(filter[3], filter[4], filter[5], r2, cell_dy, cell_dy + s, lo, hi) == 0)
            continue;
        int i0 = int(floor((x + lo) / s)), i1 = int(floor((x + hi) / s));
        for (int i = i0; i <= i1; ++i) {
            int cell[4], bits[4];
            stochtex_gabor_cell_key(seed, 2, i, j, 0, cell);
            stochtex_mix64(cell, bits);
            float dx = -((float(i) * s_hi - x) + float(i) * s_lo + stochtex_gabor_fraction(bits, 0) * s);
            float dy = -(cell_dy + stochtex_gabor_fraction(bits, 21) * s);
            float q = stochtex_quadratic_form(filter[3], filter[4], filter[5], dx, dy);
            if (q <= r2) {
                int attributes[4];
                float omega[3];
                stochtex_gabor_attributes(cell, attributes);
                stochtex_gabor_frequency(kind, f, direction, direction_length, e1, e2, orientation, below, cell, attributes,
                                         omega);
                stochtex_gabor_kernel(filter, a, q, dx, dy, 0.0, omega[0], omega[1], 0.0, attributes, channels, sum);
            }
        }
    }
    float gain = octave[o + STOCHTEX_GABOR_GAIN_2D] * filter[9];
    for (int c = 0; c < 3; ++c)
        value[c] = sum[c] * gain;
}

// GaborNoise::eval_sliced: the solid noise at p sliced by the plane (t, b) of normal n.
void stochtex_gabor_noise_sliced(float p[3], float t[3], float b[3], float n[3], float filter[STOCHTEX_GABOR_FILTER_SIZE],
                                 int kind, float octave[], int k, int key[], int oriented_below[], float direction[3],
                                 float direction_length, float e1[3], float e2[3], int channels,
                                 STOCHTEX_OUT_ARRAY(float) value[3])
{
    int o = k * STOCHTEX_GABOR_STRIDE;
    float f = octave[o + STOCHTEX_GABOR_FREQUENCY], a = octave[o + STOCHTEX_GABOR_BANDWIDTH];
    float radius = octave[o + STOCHTEX_GABOR_RADIUS];
    float s_hi = octave[o + STOCHTEX_GABOR_CELL_3D], s_lo = octave[o + STOCHTEX_GABOR_CELL_3D_LO];
    float s = s_hi + s_lo;
    float r2 = radius * radius;
    int seed[4], below[4];
    for (int l = 0; l < 4; ++l) {
        seed[l] = key[4 * k + l];
        below[l] = oriented_below[4 * k + l];
    }
    float orientation[3];
    for (int e = 0; e < 3; ++e)
        orientation[e] = octave[o + STOCHTEX_GABOR_ORIENTATION + e];
    float ixx = filter[3], ixy = filter[4], iyy = filter[5];
    // The support: the ellipsoid h^2 + p^T A^-1 p <= r^2; M = n n^T + T A^-1 T^T (texture axes).
    float extent[3];
    for (int e = 0; e < 3; ++e)
        extent[e] = radius * sqrt(n[e] * n[e] + stochtex_quadratic_form(filter[0], filter[1], filter[2], t[e], b[e]));
    float m[9];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            m[3 * r + c] = n[r] * n[c] + ixx * t[r] * t[c] + ixy * (t[r] * b[c] + b[r] * t[c]) + iyy * b[r] * b[c];
    float schur_min = stochtex_smallest_eigenvalue(m[4] - m[1] * m[1] / m[0], m[5] - m[1] * m[2] / m[0], m[8] - m[2] * m[2] / m[0]);
    float ky = -m[1] / m[0], kz = -m[2] / m[0];
    float sum[3] = { 0.0, 0.0, 0.0 };
    int k0 = int(floor((p[2] - extent[2]) / s)), k1 = int(floor((p[2] + extent[2]) / s));
    int j0 = int(floor((p[1] - extent[1]) / s)), j1 = int(floor((p[1] + extent[1]) / s));
    for (int kk = k0; kk <= k1; ++kk) {
        float cell_dz = (float(kk) * s_hi - p[2]) + float(kk) * s_lo;
        for (int j = j0; j <= j1; ++j) {
            float cell_dy = (float(j) * s_hi - p[1]) + float(j) * s_lo;
            // row_span_3d over d_y in [cell_dy, cell_dy + s], d_z in [cell_dz, cell_dz + s].
            float y0 = cell_dy, y1 = cell_dy + s, z0 = cell_dz, z1 = cell_dz + s;
            float ny = y0 > 0.0 ? y0 : (y1 < 0.0 ? y1 : 0.0), nz = z0 > 0.0 ? z0 : (z1 < 0.0 ? z1 : 0.0);
            float w2 = (r2 - schur_min * (ny * ny + nz * nz)) / m[0];
            if (w2 < 0.0)
                continue;
            float w = sqrt(w2);
            float c00 = ky * y0 + kz * z0, c01 = ky * y0 + kz * z1, c10 = ky * y1 + kz * z0, c11 = ky * y1 + kz * z1;
            float lo = min(min(c00, c01), min(c10, c11)) - w, hi = max(max(c00, c01), max(c10, c11)) + w;
            int i0 = int(floor((p[0] + lo) / s)), i1 = int(floor((p[0] + hi) / s));
            for (int i = i0; i <= i1; ++i) {
                float cell_dx = (float(i) * s_hi - p[0]) + float(i) * s_lo;
                int cell[4], bits[4];
                stochtex_gabor_cell_key(seed, 3, i, j, kk, cell);
                stochtex_mix64(cell, bits);
                float dx = -(cell_dx + stochtex_gabor_fraction(bits, 0) * s);
                float dy = -(cell_dy + stochtex_gabor_fraction(bits, 21) * s);
                float dz = -(cell_dz + stochtex_gabor_fraction(bits, 42) * s);
                float h = n[0] * dx + n[1] * dy + n[2] * dz;
                float pt = t[0] * dx + t[1] * dy + t[2] * dz, pb = b[0] * dx + b[1] * dy + b[2] * dz;
                float q = h * h + stochtex_quadratic_form(ixx, ixy, iyy, pt, pb);
                if (q <= r2) {
                    int attributes[4];
                    float omega[3];
                    stochtex_gabor_attributes(cell, attributes);
                    stochtex_gabor_frequency(kind, f, direction, direction_length, e1, e2, orientation, below, cell,
                                             attributes, omega);
                    float st = t[0] * omega[0] + t[1] * omega[1] + t[2] * omega[2];
                    float sb = b[0] * omega[0] + b[1] * omega[1] + b[2] * omega[2];
                    float wn = n[0] * omega[0] + n[1] * omega[1] + n[2] * omega[2];
                    stochtex_gabor_kernel(filter, a, q, pt, pb, h, st, sb, wn, attributes, channels, sum);
                }
            }
        }
    }
    float gain = octave[o + STOCHTEX_GABOR_GAIN_3D] * filter[9];
    for (int c = 0; c < 3; ++c)
        value[c] = sum[c] * gain;
}

// ---- The variance the filter keeps (gabor_statistics.cpp), for the histogram maps ------------

// e^-x I0(x), x >= 0 (Abramowitz & Stegun 9.8.1-2).
float stochtex_scaled_bessel_i0(float x_in)
{
    float x = abs(x_in);
    if (x < 3.75) {
        float t = (x / 3.75) * (x / 3.75);
        float i0 = 1.0 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813)))));
        return exp(-x) * i0;
    }
    float t = 3.75 / x;
    float p = 0.39894228 + t * (0.01328592 + t * (0.00225319 + t * (-0.00157565 + t * (0.00916281 + t * (-0.02057706 +
              t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))));
    return p / sqrt(x);
}

// Node (i, j) of the table, an n x n image (rows as the host runs them: stochtex_subset.h).
float stochtex_sphere_node(string table, float n, int rows_bottom_up, int i, int j)
{
    return texture(table, (float(i) + 0.5) / n, stochtex_row_t((float(j) + 0.5) / n, rows_bottom_up), "interp", "closest",
                   "width", 0.0);
}

// E over the unit sphere of exp(-alpha u1^2 - beta u2^2), interpolated bilinearly in the core's
// table (log(1 + alpha), log(1 + beta) on a grid of `size` nodes `step` apart).
float stochtex_sphere_average(string table, int size, float node_step, int rows_bottom_up, float alpha, float beta)
{
    float last = float(size - 1);
    float x = min(log(1.0 + max(0.0, alpha)) / node_step, last), y = min(log(1.0 + max(0.0, beta)) / node_step, last);
    int i = stochtex_min_int(int(x), size - 2), j = stochtex_min_int(int(y), size - 2);
    float fx = x - float(i), fy = y - float(j);
    float n = float(size);
    float v00 = stochtex_sphere_node(table, n, rows_bottom_up, i, j);
    float v10 = stochtex_sphere_node(table, n, rows_bottom_up, i + 1, j);
    float v01 = stochtex_sphere_node(table, n, rows_bottom_up, i, j + 1);
    float v11 = stochtex_sphere_node(table, n, rows_bottom_up, i + 1, j + 1);
    return (1.0 - fy) * ((1.0 - fx) * v00 + fx * v10) + fy * ((1.0 - fx) * v01 + fx * v11);
}

// gabor_retained_variance: the fraction of the octave's variance the filter keeps in the plane (t, b),
// for the isotropic, anisotropic (omega / F = direction) and hybrid kinds.
float stochtex_gabor_retained(float filter[STOCHTEX_GABOR_FILTER_SIZE], int kind, float f, float direction[3],
                              float e1[3], float e2[3], float t[3], float b[3], string table, int table_size,
                              float table_step, int rows_bottom_up)
{
    if (filter[10] > 0.0)
        return 1.0;
    float dxx = filter[6], dxy = filter[7], dyy = filter[8];
    if (kind == STOCHTEX_GABOR_ANISOTROPIC) {
        float st = f * (t[0] * direction[0] + t[1] * direction[1] + t[2] * direction[2]);
        float sb = f * (b[0] * direction[0] + b[1] * direction[1] + b[2] * direction[2]);
        return filter[9] * exp(-2.0 * stochtex_quadratic_form(dxx, dxy, dyy, st, sb));
    }
    if (kind == STOCHTEX_GABOR_HYBRID) {
        float u1t = f * (t[0] * e1[0] + t[1] * e1[1] + t[2] * e1[2]), u1b = f * (b[0] * e1[0] + b[1] * e1[1] + b[2] * e1[2]);
        float u2t = f * (t[0] * e2[0] + t[1] * e2[1] + t[2] * e2[2]), u2b = f * (b[0] * e2[0] + b[1] * e2[1] + b[2] * e2[2]);
        float m11 = 2.0 * stochtex_quadratic_form(dxx, dxy, dyy, u1t, u1b);
        float m22 = 2.0 * stochtex_quadratic_form(dxx, dxy, dyy, u2t, u2b);
        float m12 = 2.0 * (dxx * u1t * u2t + dxy * (u1t * u2b + u1b * u2t) + dyy * u1b * u2b);
        float c0 = 0.5 * (m11 + m22), r = sqrt(0.25 * (m11 - m22) * (m11 - m22) + m12 * m12);
        return filter[9] * exp(-(c0 - r)) * stochtex_scaled_bessel_i0(r);
    }
    float scale = 2.0 * f * f;
    return filter[9] * stochtex_sphere_average(table, table_size, table_step, rows_bottom_up,
                                               scale * stochtex_largest_eigenvalue(dxx, dxy, dyy),
                                               scale * max(0.0, stochtex_smallest_eigenvalue(dxx, dxy, dyy)));
}

// Kind oriented: its two populations of impulses mixed by their shares (gabor_statistics.cpp's
// mixed(): random phases leave no cross terms); the other kinds as stochtex_gabor_retained.
float stochtex_gabor_octave_retained(float filter[STOCHTEX_GABOR_FILTER_SIZE], int kind, float octave[], int o,
                                     float direction[3], float e1[3], float e2[3], float t[3], float b[3], string table,
                                     int table_size, float table_step, int rows_bottom_up)
{
    float f = octave[o + STOCHTEX_GABOR_FREQUENCY];
    if (kind != STOCHTEX_GABOR_ORIENTED)
        return stochtex_gabor_retained(filter, kind, f, direction, e1, e2, t, b, table, table_size, table_step,
                                       rows_bottom_up);
    float share = octave[o + STOCHTEX_GABOR_ORIENTED_SHARE];
    float orientation[3];
    for (int e = 0; e < 3; ++e)
        orientation[e] = octave[o + STOCHTEX_GABOR_ORIENTATION + e];
    float oriented = 0.0, isotropic = 0.0;
    if (share > 0.0)
        oriented = stochtex_gabor_retained(filter, STOCHTEX_GABOR_ANISOTROPIC, f, orientation, e1, e2, t, b, table,
                                           table_size, table_step, rows_bottom_up);
    if (share < 1.0)
        isotropic = stochtex_gabor_retained(filter, STOCHTEX_GABOR_ISOTROPIC, f, orientation, e1, e2, t, b, table,
                                            table_size, table_step, rows_bottom_up);
    return share * oriented + (1.0 - share) * isotropic;
}

// ---- The texture -----------------------------------------------------------------------------

// The texture at p (texture units; 2D: p[2] unused) with the footprint's derivatives dpdx, dpdy
// (texture units per pixel; 2D: (du, dv, 0)) and, solid, the surface normal nrm. Arrays are
// flattened: octave[k * STRIDE + field], key_2d/key_3d/oriented_below[4 k + limb], knots as in
// stochtex_colour.h; the table read with rows as the host runs them (stochtex_rows_bottom_up).
void stochtex_gabor(int solid, float p[3], float nrm[3], float dpdx[3], float dpdy[3], float pixels_per_unit,
                    int octave_count, float octave[], int key_2d[], int key_3d[], int oriented_below[], int kind, float direction[3],
                    float direction_length, float e1[3], float e2[3], int channels, float sigma_m[],
                    int knot_count[], float knot_z[], float knot_value[], float knot_slope[], float gh_node[],
                    float gh_weight[], int joint_count, float joint_first, float joint_inverse_step, float joint_curve[],
                    float mean[], float basis[], string sphere_table, int sphere_table_size,
                    float sphere_table_step, int rows_bottom_up, STOCHTEX_OUT(float) r, STOCHTEX_OUT(float) g, STOCHTEX_OUT(float) b)
{
    float t[3] = { 1.0, 0.0, 0.0 }, bt[3] = { 0.0, 1.0, 0.0 }, n[3] = { 0.0, 0.0, 1.0 };
    float dudx = dpdx[0], dvdx = dpdx[1], dudy = dpdy[0], dvdy = dpdy[1];
    if (solid) {
        // The frame of the surface point and the footprint in its tangent coordinates.
        stochtex_tangent_frame(nrm, dpdx, t, bt, n);
        dudx = t[0] * dpdx[0] + t[1] * dpdx[1] + t[2] * dpdx[2];
        dvdx = bt[0] * dpdx[0] + bt[1] * dpdx[1] + bt[2] * dpdx[2];
        dudy = t[0] * dpdy[0] + t[1] * dpdy[1] + t[2] * dpdy[2];
        dvdy = bt[0] * dpdy[0] + bt[1] * dpdy[1] + bt[2] * dpdy[2];
    }
    float sxx = 0.0, sxy = 0.0, syy = 0.0;
    stochtex_filter_covariance(dudx, dvdx, dudy, dvdy, pixels_per_unit, sxx, sxy, syy);
    stochtex_without_isotropic_blur(0.25, sxx, sxy, syy);  // the exemplar pixel's own blur, (1/2 px)^2
    float q[3];
    for (int e = 0; e < 3; ++e)
        q[e] = p[e] * pixels_per_unit;
    int tracks = knot_count[0] > 0 || knot_count[1] > 0 || knot_count[2] > 0;
    float kept[3] = { 0.0, 0.0, 0.0 }, dropped[3] = { 0.0, 0.0, 0.0 };
    for (int k = 0; k < octave_count; ++k) {
        int o = k * STOCHTEX_GABOR_STRIDE;
        float filter[STOCHTEX_GABOR_FILTER_SIZE];
        stochtex_gabor_filter(octave[o + STOCHTEX_GABOR_BANDWIDTH], sxx, sxy, syy, filter);
        float fade = stochtex_gabor_fade(1.0 / filter[9]);
        if (tracks) {
            float retained = 0.0;
            if (fade > 0.0)
                retained = fade * fade * stochtex_gabor_octave_retained(filter, kind, octave, o, direction, e1, e2, t, bt,
                                                                        sphere_table, sphere_table_size, sphere_table_step,
                                                                        rows_bottom_up);
            for (int c = 0; c < 3; ++c) {
                float w = octave[o + STOCHTEX_GABOR_WEIGHT + c];
                dropped[c] += (1.0 - retained) * w * w;
            }
        }
        if (fade == 0.0)
            continue;
        float value[3];
        if (solid)
            stochtex_gabor_noise_sliced(q, t, bt, n, filter, kind, octave, k, key_3d, oriented_below, direction,
                                        direction_length, e1, e2, channels, value);
        else
            stochtex_gabor_noise_2d(q[0], q[1], filter, kind, octave, k, key_2d, oriented_below, direction, direction_length,
                                    e1, e2, channels, value);
        for (int c = 0; c < 3; ++c)
            kept[c] += fade * octave[o + STOCHTEX_GABOR_WEIGHT + c] * value[channels == 1 ? 0 : c];
    }
    float y[3], z0 = 0.0, dropped0 = 0.0;
    for (int c = 0; c < 3; ++c) {
        float z = 0.0, spread = 0.0;
        if (sigma_m[c] > 0.0) {
            z = kept[c] / sigma_m[c];
            spread = sqrt(max(0.0, dropped[c])) / sigma_m[c];
        }
        y[c] = stochtex_channel_value(z, spread, c, sigma_m, knot_count, knot_z, knot_value, knot_slope, gh_node, gh_weight);
        if (c == 0) {
            z0 = z;
            dropped0 = spread;
        }
    }
    stochtex_colour_joint(y[0], y[1], y[2], z0, dropped0, joint_count, joint_first, joint_inverse_step, joint_curve,
                          gh_node, gh_weight, mean, basis, r, g, b);
}

#endif
