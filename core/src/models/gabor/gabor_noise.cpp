#include "models/gabor/gabor_noise.h"
#include <stochtex/models/gabor_parameters.h>

#include "models/gabor/gabor_raster_kernels.h"
#include "numerics/constants.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stochtex {

namespace {

/// Support radius: where the envelope exp(−π a² r²) falls to this (Lagae et al. 2009).
constexpr double envelope_cutoff = 0.05;

// Phases are drawn from 1024 equally spaced values: for any M ≥ 3 equally spaced phases
// E[cos(θ + φ) cos(θ' + φ)] = ½ cos(θ − θ') exactly, so the noise's second-order statistics are
// those of uniform phases, and a table replaces two trigonometric calls per impulse.
constexpr int phase_bits = 10;
constexpr int phase_count = 1 << phase_bits;

struct PhaseTable {
    float cosine[phase_count], sine[phase_count];
    PhaseTable()
    {
        for (int k = 0; k < phase_count; ++k) {
            cosine[k] = float(std::cos(2 * kPi * k / phase_count));
            sine[k] = float(std::sin(2 * kPi * k / phase_count));
        }
    }
};
const PhaseTable phase_table;

double phase_angle(int index) { return 2 * kPi * index / phase_count; }

/// SplitMix64's output function: a strong 64-bit mixer (Steele et al. 2014).
inline std::uint64_t mix64(std::uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// Cell-relative position of an impulse: 21 bits per axis, at the centre of its sub-cell. (Through
/// a 32-bit integer: converting those is cheaper than 64-bit ones.)
inline double position_fraction(std::uint64_t bits) { return (std::int32_t(bits & 0x1fffff) + 0.5) * 0x1.0p-21; }

/// Attribute word layout: channel phases in bits 0–29, azimuth index in 30–39, cos(colatitude) in 40–63.
inline int phase_index(std::uint64_t attributes, int channel) { return int((attributes >> (phase_bits * channel)) & (phase_count - 1)); }

/// floor(x) as an integer, for |x| < 2^63: truncation, one less below zero off the integers
/// (std::floor is a library call on baseline x86-64, a few of them per row of cells).
inline std::int64_t floor_index(double x)
{
    const std::int64_t t = std::int64_t(x);
    return t - std::int64_t(x < double(t));
}

/// P(χ² with 3 degrees of freedom ≤ x): the energy fraction of a 3D Gaussian inside a sphere.
double chi_square_3_cdf(double x)
{
    return std::erf(std::sqrt(x / 2)) - std::sqrt(2 * x / kPi) * std::exp(-x / 2);
}

}  // namespace

namespace {

// Cell keys are the seed plus the cell index times these odd constants; a cell's words are mixes
// of its key (the position) and of its key plus the attribute offset. Distinct cells never share
// an input for indices of any practical size.
constexpr std::uint64_t step_i = 0xd1b54a32d192ed03ull, step_j = 0xaef17502108ef2d9ull, step_k = 0xf39cc0605cedc835ull;
constexpr std::uint64_t attribute_offset = 0x9e3779b97f4a7c15ull;
constexpr std::uint64_t oriented_offset = 0x632be59bd9b4e019ull;

}  // namespace

GaborNoise::GaborNoise(const GaborNoiseParameters& parameters) : parameters_(parameters)
{
    const double f = parameters.frequency, a = parameters.bandwidth, n = parameters.impulses_per_kernel;
    if (!(f >= 0) || !std::isfinite(f)) throw std::invalid_argument("GaborNoise: frequency must be finite and ≥ 0");
    if (!(a > 0) || !std::isfinite(a)) throw std::invalid_argument("GaborNoise: bandwidth must be positive");
    if (!(n >= 1) || !(n <= 256)) throw std::invalid_argument("GaborNoise: impulses per kernel must be in [1, 256]");
    if (parameters.channels != 1 && parameters.channels != max_channels)
        throw std::invalid_argument("GaborNoise: channels must be 1 or 3");
    const Vec3& d = parameters.direction;
    const double length = std::sqrt(dot3(d, d));
    if (parameters.kind != GaborKind::isotropic && !(std::abs(length - 1) < 1e-3))
        throw std::invalid_argument("GaborNoise: direction must be a unit vector");
    const double p = parameters.oriented_fraction;
    if (!(p >= 0 && p <= 1)) throw std::invalid_argument("GaborNoise: the oriented fraction must be in [0, 1]");

    radius_ = support_radius(a);
    // The 2D and the solid noise of one seed are unrelated processes.
    key_2d_ = mix64(parameters.seed ^ 0x2d2d2d2d2d2d2d2dull);
    key_3d_ = mix64(parameters.seed ^ 0x3d3d3d3d3d3d3d3dull);
    // One impulse per cell: the cell's area (volume) is that of the support disc (ball) over N.
    cell_x_ = cell_y_ = radius_ * std::sqrt(kPi / n);
    cell_3d_ = radius_ * std::cbrt(4 * kPi / (3 * n));
    const bool periodic = parameters.period[0] > 0 && parameters.period[1] > 0;
    if (periodic) {
        if (!(parameters.period[0] >= 2 * radius_ && parameters.period[1] >= 2 * radius_))
            throw std::invalid_argument("GaborNoise: the period must hold at least two kernel radii per axis");
        wrap_x_ = std::max<std::int64_t>(1, std::llround(parameters.period[0] / cell_x_));
        wrap_y_ = std::max<std::int64_t>(1, std::llround(parameters.period[1] / cell_y_));
        cell_x_ = parameters.period[0] / double(wrap_x_);
        cell_y_ = parameters.period[1] / double(wrap_y_);
    }
    const double density_2d = 1 / (cell_x_ * cell_y_), density_3d = 1 / (cell_3d_ * cell_3d_ * cell_3d_);

    // Var = λ · ½ ∫_{|x|<r} exp(−2π a² |x|²) dx (random phases: no cross terms, whatever the
    // positions, so a jittered grid has a Poisson process's second-order statistics). The
    // integral is (2a²)^(-n/2) times the Gaussian's energy fraction inside the support: 1 − cutoff²
    // in 2D, a χ²₃ probability in 3D.
    const double energy_2d = 1 - envelope_cutoff * envelope_cutoff;
    const double energy_3d = chi_square_3_cdf(4 * kPi * a * a * radius_ * radius_);
    gain_2d_ = 1 / std::sqrt(density_2d * 0.5 / (2 * a * a) * energy_2d);
    gain_3d_ = 1 / std::sqrt(density_3d * 0.5 * std::pow(2 * a * a, -1.5) * energy_3d);

    if (parameters.kind == GaborKind::anisotropic || parameters.kind == GaborKind::oriented) {
        omega_ = {f * d[0] / length, f * d[1] / length, f * d[2] / length};
        // 53-bit draws: a fraction of 1 keeps every impulse (draws are < 2^53), 0 none.
        if (parameters.kind == GaborKind::oriented) oriented_below_ = std::uint64_t(std::ldexp(p, 53));
    } else if (parameters.kind == GaborKind::hybrid) {
        const TangentFrame plane = tangent_frame(d, {0, 0, 0});
        plane_e1_ = plane.t;
        plane_e2_ = plane.b;
    }
}

double GaborNoise::support_radius(double bandwidth) { return std::sqrt(-std::log(envelope_cutoff) / kPi) / bandwidth; }

std::uint64_t GaborNoise::cell_key_2d(std::int64_t i, std::int64_t j) const
{
    if (wrap_x_ > 0) {
        i = ((i % wrap_x_) + wrap_x_) % wrap_x_;
        j = ((j % wrap_y_) + wrap_y_) % wrap_y_;
    }
    return key_2d_ + std::uint64_t(i) * step_i + std::uint64_t(j) * step_j;
}

std::uint64_t GaborNoise::cell_key_3d(std::int64_t i, std::int64_t j, std::int64_t k) const
{
    return key_3d_ + std::uint64_t(i) * step_i + std::uint64_t(j) * step_j + std::uint64_t(k) * step_k;
}

inline Vec3 GaborNoise::frequency_of(std::uint64_t key, std::uint64_t attributes) const
{
    const double f = parameters_.frequency;
    // Oriented or isotropic: a draw of its own (every attribute bit is taken), made only for the
    // oriented kind, so the other kinds' impulses are what they always were; the isotropic ones
    // of an oriented noise are those of the isotropic noise of the same seed.
    if (parameters_.kind == GaborKind::oriented && (mix64(key + oriented_offset) >> 11) < oriented_below_) return omega_;
    const int azimuth = int((attributes >> (3 * phase_bits)) & (phase_count - 1));
    const double c = phase_table.cosine[azimuth], s = phase_table.sine[azimuth];
    switch (parameters_.kind) {
    case GaborKind::anisotropic: return omega_;
    case GaborKind::hybrid:
        return {f * (c * plane_e1_[0] + s * plane_e2_[0]), f * (c * plane_e1_[1] + s * plane_e2_[1]),
                f * (c * plane_e1_[2] + s * plane_e2_[2])};
    case GaborKind::isotropic:
    case GaborKind::oriented: break;
    }
    // Uniform on the sphere: cos(colatitude) uniform in [−1, 1] (not the colatitude itself).
    const double z = 2 * ((double(attributes >> 40) + 0.5) * 0x1.0p-24) - 1;
    const double rho = std::sqrt(std::max(0.0, 1 - z * z));
    return {f * rho * c, f * rho * s, f * z};
}

namespace {

/// The cells [first, last] along one axis that a support of half-width `reach` around `x` meets.
inline void cell_span(double x, double reach, double cell, std::int64_t& first, std::int64_t& last)
{
    first = floor_index((x - reach) / cell);
    last = floor_index((x + reach) / cell);
}

/// The x-extent [lo, hi] (relative to the point) of the filtered support, an ellipse dᵀQd ≤ r²
/// in 2D or an ellipsoid in 3D, over one row of cells. Along x the support at fixed other
/// coordinates is centred at a linear function of them, with a half-width largest where their
/// part of the quadratic form (its Schur complement) is smallest: bounding both over the row's
/// band gives spans that follow the ellipse — so the cost of a filtered evaluation grows with the
/// support's area (√det A), not with the square of its long axis. False: the row misses it.
struct RowSpan {
    double lo, hi;
};

/// 2D: Q = A⁻¹, the row d_y ∈ [y0, y1].
inline bool row_span_2d(const Symmetric2& q, double r2, double y0, double y1, RowSpan& span)
{
    const double schur = q.determinant() / q.xx;  // > 0: Q is positive definite
    const double nearest = y0 > 0 ? y0 : y1 < 0 ? y1 : 0.0;
    const double w2 = (r2 - schur * nearest * nearest) / q.xx;
    if (w2 < 0) return false;
    const double w = std::sqrt(w2), c0 = -q.xy / q.xx * y0, c1 = -q.xy / q.xx * y1;
    span = {std::min(c0, c1) - w, std::max(c0, c1) + w};
    return true;
}

/// 3D: the symmetric 3×3 M = n nᵀ + T A⁻¹ Tᵀ (texture axes), the row d_y ∈ [y0, y1], d_z ∈ [z0, z1].
struct Ellipsoid {
    double m[3][3];
    double schur_min;  // smallest eigenvalue of the (y, z) Schur complement
    // Once per ellipsoid rather than per row (divisions): 1 / m_xx and the centre's slopes
    // −m_xy / m_xx, −m_xz / m_xx. (A span a rounding wider or narrower moves its ends by far less
    // than its margin: the cells whose kernels can reach the points are the same.)
    double inverse_xx, ky, kz;
    void prepare()
    {
        inverse_xx = 1 / m[0][0];
        ky = -m[0][1] * inverse_xx, kz = -m[0][2] * inverse_xx;
    }
};

inline bool row_span_3d(const Ellipsoid& e, double r2, double y0, double y1, double z0, double z1, RowSpan& span)
{
    const double ny = y0 > 0 ? y0 : y1 < 0 ? y1 : 0.0, nz = z0 > 0 ? z0 : z1 < 0 ? z1 : 0.0;
    const double w2 = (r2 - e.schur_min * (ny * ny + nz * nz)) * e.inverse_xx;
    if (w2 < 0) return false;
    const double w = std::sqrt(w2), ky = e.ky, kz = e.kz;
    const double c00 = ky * y0 + kz * z0, c01 = ky * y0 + kz * z1, c10 = ky * y1 + kz * z0, c11 = ky * y1 + kz * z1;
    span = {std::min(std::min(c00, c01), std::min(c10, c11)) - w, std::max(std::max(c00, c01), std::max(c10, c11)) + w};
    return true;
}

}  // namespace

namespace {

/// Cells are visited over the support of a radius this much larger than the kernels': every
/// kernel the float test q ≤ limit can keep (q is exact to ~1e-6 relative) lies well inside, so
/// which cells a point's vector visits never decides which kernels it sums.
constexpr double span_margin = 1.001;

/// The Envelope (gabor_raster_kernels.h) of a filter, 2D or in the plane (t, b) of a slice with
/// normal n: π a² (h² + pᵀA⁻¹p) as squares of linear forms, from the Cholesky factor of π a² A⁻¹
/// (a, β; β, c) = (√a, β/√a)ᵀ(√a, β/√a) + (0, √(det/a))ᵀ(0, √(det/a)).
gabor_raster::Envelope envelope_of(const Symmetric2& inverse, double pi_a2, double r2, const TangentFrame* frame)
{
    const double a = pi_a2 * inverse.xx, beta = pi_a2 * inverse.xy, c = pi_a2 * inverse.yy;
    const double root_a = std::sqrt(a), cross = beta / root_a, rest = std::sqrt(std::max(0.0, (a * c - beta * beta) / a));
    gabor_raster::Envelope envelope;
    envelope.limit = float(pi_a2 * r2);
    if (!frame) {
        envelope.e[1][0] = float(root_a), envelope.e[1][1] = float(cross);
        envelope.e[2][1] = float(rest);
        return envelope;
    }
    const double root_pi_a2 = std::sqrt(pi_a2);
    for (int k = 0; k < 3; ++k) {
        envelope.e[0][k] = float(root_pi_a2 * frame->n[k]);
        envelope.e[1][k] = float(root_a * frame->t[k] + cross * frame->b[k]);
        envelope.e[2][k] = float(rest * frame->b[k]);
    }
    return envelope;
}

/// What a block of points shares: its cells' impulses, its rows of cells (and their lattice
/// indices), and one row of points' list of those rows. Kept per thread: evaluation allocates
/// nothing once a thread has seen a block as large.
struct GridScratch {
    gabor_raster::CellImpulses cells;
    std::vector<gabor_raster::CellRow> block_rows, rows;
    std::vector<std::int64_t> row_j, row_k;
    // A single point's kept candidate cells: keys, impulse positions; solid, its rows of cells.
    std::vector<std::uint64_t> key;
    std::vector<double> cx, cy, cz;
    std::vector<gabor_raster::CandidateRow> candidate_rows;
};

GridScratch& grid_scratch()
{
    thread_local GridScratch scratch;
    return scratch;
}

/// Blocks of points sharing one cell cache: wide enough for whole vectors, small enough that the
/// cells of the finest octaves stay in the L1/L2 cache.
constexpr std::size_t block_columns = 64, block_rows = 16;

void set_phases(gabor_raster::CellImpulses& cells, std::size_t m, std::uint64_t attributes)
{
    for (int c = 0; c < 3; ++c) {
        const int index = phase_index(attributes, c);
        cells.cos_phase[c][m] = phase_table.cosine[index];
        cells.sin_phase[c][m] = phase_table.sine[index];
    }
}

/// The support's matrix of a slice with the frame (t, b, n): M = n nᵀ + T A⁻¹ Tᵀ, the ellipsoid
/// h² + pᵀA⁻¹p ≤ r² (thickness r along n: slicing does not widen kernels, filtering widens them
/// in the plane), with its Schur complement's smallest eigenvalue for row_span_3d.
Ellipsoid sliced_support(const TangentFrame& frame, const Symmetric2& inverse)
{
    const Vec3 &t = frame.t, &b = frame.b, &n = frame.n;
    Ellipsoid support{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            support.m[i][j] = n[i] * n[j] + inverse.xx * t[i] * t[j] + inverse.xy * (t[i] * b[j] + b[i] * t[j]) +
                              inverse.yy * b[i] * b[j];
    const double (&m)[3][3] = support.m;
    support.schur_min = Symmetric2{m[1][1] - m[0][1] * m[0][1] / m[0][0], m[1][2] - m[0][1] * m[0][2] / m[0][0],
                                   m[2][2] - m[0][2] * m[0][2] / m[0][0]}
                            .smallest_eigenvalue();
    support.prepare();
    return support;
}

}  // namespace

void GaborNoise::eval_2d(double x, double y, const GaborFilter& filter, float out[max_channels]) const
{
    float* const channels[max_channels] = {&out[0], &out[1], &out[2]};
    eval_grid<false>(&x, 1, &y, 1, 0, TangentFrame{}, filter, channels);
}

void GaborNoise::eval_sliced(const Vec3& p, const TangentFrame& frame, const GaborFilter& filter,
                             float out[max_channels]) const
{
    float* const channels[max_channels] = {&out[0], &out[1], &out[2]};
    eval_grid<true>(&p[0], 1, &p[1], 1, p[2], frame, filter, channels);
}

void GaborNoise::eval_2d_grid(const double* x, std::size_t nx, const double* y, std::size_t ny, const GaborFilter& filter,
                              float* const out[max_channels]) const
{
    eval_grid<false>(x, nx, y, ny, 0, TangentFrame{}, filter, out);
}

void GaborNoise::eval_sliced_grid(const double* x, std::size_t nx, const double* y, std::size_t ny, double z,
                                  const TangentFrame& frame, const GaborFilter& filter, float* const out[max_channels]) const
{
    eval_grid<true>(x, nx, y, ny, z, frame, filter, out);
}

/// One eval_grid call, in steps: which cells a block of points needs (gather_block), each
/// cell's impulse prepared for the filter (set_impulse), and the sums, row by row of points
/// (sum_block_rows) or for a single point over only the cells that can reach it
/// (sum_single_point). What the steps share is fixed by the constructor.
template <bool Solid>
class GaborNoise::GridEvaluation {
public:
    GridEvaluation(const GaborNoise& noise, const double* x, std::size_t nx, const double* y, std::size_t ny, double z,
                   const TangentFrame& frame, const GaborFilter& filter);
    void run(float* const out[max_channels]);

private:
    bool row_span(std::int64_t j, std::int64_t k, double y_lo, double y_hi, RowSpan& span) const;
    void test_cell_2d(std::int64_t i, std::int64_t j);
    void set_impulse(std::size_t m, std::uint64_t key, double cx, double cy, double cz);
    void set_cell(std::size_t m, std::int64_t i, std::int64_t j, std::int64_t k);
    void gather_block(double x_lo, double x_hi, double y_lo, double y_hi);
    void sum_single_point(float* const out[max_channels]);
    void sum_block_rows(std::size_t by, std::size_t rows_here, std::size_t bx, std::size_t columns,
                        float* const out[max_channels]);

    const GaborNoise& noise_;
    const double *x_, *y_;
    std::size_t nx_, ny_;
    double z_;
    const TangentFrame& frame_;
    const Symmetric2& inverse_;
    const Symmetric2& damping_;
    const double reach_, reach2_;  // the support's radius with its margin, and its square
    const bool fixed_;
    const double sx_, sy_, sz_, inverse_sx_;  // cell sides; cells of a span: its ends times inverse_sx_ (see Ellipsoid)
    Ellipsoid support_{};                     // solid: the support (sliced_support)
    double extent_y_, extent_z_ = 0;          // the support's half-extents along y and z
    gabor_raster::RowInput input_;
    GridScratch& scratch_;
    // A single point (eval(), eval_sliced()) keeps only the cells whose kernel can reach it: q in
    // double with the span's margin, a superset of what the kernel's float test keeps, so the
    // sum is the same as in any grid. Candidates are stored unconditionally and counted only when
    // kept (most are rejected: a mispredicted branch each would cost more than the test).
    const bool single_;
    std::size_t kept_ = 0, candidate_count_ = 0;
};

template <bool Solid>
GaborNoise::GridEvaluation<Solid>::GridEvaluation(const GaborNoise& noise, const double* x, std::size_t nx, const double* y,
                                                  std::size_t ny, double z, const TangentFrame& frame,
                                                  const GaborFilter& filter)
    : noise_(noise), x_(x), y_(y), nx_(nx), ny_(ny), z_(z), frame_(frame), inverse_(filter.inverse_a),
      damping_(filter.damping), reach_(noise.radius_ * span_margin), reach2_(reach_ * reach_),
      fixed_(noise.parameters_.kind == GaborKind::anisotropic), sx_(Solid ? noise.cell_3d_ : noise.cell_x_),
      sy_(Solid ? noise.cell_3d_ : noise.cell_y_), sz_(noise.cell_3d_), inverse_sx_(1 / sx_), scratch_(grid_scratch()),
      single_(nx == 1 && ny == 1)
{
    const double a = noise.parameters_.bandwidth, pi_a2 = kPi * a * a;
    const double reach = reach_;
    input_.envelope = envelope_of(inverse_, pi_a2, noise.radius_ * noise.radius_, Solid ? &frame : nullptr);
    input_.gain = (Solid ? noise.gain_3d_ : noise.gain_2d_) * filter.amplitude;
    input_.channels = noise.parameters_.channels;
    input_.solid = Solid;
    input_.z = z;
    input_.cell_x = sx_;
    // The support: 2D the ellipse dᵀA⁻¹d ≤ r²; sliced the ellipsoid of sliced_support, whose
    // extent along texture axis e is r·√((M⁻¹)_ee), M⁻¹ = n nᵀ + T A Tᵀ.
    extent_y_ = reach * std::sqrt(filter.matrix.yy);
    if (Solid) {
        const Vec3 &t = frame.t, &b = frame.b, &n = frame.n;
        extent_y_ = reach * std::sqrt(n[1] * n[1] + filter.matrix.quadratic_form(t[1], b[1]));
        extent_z_ = reach * std::sqrt(n[2] * n[2] + filter.matrix.quadratic_form(t[2], b[2]));
        support_ = sliced_support(frame, inverse_);
    }
    if (single_) scratch_.candidate_rows.clear();
}

/// The span along x of the support over the row of cells (j, k), for points with y in
/// [y_lo, y_hi] (and the grid's z).
template <bool Solid>
bool GaborNoise::GridEvaluation<Solid>::row_span(std::int64_t j, std::int64_t k, double y_lo, double y_hi, RowSpan& span) const
{
    const double y0 = j * sy_ - y_hi, y1 = j * sy_ + sy_ - y_lo;
    if (!Solid) return row_span_2d(inverse_, reach2_, y0, y1, span);
    const double z0 = k * sz_ - z_;
    return row_span_3d(support_, reach2_, y0, y1, z0, z0 + sz_, span);
}

/// A single 2D point's candidate cell (i, j), kept when its kernel can reach the point. (Solid
/// points' rows are collected and tested together by vectors of cells, in sum_single_point:
/// gabor_raster::test_candidates, the same operations lane-wise.)
template <bool Solid>
void GaborNoise::GridEvaluation<Solid>::test_cell_2d(std::int64_t i, std::int64_t j)
{
    const std::uint64_t key = noise_.cell_key_2d(i, j), bits = mix64(key);
    const double cx = i * sx_ + position_fraction(bits) * sx_, cy = j * sy_ + position_fraction(bits >> 21) * sy_;
    const double q = inverse_.quadratic_form(x_[0] - cx, y_[0] - cy);
    scratch_.key[kept_] = key;
    scratch_.cx[kept_] = cx, scratch_.cy[kept_] = cy, scratch_.cz[kept_] = 0.0;
    kept_ += q <= reach2_;
}

/// One impulse of cell `key` at (cx, cy, cz) into the cache, prepared for this filter (and frame).
/// Written at index m of cells already sized (CellImpulses::resize): no growth checks per array.
template <bool Solid>
void GaborNoise::GridEvaluation<Solid>::set_impulse(std::size_t m, std::uint64_t key, double cx, double cy, double cz)
{
    gabor_raster::CellImpulses& cells = scratch_.cells;
    const Vec3 &t = frame_.t, &b = frame_.b, &n = frame_.n;
    const std::uint64_t attributes = mix64(key + attribute_offset);
    const Vec3 omega = fixed_ ? noise_.omega_ : noise_.frequency_of(key, attributes);
    cells.x[m] = cx, cells.y[m] = cy, cells.z[m] = cz;
    // In-plane frequency ω^s (2D: the projected one), filtered: A⁻¹ω^s (eq. 10).
    const double st = Solid ? dot3(t, omega) : omega[0], sb = Solid ? dot3(b, omega) : omega[1];
    const double wx = inverse_.xx * st + inverse_.xy * sb, wy = inverse_.xy * st + inverse_.yy * sb;
    if (Solid) {
        // The phase 2π (A⁻¹ω^s·p + h n·ω) (eq. 6) as one frequency in texture axes.
        const double wn = dot3(n, omega);
        cells.wx[m] = float(wx * t[0] + wy * b[0] + wn * n[0]);
        cells.wy[m] = float(wx * t[1] + wy * b[1] + wn * n[1]);
        cells.wz[m] = float(wx * t[2] + wy * b[2] + wn * n[2]);
    } else {
        cells.wx[m] = float(wx), cells.wy[m] = float(wy), cells.wz[m] = 0.0f;
    }
    cells.log_amplitude[m] = float(-damping_.quadratic_form(st, sb));
    set_phases(cells, m, attributes);
}

template <bool Solid>
void GaborNoise::GridEvaluation<Solid>::set_cell(std::size_t m, std::int64_t i, std::int64_t j, std::int64_t k)
{
    const std::uint64_t key = Solid ? noise_.cell_key_3d(i, j, k) : noise_.cell_key_2d(i, j);
    const std::uint64_t bits = mix64(key);
    set_impulse(m, key, i * sx_ + position_fraction(bits) * sx_, j * sy_ + position_fraction(bits >> 21) * sy_,
                Solid ? k * sz_ + position_fraction(bits >> 42) * sz_ : 0.0);
}

/// The block's cells: every row of cells its support reaches, each over the span that the
/// block's points need; a single point's candidates instead (kept or collected, see above).
template <bool Solid>
void GaborNoise::GridEvaluation<Solid>::gather_block(double x_lo, double x_hi, double y_lo, double y_hi)
{
    GridScratch& scratch = scratch_;
    gabor_raster::CellImpulses& cells = scratch.cells;
    cells.clear();
    scratch.block_rows.clear(), scratch.row_j.clear(), scratch.row_k.clear();
    std::int64_t k0 = 0, k1 = 0, j0, j1;
    if (Solid) cell_span(z_, extent_z_, sz_, k0, k1);
    j0 = floor_index((y_lo - extent_y_) / sy_), j1 = floor_index((y_hi + extent_y_) / sy_);
    for (std::int64_t k = k0; k <= k1; ++k)
        for (std::int64_t j = j0; j <= j1; ++j) {
            RowSpan span;
            if (!row_span(j, k, y_lo, y_hi, span)) continue;
            const std::int64_t i0 = floor_index((x_lo + span.lo) * inverse_sx_), i1 = floor_index((x_hi + span.hi) * inverse_sx_);
            if (single_) {  // one list of the kept cells: sum_single_point
                candidate_count_ += std::size_t(i1 - i0 + 1);
                if (scratch.key.size() < candidate_count_ + 64) {  // (+ a vector: test_candidates)
                    scratch.key.resize(2 * (candidate_count_ + 64));
                    for (auto* v : {&scratch.cx, &scratch.cy, &scratch.cz}) v->resize(scratch.key.size());
                }
                if (Solid) scratch.candidate_rows.push_back({i0, i1, j, k});
                else for (std::int64_t i = i0; i <= i1; ++i) test_cell_2d(i, j);
                continue;
            }
            gabor_raster::CellRow row;
            row.first = std::uint32_t(cells.size());
            cells.resize(cells.size() + std::size_t(i1 - i0 + 1));
            for (std::int64_t i = i0; i <= i1; ++i) set_cell(row.first + std::size_t(i - i0), i, j, k);
            row.count = std::uint32_t(cells.size() - row.first);
            row.i_first = i0;
            scratch.block_rows.push_back(row);
            scratch.row_j.push_back(j), scratch.row_k.push_back(k);
        }
}

template <bool Solid>
void GaborNoise::GridEvaluation<Solid>::sum_single_point(float* const out[max_channels])
{
    GridScratch& candidates = scratch_;
    gabor_raster::CellImpulses& cells = scratch_.cells;
    if (Solid) {
        // M = n nᵀ + T A⁻¹ Tᵀ, the support's matrix: dᵀMd = (n·d)² + (t·d, b·d) A⁻¹ (t·d, b·d)ᵀ
        // in half the operations. q only has to be right to far less than the margin:
        // kept octaves have det A ≤ 32², A⁻¹ a condition number ≤ 1024, q an error ~1e-13.
        gabor_raster::CandidateTest test{noise_.key_3d_, step_i, step_j, step_k, noise_.cell_3d_, {x_[0], y_[0], z_}, {}, reach2_};
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) test.m[r][c] = support_.m[r][c];
        kept_ = gabor_raster::test_candidates(test, candidates.candidate_rows.data(), candidates.candidate_rows.size(),
                                              candidates.key.data(), candidates.cx.data(), candidates.cy.data(),
                                              candidates.cz.data());
    }
    cells.resize(kept_);
    for (std::size_t m = 0; m < kept_; ++m) set_impulse(m, candidates.key[m], candidates.cx[m], candidates.cy[m], candidates.cz[m]);
    gabor_raster::CellRow every;
    every.count = std::uint32_t(cells.size());
    every.every_cell = true;
    input_.rows = &every;
    input_.row_count = 1;
    input_.y = y_[0];
    float* row_out[max_channels] = {};
    for (int c = 0; c < noise_.parameters_.channels; ++c) row_out[c] = out[c];
    gabor_raster::sum_row(input_, x_, 1, row_out);
}

template <bool Solid>
void GaborNoise::GridEvaluation<Solid>::sum_block_rows(std::size_t by, std::size_t rows_here, std::size_t bx,
                                                       std::size_t columns, float* const out[max_channels])
{
    GridScratch& scratch = scratch_;
    for (std::size_t py = by; py < by + rows_here; ++py) {
        // This row of points' spans (narrower than the block's: fewer cells per vector).
        scratch.rows.clear();
        for (std::size_t r = 0; r < scratch.block_rows.size(); ++r) {
            RowSpan span;
            if (!row_span(scratch.row_j[r], scratch.row_k[r], y_[py], y_[py], span)) continue;
            gabor_raster::CellRow row = scratch.block_rows[r];
            row.lo = span.lo, row.hi = span.hi;
            scratch.rows.push_back(row);
        }
        input_.rows = scratch.rows.data();
        input_.row_count = scratch.rows.size();
        input_.y = y_[py];
        float* row_out[max_channels] = {};
        for (int c = 0; c < noise_.parameters_.channels; ++c) row_out[c] = out[c] + py * nx_ + bx;
        gabor_raster::sum_row(input_, x_ + bx, columns, row_out);
    }
}

template <bool Solid>
void GaborNoise::GridEvaluation<Solid>::run(float* const out[max_channels])
{
    for (std::size_t by = 0; by < ny_; by += block_rows) {
        const std::size_t rows_here = std::min(block_rows, ny_ - by);
        const auto [y_lo_at, y_hi_at] = std::minmax_element(y_ + by, y_ + by + rows_here);
        for (std::size_t bx = 0; bx < nx_; bx += block_columns) {
            const std::size_t columns = std::min(block_columns, nx_ - bx);
            const auto [x_lo_at, x_hi_at] = std::minmax_element(x_ + bx, x_ + bx + columns);
            gather_block(*x_lo_at, *x_hi_at, *y_lo_at, *y_hi_at);
            input_.cells = &scratch_.cells;
            if (single_) return sum_single_point(out);
            sum_block_rows(by, rows_here, bx, columns, out);
        }
    }
}

template <bool Solid>
void GaborNoise::eval_grid(const double* x, std::size_t nx, const double* y, std::size_t ny, double z,
                           const TangentFrame& frame, const GaborFilter& filter, float* const out[max_channels]) const
{
    GridEvaluation<Solid>(*this, x, nx, y, ny, z, frame, filter).run(out);
}

std::vector<GaborNoise::Impulse> GaborNoise::impulses_near_2d(double x, double y, double reach) const
{
    std::vector<Impulse> impulses;
    if (!(reach > 0)) reach = radius_;
    std::int64_t i0, i1, j0, j1;
    cell_span(x, reach, cell_x_, i0, i1);
    cell_span(y, reach, cell_y_, j0, j1);
    for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t i = i0; i <= i1; ++i) {
            const std::uint64_t key = cell_key_2d(i, j), bits = mix64(key), attributes = mix64(key + attribute_offset);
            const Vec3 omega = frequency_of(key, attributes);
            Impulse impulse{{(i + position_fraction(bits)) * cell_x_, (j + position_fraction(bits >> 21)) * cell_y_, 0},
                            {omega[0], omega[1], 0}, {}};
            for (int c = 0; c < max_channels; ++c) impulse.phase[c] = phase_angle(phase_index(attributes, c));
            impulses.push_back(impulse);
        }
    return impulses;
}

std::vector<GaborNoise::Impulse> GaborNoise::impulses_near_3d(const Vec3& p, double reach) const
{
    std::vector<Impulse> impulses;
    if (!(reach > 0)) reach = radius_;
    const double s = cell_3d_;
    std::int64_t lo[3], hi[3];
    for (int e = 0; e < 3; ++e) cell_span(p[e], reach, s, lo[e], hi[e]);
    for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            for (std::int64_t i = lo[0]; i <= hi[0]; ++i) {
                const std::uint64_t key = cell_key_3d(i, j, k), bits = mix64(key), attributes = mix64(key + attribute_offset);
                Impulse impulse{{(i + position_fraction(bits)) * s, (j + position_fraction(bits >> 21)) * s,
                                 (k + position_fraction(bits >> 42)) * s},
                                frequency_of(key, attributes), {}};
                for (int c = 0; c < max_channels; ++c) impulse.phase[c] = phase_angle(phase_index(attributes, c));
                impulses.push_back(impulse);
            }
    return impulses;
}

double GaborNoise::reference_2d(double x, double y, int channel) const
{
    const double a = parameters_.bandwidth;
    double sum = 0;
    for (const Impulse& impulse : impulses_near_2d(x, y)) {
        const double dx = x - impulse.position[0], dy = y - impulse.position[1];
        const double d2 = dx * dx + dy * dy;
        if (d2 > radius_ * radius_) continue;
        sum += std::exp(-kPi * a * a * d2) *
               std::cos(2 * kPi * (impulse.omega[0] * dx + impulse.omega[1] * dy) + impulse.phase[channel]);
    }
    return sum * gain_2d_;
}

double GaborNoise::reference_3d(const Vec3& p, int channel) const
{
    const double a = parameters_.bandwidth;
    double sum = 0;
    for (const Impulse& impulse : impulses_near_3d(p)) {
        const Vec3 d{p[0] - impulse.position[0], p[1] - impulse.position[1], p[2] - impulse.position[2]};
        const double d2 = dot3(d, d);
        if (d2 > radius_ * radius_) continue;
        sum += std::exp(-kPi * a * a * d2) * std::cos(2 * kPi * dot3(impulse.omega, d) + impulse.phase[channel]);
    }
    return sum * gain_3d_;
}

}  // namespace stochtex
