// Random-phase Gabor noise (paper 001, eq. 7) by sparse convolution, in 2D and as a solid sliced
// by the surface's tangent plane and filtered there analytically (eqs. 6, 10, 11).
//
//   n(x) = Σ_i g(x − x_i; a, ω_i, φ_i)      (gabor_kernel.h), no random weights
//
// Impulses. The impulse density λ is set by the impulses per kernel N: N = λ·(volume of the ball
// of the support radius r, where the Gaussian envelope falls to 5 %, Lagae et al. 2009). Space is
// cut into cells of volume 1/λ holding one impulse each at a uniform random position: a jittered
// grid rather than the paper's Poisson process. With random phases every cross term between
// kernels vanishes whatever their positions, so the noise's variance, correlation and PSD are
// exactly the Poisson process's; what changes is that no cell is empty or crowded (the noise is,
// if anything, closer to Gaussian), and that a cell costs one hash and no Poisson draw — half the
// candidates of Poisson cells of side r. Each cell's words are a hash of its index and the seed:
// a pure function of the cell, so evaluation is random-access, thread-safe and deterministic.
//
// Channels. One evaluation returns up to three noises that share impulse positions and
// frequencies but have independent phases: they are uncorrelated (E[cos(θ+φ₁)cos(θ+φ₂)] = 0), each
// has the exact single-channel statistics, and three cost little more than one.
//
// The 2D noise. Sliced by a plane, solid RPGN is in distribution a 2D RPGN whose frequencies are
// the projections ω^s of the solid ones (paper eq. 8). The 2D noise (eval_2d) draws exactly those
// projected frequencies (projection on the (u, v) plane), so a 2D render has the statistics of a
// w = const slice of the solid texture — and one by-example fit serves both — at the cost of a 2D
// sum (about half the candidate cells of a solid evaluation).
//
// Normalisation. Values are divided by the analytic standard deviation of the unfiltered noise,
// including the 5 % truncation, so unfiltered noise has unit variance; filtered noise has the
// variance gabor_statistics.h predicts (< 1).
#pragma once

#include "models/gabor/gabor_kernel.h"

#include <stochtex/texture_description.h>
#include <stochtex/models/gabor_parameters.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace stochtex {

struct GaborNoiseParameters {
    GaborKind kind = GaborKind::isotropic;
    double frequency = 1;  ///< F = |ω|, cycles per noise unit
    double bandwidth = 1;  ///< a, per noise unit (the envelope is exp(−π a² |x|²))
    Vec3 direction{0, 0, 1};  ///< anisotropic, oriented: ω / F; hybrid: normal of the plane of ω
    /// Oriented kind: the fraction of the impulses with ω = F·direction; the others are isotropic.
    double oriented_fraction = 0;
    double impulses_per_kernel = 16;
    std::uint64_t seed = 1;
    int channels = 3;  ///< 1 or 3 independent phase sets
    /// Periodic 2D noise: eval_2d repeats with this period (noise units) when both are > 0. The
    /// cells are stretched so that a whole number of them fits the period (at least 2 per axis).
    Vec2 period{0, 0};
};

class GaborNoise {
public:
    static constexpr int max_channels = 3;

    /// Throws std::invalid_argument for parameters outside their domain (and for a period
    /// shorter than two kernel radii: such a noise would overlap its own copies).
    explicit GaborNoise(const GaborNoiseParameters& parameters);

    /// The 2D noise at (x, y), filtered (`filter` built with this noise's bandwidth).
    void eval_2d(double x, double y, const GaborFilter& filter, float out[max_channels]) const;
    /// The solid noise sliced by the plane through p normal to frame.n, filtered in that plane.
    /// Unfiltered (identity filter), it equals the solid noise at p for any frame (eq. 6).
    void eval_sliced(const Vec3& p, const TangentFrame& frame, const GaborFilter& filter, float out[max_channels]) const;

    /// eval_2d at every point (x[i], y[j]) of a grid, i < nx, j < ny: channel c of the point goes
    /// to out[c][j·nx + i] (c < channels). Rows of points share the cells they reach and are
    /// summed in vectors (gabor_raster_kernels.h); the point methods are this with one point, so
    /// the values are bit-identical to eval_2d's.
    void eval_2d_grid(const double* x, std::size_t nx, const double* y, std::size_t ny, const GaborFilter& filter,
                      float* const out[max_channels]) const;
    /// eval_sliced at every point (x[i], y[j], z) of a grid, all with one frame and filter.
    void eval_sliced_grid(const double* x, std::size_t nx, const double* y, std::size_t ny, double z,
                          const TangentFrame& frame, const GaborFilter& filter, float* const out[max_channels]) const;

    /// Plain double-precision kernel sums with std::exp and std::cos (no slicing, no filter), over
    /// the same impulses: the reference the fast paths are tested and benchmarked against.
    double reference_2d(double x, double y, int channel) const;
    double reference_3d(const Vec3& p, int channel) const;

    /// One impulse: position, frequency and per-channel phases.
    struct Impulse {
        Vec3 position;  ///< position[2] = 0 for the 2D noise
        Vec3 omega;     ///< for the 2D noise: the projected frequency (omega[2] = 0)
        std::array<double, max_channels> phase;
    };
    /// Every impulse of the cells within `reach` of p along each axis (0: the support radius,
    /// which every kernel that can reach p is within unfiltered), in a fixed order.
    std::vector<Impulse> impulses_near_3d(const Vec3& p, double reach = 0) const;
    std::vector<Impulse> impulses_near_2d(double x, double y, double reach = 0) const;

    const GaborNoiseParameters& parameters() const { return parameters_; }
    /// Support radius r: the envelope exp(−π a² r²) = 5 %.
    double radius() const { return radius_; }
    static double support_radius(double bandwidth);
    /// Cell sides: one impulse per cell (2D: cell_size_2d[0] × [1]).
    std::array<double, 2> cell_size_2d() const { return {cell_x_, cell_y_}; }
    double cell_size_3d() const { return cell_3d_; }
    /// For re-implementations of the noise (gabor_shader_data.h): the mixed seeds of the 2D and
    /// solid cell keys, the gains (1 / σ of the raw sums), the hybrid kind's frequency plane.
    std::uint64_t key_2d() const { return key_2d_; }
    std::uint64_t key_3d() const { return key_3d_; }
    double gain_2d() const { return gain_2d_; }
    double gain_3d() const { return gain_3d_; }
    const Vec3& plane_e1() const { return plane_e1_; }
    const Vec3& plane_e2() const { return plane_e2_; }
    /// Oriented kind: an impulse is oriented when its 53-bit draw is below this (p·2^53); else 0.
    std::uint64_t oriented_bound() const { return oriented_below_; }

private:
    template <bool Solid>
    class GridEvaluation;  // eval_grid's steps (gabor_noise.cpp)
    template <bool Solid>
    void eval_grid(const double* x, std::size_t nx, const double* y, std::size_t ny, double z, const TangentFrame& frame,
                   const GaborFilter& filter, float* const out[max_channels]) const;

    std::uint64_t cell_key_2d(std::int64_t i, std::int64_t j) const;
    std::uint64_t cell_key_3d(std::int64_t i, std::int64_t j, std::int64_t k) const;
    /// ω of an impulse (3D) of cell `key` from its attribute bits.
    Vec3 frequency_of(std::uint64_t key, std::uint64_t attributes) const;

    GaborNoiseParameters parameters_;
    std::uint64_t key_2d_ = 0, key_3d_ = 0;  // the seed, mixed
    double radius_ = 0;
    double cell_x_ = 0, cell_y_ = 0;  // 2D cell sides (stretched to fit the period when periodic)
    std::int64_t wrap_x_ = 0, wrap_y_ = 0;  // periodic 2D: cells per period, else 0
    double cell_3d_ = 0;
    double gain_2d_ = 1, gain_3d_ = 1;  // 1 / σ of the raw sums
    Vec3 omega_{0, 0, 0};               // anisotropic and oriented ω
    std::uint64_t oriented_below_ = 0;  // oriented kind: an impulse is oriented if its draw is below this
    Vec3 plane_e1_{1, 0, 0}, plane_e2_{0, 1, 0};  // hybrid: orthonormal basis of the plane of ω
};

}  // namespace stochtex
