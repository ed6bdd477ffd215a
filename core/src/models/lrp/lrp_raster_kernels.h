// The lrp raster's inner loops, vectorised with Highway (lrp_raster_kernels.cpp, dispatched to
// the best instruction set of the CPU at run time). Pixels are the lanes.
//
// Each kernel performs, lane by lane, exactly the IEEE operations of the scalar code it stands
// for (fast_sincos_turns, sum_terms_separable, sum_windows, sum_terms), in the same order and
// without fused multiply-add (the core builds with -ffp-contract=off), so the raster is
// bit-identical to LrpStratumNoise::eval and LrpStructureNoise::eval on every target, at any
// vector width.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stochtex {
struct LrpTermView;
}

namespace stochtex::lrp_raster {

/// How many floats past `count` the kernels may read and write (callers pad their buffers).
constexpr std::size_t padding = 16;

/// sine[k], cosine[k] = fast_sincos_turns(a · b[k]) for k < count (writes up to the padding).
void sincos_of_products(float a, const float* b, std::size_t count, float* sine, float* cosine);

/// Planes of row factors: channel c's factor of term t is p[c · factor_plane(terms) + t].
constexpr std::size_t factor_plane(int terms) { return (std::size_t(terms) + padding - 1) / padding * padding; }

/// A window's row factors at row offset dy: with (sb, cb) = fast_sincos_turns(fy[t] · dy),
/// p = re·cb − im·sb and q = re·sb + im·cb (sum_terms_separable), in planes (factor_plane).
/// Reads up to the padding past `terms` of fy, re and im.
void row_factors(float dy, const float* fy, const float* const re[3], const float* const im[3], int terms, float* p,
                 float* q);

/// One window's terms in a WindowRow: term t is ca·P_c − sa·Q_c, (ca, sa) = (cosine, sine)[t·stride
/// + k] (its column factor at pixel k), P_c = p[c · factor_plane(terms) + t], Q_c likewise (its row
/// factors, row_factors()), summed in sum_terms_separable's running sum per channel into `local`;
/// then sum_c[k] += w · local_c.
struct WindowTerms {
    const float* cosine = nullptr;
    const float* sine = nullptr;
    std::size_t stride = 0;
    const float* p = nullptr;
    const float* q = nullptr;
    int terms = 0;     ///< the window's live terms (LrpTermView::live); 0: nothing to add
    int channels = 3;  ///< 1: only channel 0 (the others' terms are 0: their sums stay +0)
    float* sum[3] = {nullptr, nullptr, nullptr};
};

/// Strata whose windows are the same (one lattice, one normalisation) share a WindowRow: the
/// weights are computed once for all of them.
constexpr int max_layers = 3;

/// One window's contribution to a row of pixels, for each of `layers` strata that share the
/// window (WindowTerms). The window weight is w = LrpWindowTable(rx2[k] + ry2) and, where w > 0
/// (as sum_windows skips the others), each layer's sums get w · local and
///   weight[k] += w,  weight_squared[k] += w · w.
struct WindowRow {
    WindowTerms layer[max_layers];
    int layers = 1;
    const float* rx2 = nullptr;  ///< (dx / spacing)² per pixel; > 2.25 past the window (w = 0)
    float ry2 = 0;
    std::size_t count = 0;
    float* weight = nullptr;
    float* weight_squared = nullptr;
};
void accumulate_window_row(const WindowRow& row);

/// LrpNormalisation, for the kernels.
enum class Normalisation { variance, partition, none };

/// sine[k], cosine[k] = fast_sincos_turns(a[index[k] + offset] · b[k]) for k < count: a column
/// table whose lanes belong to different windows (writes up to the padding, reads index and b
/// as far).
void gathered_sincos(const float* a, const std::int32_t* index, std::int32_t offset, const float* b, std::size_t count,
                     float* sine, float* cosine);

/// One pixel row of the lattice-row raster (lrp_raster.cpp): pixel k's windows are the 3×3
/// around its nearest lattice point, lattice rows dj = 0, 1, 2 (the nearest row − 1, + 0, + 1)
/// and in each the windows window[k] + dix − 1 (dix = 0, 1, 2), in that order (sum_windows').
/// Per lattice row dj: whether its windows reach the pixel row at all (ry2 < 2.25), ry2, the
/// column tables cosine[dj], sine[dj] at [(dix · terms + t) · stride + k], and the row factors
/// p[dj], q[dj] of window w's term t in channel c at [c · plane[dj] + t · windows + w] (terms[dj]
/// of them, zero past a window's own). rx2 of slot
/// dix at [dix · stride + k]. out[c][k] = sum_windows' normalised value, bit for bit. Reads
/// window, rx2 and the tables up to the padding past `count` (window repeats its last value
/// there, rx2 holds 4.5) and the factors up to the padding past each window.
struct PixelRow {
    std::size_t count = 0;
    int terms[3] = {0, 0, 0};  ///< per lattice row dj: the most live terms of its windows
    const std::int32_t* window = nullptr;
    const float* rx2 = nullptr;
    std::size_t stride = 0;
    bool reaches[3] = {false, false, false};
    float ry2[3] = {0, 0, 0};
    const float* cosine[3] = {nullptr, nullptr, nullptr};
    const float* sine[3] = {nullptr, nullptr, nullptr};
    const float* p[3] = {nullptr, nullptr, nullptr};
    const float* q[3] = {nullptr, nullptr, nullptr};
    std::size_t plane[3] = {0, 0, 0}, windows = 0;
    Normalisation normalisation = Normalisation::variance;
    bool add = false;  ///< out[c][k] + value instead of value
    float* out[3] = {nullptr, nullptr, nullptr};
};
void accumulate_pixel_row(const PixelRow& row);

/// sum_windows' normalisation of `rows` rows of `width` sums: out[c][r · width + k] =
/// sum[c][r · stride + k] · scale, scale = 1/√weight_squared, 1/weight or 1 (with `add`, out +
/// that), for the channels whose out[c] is not null. Reads the sums up to the padding past each row.
void normalise(const float* const sum[3], const float* weight, const float* weight_squared, std::size_t stride,
               std::size_t width, int rows, Normalisation normalisation, bool add, float* const out[3]);

/// sum_terms (the direct form: sin/cos of fx·dx + fy·dy, four partial sums t mod 4) at each of
/// `count` points (dx[k], dy[k]) of one set of terms: out[c][k]. Reads and writes up to the
/// padding past `count`.
void sum_terms_at(const LrpTermView& terms, const float* dx, const float* dy, std::size_t count, float* const out[3]);

}  // namespace stochtex::lrp_raster
