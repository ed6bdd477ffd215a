// stochtex - the tiling model's synthesis in OSL (docs/osl.md).
//
// A transcription of the core's TilingTexture::eval (core/src/models/tiling/) with the numbers
// of core/include/stochtex/models/tiling_shader_data.h:
//   - the triangle grid and its blend weights w = B / |B| (blending/tiling_grid.cpp), each
//     vertex's random offset drawn as the core draws it (mix_seed, then two SplitMix64
//     uniforms: 64-bit arithmetic in 16-bit limbs, stochtex_u64.h) and its whole-pixel tile
//     shift rounded from exact parts (so float rounding cannot pick a neighbouring pixel);
//   - the moment pyramid (moment_pyramid.h): every level's means and centred second moments in
//     one atlas image (level l below level l - 1), read with closest-texel texture() lookups and
//     interpolated here as the core does (bilinear between texel centres with wrap, linear
//     between levels), so the exemplar texels are the core's floats;
//   - the footprint estimator (tiling_noise.cpp): taps over the footprint's parallelogram at the
//     level of their spacing, combined by the law of total variance;
//   - the output: colour (histogram-preserving blend: Gauss-Hermite over each channel's
//     spread, then the colour basis, stochtex_colour.h) or a normal map (the mean slopes'
//     normal). The colour_map output has no transcription (its pre-blurred table).
//
// Common subset of OSL and C++ (see stochtex_wavelet.h); tests/osl_tiling_test.cpp compiles it.
#ifndef STOCHTEX_TILING_H
#define STOCHTEX_TILING_H

#include "stochtex_subset.h"

#include "stochtex_colour.h"
#include "stochtex_u64.h"

#define STOCHTEX_TILING_COLOUR 0
#define STOCHTEX_TILING_NORMAL_MAP 2
// Moments: mean[3], then the centred second moments packed as (0,0) (0,1) (0,2) (1,1) (1,2) (2,2).
#define STOCHTEX_TILING_MOMENTS 9
// The moment planes per row (and rows) of the atlas image: 3 x 3 (stochtex_tiling_texel).
#define STOCHTEX_TILING_GRID 3

// The vertex (i, j)'s offset into the exemplar, as the 48 leading bits of the core's 53-bit
// uniforms: offset = hi / 2^24 + lo / 2^48 (TilingGrid::draw: SplitMix64(mix_seed(seed, i, j))).
void stochtex_tiling_offset(int seed[4], int i, int j, STOCHTEX_OUT_ARRAY(int) hi[2], STOCHTEX_OUT_ARRAY(int) lo[2])
{
    int c1[4] = { 31765, 32586, 31161, 40503 };  // 0x9e3779b97f4a7c15
    int c2[4] = { 57369, 55732, 58779, 25387 };  // 0x632be59bd9b4e019
    int c3[4] = { 64915, 26201, 65208, 55016 };  // 0xd6e8feb86659fd93
    int a[4], b[4], c[4], state[4], z[4];
    // mix_seed: SplitMix64(seed * c1 ^ (i + c2) ^ (j * c3)).next()
    stochtex_u64_mul(seed, c1, a);
    stochtex_u64_from_int(i, b);
    stochtex_u64_add(b, c2, b);
    stochtex_u64_from_int(j, c);
    stochtex_u64_mul(c, c3, c);
    stochtex_u64_xor(a, b, state);
    stochtex_u64_xor(state, c, state);
    stochtex_splitmix_next(state, z);
    stochtex_u64_copy(z, state);
    for (int k = 0; k < 2; ++k) {
        stochtex_splitmix_next(state, z);
        hi[k] = stochtex_u64_bits(z, 40, 24);
        lo[k] = stochtex_u64_bits(z, 16, 24);
    }
}

// round(offset * size - centre), centre = (centre_hi + centre_lo) * m with centre_hi of at most
// 12 significant bits and |2 m| < 4096, size = 2^size_log2 <= 2^24: tile_position's shift, from
// parts each exact in float (integer parts apart), so the rounding is the core's.
float stochtex_tiling_shift(int offset_hi, int offset_lo, int size_log2, float centre_hi, float centre_lo, float m)
{
    int unit = 1 << (24 - size_log2);
    float size = float(1 << size_log2);
    float a_int = float(offset_hi / unit);
    float a_frac = float(offset_hi % unit) / float(unit) + float(offset_lo) * size / 281474976710656.0;
    float b = centre_hi * m;  // exact
    float b_int = floor(b);
    return a_int - b_int + round(a_frac - (b - b_int) - centre_lo * m);
}

// One texel's moments from the atlas (level at row offset level_y, size level_w x level_h; rows
// as the host runs them: stochtex_subset.h). The atlas image holds the 9 moment planes, each
// atlas_w x atlas_h, as a 3 x 3 grid of one channel (plane k at column k % 3, row k / 3), not as
// 9 channels: Cycles 5.2 ignores the firstchannel option (a float lookup there returns the
// file's first channel whatever it asks for); a single-channel texel reads the same everywhere.
void stochtex_tiling_texel(string atlas, int atlas_w, int atlas_h, int rows_bottom_up, int level_y, int x, int y,
                           STOCHTEX_OUT_ARRAY(float) texel[STOCHTEX_TILING_MOMENTS])
{
    float grid_w = float(STOCHTEX_TILING_GRID * atlas_w), grid_h = float(STOCHTEX_TILING_GRID * atlas_h);
    for (int k = 0; k < STOCHTEX_TILING_MOMENTS; ++k) {
        float s = (float(x + atlas_w * (k % STOCHTEX_TILING_GRID)) + 0.5) / grid_w;
        float t = (float(level_y + y + atlas_h * (k / STOCHTEX_TILING_GRID)) + 0.5) / grid_h;
        texel[k] = texture(atlas, s, stochtex_row_t(t, rows_bottom_up), "interp", "closest", "width", 0.0);
    }
}

int stochtex_tiling_wrap(int i, int n)
{
    return ((i % n) + n) % n;
}

// MomentPyramid::sample_level (linear): bilinear between texel centres, with wrap.
void stochtex_tiling_sample_level(string atlas, int width, int height, int atlas_h, int rows_bottom_up, int level, float x,
                                  float y, STOCHTEX_OUT_ARRAY(float) result[STOCHTEX_TILING_MOMENTS])
{
    int level_y = 0;
    for (int l = 0; l < level; ++l)
        level_y += stochtex_max_int(1, height >> l);
    int lw = stochtex_max_int(1, width >> level), lh = stochtex_max_int(1, height >> level);
    float lx = x * float(lw) / float(width) - 0.5, ly = y * float(lh) / float(height) - 0.5;
    float x0 = floor(lx), y0 = floor(ly);
    float tx = lx - x0, ty = ly - y0;
    int ix = stochtex_tiling_wrap(int(x0), lw), iy = stochtex_tiling_wrap(int(y0), lh);
    int jx = ix + 1 == lw ? 0 : ix + 1, jy = iy + 1 == lh ? 0 : iy + 1;
    float weights[4];
    weights[0] = (1.0 - tx) * (1.0 - ty);
    weights[1] = tx * (1.0 - ty);
    weights[2] = (1.0 - tx) * ty;
    weights[3] = tx * ty;
    for (int k = 0; k < STOCHTEX_TILING_MOMENTS; ++k)
        result[k] = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
        float w = weights[corner];
        if (w == 0.0)
            continue;
        float texel[STOCHTEX_TILING_MOMENTS];
        stochtex_tiling_texel(atlas, width, atlas_h, rows_bottom_up, level_y, corner % 2 == 0 ? ix : jx,
                              corner < 2 ? iy : jy, texel);
        for (int k = 0; k < STOCHTEX_TILING_MOMENTS; ++k)
            result[k] += w * texel[k];
    }
}

// MomentPyramid::sample (linear): levels clamped, interpolated linearly.
void stochtex_tiling_sample(string atlas, int width, int height, int atlas_h, int rows_bottom_up, int level_count,
                            float level_in, float x, float y, STOCHTEX_OUT_ARRAY(float) result[STOCHTEX_TILING_MOMENTS])
{
    float level = clamp(level_in, 0.0, float(level_count - 1));
    int lower = stochtex_min_int(int(level), level_count - 1);
    float t = level - float(lower);
    stochtex_tiling_sample_level(atlas, width, height, atlas_h, rows_bottom_up, lower, x, y, result);
    if (t == 0.0)
        return;
    float upper[STOCHTEX_TILING_MOMENTS];
    stochtex_tiling_sample_level(atlas, width, height, atlas_h, rows_bottom_up, lower + 1, x, y, upper);
    for (int k = 0; k < STOCHTEX_TILING_MOMENTS; ++k)
        result[k] += t * (upper[k] - result[k]);
}

// TilingNoise::texel_estimate at (x, y) exemplar pixels: the blend of the three tiles.
void stochtex_tiling_texel_estimate(float x, float y, float level, string atlas, int width, int height, int size_log2_x,
                                    int size_log2_y, int atlas_h, int rows_bottom_up, int level_count, int seed[4],
                                    float edge_x, float edge_y, float centre_x_hi, float centre_x_lo, float centre_y_hi,
                                    float centre_y_lo, float global_mean[3], STOCHTEX_OUT_ARRAY(float) result[STOCHTEX_TILING_MOMENTS])
{
    // TilingGrid::blend: skew to the lattice basis (1, 0), (1/2, sqrt(3)/2).
    float sqrt3 = sqrt(3.0);
    float gx = x / edge_x, gy = y / edge_y;
    float sy = 2.0 * gy / sqrt3, sx = gx - 0.5 * sy;
    float cx = floor(sx), cy = floor(sy);
    float fx = sx - cx, fy = sy - cy;
    int i = int(cx), j = int(cy);
    int vi[3], vj[3];
    float bary[3];
    if (fx + fy < 1.0) {
        vi[0] = i;
        vj[0] = j;
        vi[1] = i + 1;
        vj[1] = j;
        vi[2] = i;
        vj[2] = j + 1;
        bary[0] = 1.0 - fx - fy;
        bary[1] = fx;
        bary[2] = fy;
    } else {
        vi[0] = i + 1;
        vj[0] = j + 1;
        vi[1] = i + 1;
        vj[1] = j;
        vi[2] = i;
        vj[2] = j + 1;
        bary[0] = fx + fy - 1.0;
        bary[1] = 1.0 - fy;
        bary[2] = 1.0 - fx;
    }
    float norm = sqrt(bary[0] * bary[0] + bary[1] * bary[1] + bary[2] * bary[2]);
    for (int k = 0; k < STOCHTEX_TILING_MOMENTS; ++k)
        result[k] = k < 3 ? global_mean[k] : 0.0;
    for (int v = 0; v < 3; ++v) {
        float w = bary[v] / norm;
        if (w == 0.0)
            continue;
        int hi[2], lo[2];
        stochtex_tiling_offset(seed, vi[v], vj[v], hi, lo);
        // tile_position: the vertex's centre is edge_x (vi + vj / 2), edge_y (sqrt(3) / 2) vj.
        float shift_x = stochtex_tiling_shift(hi[0], lo[0], size_log2_x, centre_x_hi, centre_x_lo,
                                              float(vi[v]) + 0.5 * float(vj[v]));
        float shift_y = stochtex_tiling_shift(hi[1], lo[1], size_log2_y, centre_y_hi, centre_y_lo, float(vj[v]));
        float tile[STOCHTEX_TILING_MOMENTS];
        stochtex_tiling_sample(atlas, width, height, atlas_h, rows_bottom_up, level_count, level, x + shift_x, y + shift_y,
                               tile);
        for (int k = 0; k < STOCHTEX_TILING_MOMENTS; ++k)
            result[k] += k < 3 ? w * (tile[k] - global_mean[k]) : w * w * tile[k];
    }
}

// MomentMixture::add: the weighted union's moments, Welford's update (law of total variance).
void stochtex_tiling_mixture_add(float weight, float part[STOCHTEX_TILING_MOMENTS], STOCHTEX_OUT(float) total_weight,
                                 STOCHTEX_OUT_ARRAY(float) total[STOCHTEX_TILING_MOMENTS])
{
    int pa[6] = { 0, 0, 0, 1, 1, 2 };
    int pb[6] = { 0, 1, 2, 1, 2, 2 };
    float sum = total_weight + weight;
    float delta[3];
    for (int a = 0; a < 3; ++a)
        delta[a] = part[a] - total[a];
    float scatter = total_weight * weight / sum;
    for (int a = 0; a < 3; ++a)
        total[a] += weight / sum * delta[a];
    for (int p = 0; p < 6; ++p)
        total[3 + p] += weight * part[3 + p] + scatter * delta[pa[p]] * delta[pb[p]];
    total_weight = sum;
}

// TilingNoise::footprint_estimate: the footprint's columns (dudx, dvdx), (dudy, dvdy) in exemplar pixels.
void stochtex_tiling_footprint_estimate(float x, float y, float dudx, float dvdx, float dudy, float dvdy, int taps,
                                        int max_taps, string atlas, int width, int height, int size_log2_x,
                                        int size_log2_y, int atlas_h, int rows_bottom_up, int level_count, int seed[4],
                                        float edge_x, float edge_y, float centre_x_hi, float centre_x_lo,
                                        float centre_y_hi, float centre_y_lo, float global_mean[3],
                                        STOCHTEX_OUT_ARRAY(float) result[STOCHTEX_TILING_MOMENTS])
{
    float length_a = hypot(dudx, dvdx), length_b = hypot(dudy, dvdy);
    float minor = max(1e-12, min(length_a, length_b));
    int counts[2];
    for (int axis = 0; axis < 2; ++axis) {
        float norm_length = axis == 0 ? length_a : length_b;
        counts[axis] = 1;
        if (norm_length > 1.0)
            counts[axis] = stochtex_min_int(stochtex_max_int(int(round(float(taps) * norm_length / max(minor, 1.0))), stochtex_max_int(1, taps)),
                                            stochtex_max_int(taps, max_taps));
    }
    int na = counts[0], nb = counts[1];
    float piece = max(length_a / float(na), length_b / float(nb));
    float level = piece > 1.0 ? log2(piece) : 0.0;
    if (na == 1 && nb == 1) {
        stochtex_tiling_texel_estimate(x, y, level, atlas, width, height, size_log2_x, size_log2_y, atlas_h,
                                       rows_bottom_up, level_count, seed, edge_x, edge_y, centre_x_hi, centre_x_lo,
                                       centre_y_hi, centre_y_lo, global_mean, result);
        return;
    }
    float total_weight = 0.0;
    for (int k = 0; k < STOCHTEX_TILING_MOMENTS; ++k)
        result[k] = 0.0;
    float weight = 1.0 / float(na * nb);
    for (int tj = 0; tj < nb; ++tj) {
        for (int ti = 0; ti < na; ++ti) {
            float s = (float(ti) + 0.5) / float(na) - 0.5, t = (float(tj) + 0.5) / float(nb) - 0.5;
            float tap[STOCHTEX_TILING_MOMENTS];
            stochtex_tiling_texel_estimate(x + s * dudx + t * dudy, y + s * dvdx + t * dvdy, level, atlas, width, height,
                                           size_log2_x, size_log2_y, atlas_h, rows_bottom_up, level_count, seed, edge_x,
                                           edge_y, centre_x_hi, centre_x_lo, centre_y_hi, centre_y_lo, global_mean, tap);
            stochtex_tiling_mixture_add(weight, tap, total_weight, result);
        }
    }
    for (int k = 3; k < STOCHTEX_TILING_MOMENTS; ++k)
        result[k] /= total_weight;
}

// The texture at (u, v) (texture units) with the footprint (dudx, dvdx), (dudy, dvdy) (texture
// units per pixel); the atlas read with rows as the host runs them (stochtex_rows_bottom_up).
void stochtex_tiling(float tex_u, float tex_v, float dudx, float dvdx, float dudy, float dvdy, float pixels_per_unit,
                     int output_kind, int taps, int max_taps, string atlas, int width, int height, int atlas_h,
                     int rows_bottom_up, int level_count, int seed[4], float edge_x, float edge_y, float centre_x_hi,
                     float centre_x_lo, float centre_y_hi, float centre_y_lo, float global_mean[3], int knot_count[], float knot_z[],
                     float knot_value[], float knot_slope[], float gh_node[], float gh_weight[], float mean[],
                     float basis[], STOCHTEX_OUT(float) r, STOCHTEX_OUT(float) g, STOCHTEX_OUT(float) b)
{
    int size_log2_x = int(round(log2(float(width)))), size_log2_y = int(round(log2(float(height))));
    float m[STOCHTEX_TILING_MOMENTS];
    float ppu = pixels_per_unit;
    stochtex_tiling_footprint_estimate(tex_u * ppu, tex_v * ppu, dudx * ppu, dvdx * ppu, dudy * ppu, dvdy * ppu, taps, max_taps,
                                       atlas, width, height, size_log2_x, size_log2_y, atlas_h, rows_bottom_up, level_count,
                                       seed, edge_x, edge_y, centre_x_hi, centre_x_lo, centre_y_hi, centre_y_lo, global_mean, m);
    if (output_kind == STOCHTEX_TILING_NORMAL_MAP) {
        // normal_from_slopes: (-sx, -sy, 1) normalised, encoded n / 2 + 1/2.
        float norm_length = sqrt(m[0] * m[0] + m[1] * m[1] + 1.0);
        r = 0.5 + 0.5 * (-m[0] / norm_length);
        g = 0.5 + 0.5 * (-m[1] / norm_length);
        b = 0.5 + 0.5 * (1.0 / norm_length);
        return;
    }
    // The exemplar holds each channel in its map's input units: sigma_m = 1.
    float unit[3] = { 1.0, 1.0, 1.0 };
    int diagonal[3] = { 3, 6, 8 };
    float y[3];
    for (int c = 0; c < 3; ++c)
        y[c] = stochtex_channel_value(m[c], sqrt(max(0.0, m[diagonal[c]])), c, unit, knot_count, knot_z, knot_value,
                                      knot_slope, gh_node, gh_weight);
    stochtex_colour_basis(y[0], y[1], y[2], mean, basis, r, g, b);
}

#endif
