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

/// One window's contribution to a row of pixels. Term t of the window is
///   ca·P_c − sa·Q_c,  (ca, sa) = (cosine, sine)[t·stride + k] (its column factor at pixel k),
/// P_c = p[c · factor_plane(terms) + t], Q_c likewise (its row factors, row_factors()),, summed in sum_terms_separable's four partial sums; the window weight is
/// w = LrpWindowTable(rx2[k] + ry2) and, where w > 0 (as sum_windows skips the others),
///   sum_c[k] += w · local_c,  weight[k] += w,  weight_squared[k] += w · w.
struct WindowRow {
    const float* cosine = nullptr;
    const float* sine = nullptr;
    std::size_t stride = 0;
    const float* p = nullptr;
    const float* q = nullptr;
    int terms = 0;  ///< the window's live terms (LrpTermView::live); 0: weights only
    const float* rx2 = nullptr;  ///< (dx / spacing)² per pixel; > 2.25 past the window (w = 0)
    float ry2 = 0;
    std::size_t count = 0;
    float* sum[3] = {nullptr, nullptr, nullptr};
    float* weight = nullptr;
    float* weight_squared = nullptr;
};
void accumulate_window_row(const WindowRow& row);

/// sum_terms (the direct form: sin/cos of fx·dx + fy·dy, four partial sums t mod 4) at each of
/// `count` points (dx[k], dy[k]) of one set of terms: out[c][k]. Reads and writes up to the
/// padding past `count`.
void sum_terms_at(const LrpTermView& terms, const float* dx, const float* dy, std::size_t count, float* const out[3]);

}  // namespace stochtex::lrp_raster
