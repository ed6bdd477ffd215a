#include "models/gabor/gabor_noise.h"
#include <stochtex/models/gabor_parameters.h>

#include "numerics/fast_math.h"

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
            cosine[k] = float(std::cos(2 * M_PI * k / phase_count));
            sine[k] = float(std::sin(2 * M_PI * k / phase_count));
        }
    }
};
const PhaseTable phase_table;

double phase_angle(int index) { return 2 * M_PI * index / phase_count; }

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

inline std::int64_t floor_index(double x) { return std::int64_t(std::floor(x)); }

/// P(χ² with 3 degrees of freedom ≤ x): the energy fraction of a 3D Gaussian inside a sphere.
double chi_square_3_cdf(double x)
{
    return std::erf(std::sqrt(x / 2)) - std::sqrt(2 * x / M_PI) * std::exp(-x / 2);
}

}  // namespace

/// Kernels waiting for their exp and sin/cos: evaluated in blocks so the loop vectorises.
struct GaborNoise::Batch {
    static constexpr int capacity = 64;
    int size = 0;
    int channels;
    float exponent[capacity], turns[capacity];
    float cos_phase[max_channels][capacity], sin_phase[max_channels][capacity];
    float value[max_channels][capacity];
    double sum[max_channels] = {0, 0, 0};

    explicit Batch(int channel_count) : channels(channel_count) {}

    void add(float kernel_exponent, float kernel_turns, std::uint64_t attributes)
    {
        exponent[size] = std::max(kernel_exponent, -87.0f);  // fast_exp's domain; e^-87 ≈ 0
        turns[size] = kernel_turns;
        for (int c = 0; c < max_channels; ++c) {  // all three: flush() reads them (unused ones too)
            const int index = phase_index(attributes, c);
            cos_phase[c][size] = phase_table.cosine[index];
            sin_phase[c][size] = phase_table.sine[index];
        }
        if (++size == capacity) flush();
    }

    void flush()
    {
        // cos(2πT + φ) = cos 2πT cos φ − sin 2πT sin φ: one sin/cos per kernel for all channels.
        for (int i = 0; i < size; ++i) {
            const float envelope = fast_exp(exponent[i]);
            float s, c;
            fast_sincos_turns(turns[i], s, c);
            const float es = envelope * s, ec = envelope * c;
            value[0][i] = ec * cos_phase[0][i] - es * sin_phase[0][i];
            value[1][i] = ec * cos_phase[1][i] - es * sin_phase[1][i];
            value[2][i] = ec * cos_phase[2][i] - es * sin_phase[2][i];
        }
        // Summed separately, in order: float reductions do not vectorise without reassociation.
        for (int c = 0; c < channels; ++c)
            for (int i = 0; i < size; ++i) sum[c] += value[c][i];
        size = 0;
    }
};

/// Impulses whose support reaches the point. Candidates are stored unconditionally and the count
/// advances only for those inside the support: most candidates are rejected, and a mispredicted
/// branch per kept one would cost more than the test itself.
struct GaborNoise::Kept {
    static constexpr int capacity = 256;
    int size = 0;
    double u[capacity], v[capacity], h[capacity], q[capacity];
    std::uint64_t attribute_counter[capacity];

    void push(double in_plane_u, double in_plane_v, double height, double distance2, double limit2, std::uint64_t counter)
    {
        u[size] = in_plane_u, v[size] = in_plane_v, h[size] = height, q[size] = distance2;
        attribute_counter[size] = counter;
        size += distance2 <= limit2;
    }
    bool full() const { return size == capacity; }
};

namespace {

// Cell keys are the seed plus the cell index times these odd constants; a cell's words are mixes
// of its key (the position) and of its key plus the attribute offset. Distinct cells never share
// an input for indices of any practical size.
constexpr std::uint64_t step_i = 0xd1b54a32d192ed03ull, step_j = 0xaef17502108ef2d9ull, step_k = 0xf39cc0605cedc835ull;
constexpr std::uint64_t attribute_offset = 0x9e3779b97f4a7c15ull;

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

    radius_ = support_radius(a);
    // The 2D and the solid noise of one seed are unrelated processes.
    key_2d_ = mix64(parameters.seed ^ 0x2d2d2d2d2d2d2d2dull);
    key_3d_ = mix64(parameters.seed ^ 0x3d3d3d3d3d3d3d3dull);
    // One impulse per cell: the cell's area (volume) is that of the support disc (ball) over N.
    cell_x_ = cell_y_ = radius_ * std::sqrt(M_PI / n);
    cell_3d_ = radius_ * std::cbrt(4 * M_PI / (3 * n));
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
    const double energy_3d = chi_square_3_cdf(4 * M_PI * a * a * radius_ * radius_);
    gain_2d_ = 1 / std::sqrt(density_2d * 0.5 / (2 * a * a) * energy_2d);
    gain_3d_ = 1 / std::sqrt(density_3d * 0.5 * std::pow(2 * a * a, -1.5) * energy_3d);

    if (parameters.kind == GaborKind::anisotropic) {
        omega_ = {f * d[0] / length, f * d[1] / length, f * d[2] / length};
    } else if (parameters.kind == GaborKind::hybrid) {
        const TangentFrame plane = tangent_frame(d, {0, 0, 0});
        plane_e1_ = plane.t;
        plane_e2_ = plane.b;
    }
}

double GaborNoise::support_radius(double bandwidth) { return std::sqrt(-std::log(envelope_cutoff) / M_PI) / bandwidth; }

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

inline Vec3 GaborNoise::frequency_of(std::uint64_t attributes) const
{
    const double f = parameters_.frequency;
    const int azimuth = int((attributes >> (3 * phase_bits)) & (phase_count - 1));
    const double c = phase_table.cosine[azimuth], s = phase_table.sine[azimuth];
    switch (parameters_.kind) {
    case GaborKind::anisotropic: return omega_;
    case GaborKind::hybrid:
        return {f * (c * plane_e1_[0] + s * plane_e2_[0]), f * (c * plane_e1_[1] + s * plane_e2_[1]),
                f * (c * plane_e1_[2] + s * plane_e2_[2])};
    case GaborKind::isotropic: break;
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
};

inline bool row_span_3d(const Ellipsoid& e, double r2, double y0, double y1, double z0, double z1, RowSpan& span)
{
    const double ny = y0 > 0 ? y0 : y1 < 0 ? y1 : 0.0, nz = z0 > 0 ? z0 : z1 < 0 ? z1 : 0.0;
    const double w2 = (r2 - e.schur_min * (ny * ny + nz * nz)) / e.m[0][0];
    if (w2 < 0) return false;
    const double w = std::sqrt(w2), ky = -e.m[0][1] / e.m[0][0], kz = -e.m[0][2] / e.m[0][0];
    const double c00 = ky * y0 + kz * z0, c01 = ky * y0 + kz * z1, c10 = ky * y1 + kz * z0, c11 = ky * y1 + kz * z1;
    span = {std::min(std::min(c00, c01), std::min(c10, c11)) - w, std::max(std::max(c00, c01), std::max(c10, c11)) + w};
    return true;
}

}  // namespace

void GaborNoise::eval_2d(double x, double y, const GaborFilter& filter, float out[max_channels]) const
{
    const double a = parameters_.bandwidth, r2 = radius_ * radius_, pi_a2 = M_PI * a * a;
    const Symmetric2& inverse = filter.inverse_a;
    const Symmetric2& damping = filter.damping;
    // The filtered support is the ellipse dᵀA⁻¹d ≤ r²: its bounding box, and a disc holding it.
    const double extent_y = radius_ * std::sqrt(filter.matrix.yy);
    const double sx = cell_x_, sy = cell_y_;

    // Anisotropic noise: one frequency, so its filtered form is computed once.
    const bool fixed = parameters_.kind == GaborKind::anisotropic;
    const double fixed_fx = inverse.xx * omega_[0] + inverse.xy * omega_[1];
    const double fixed_fy = inverse.xy * omega_[0] + inverse.yy * omega_[1];
    const double fixed_damping = damping.quadratic_form(omega_[0], omega_[1]);

    Batch batch(parameters_.channels);
    Kept kept;
    auto evaluate_kept = [&] {
        for (int n = 0; n < kept.size; ++n) {
            const std::uint64_t attributes = mix64(kept.attribute_counter[n]);
            const double dx = kept.u[n], dy = kept.v[n];
            double wx = fixed_fx, wy = fixed_fy, damp = fixed_damping;
            if (!fixed) {
                const Vec3 omega = frequency_of(attributes);
                wx = inverse.xx * omega[0] + inverse.xy * omega[1];
                wy = inverse.xy * omega[0] + inverse.yy * omega[1];
                damp = damping.quadratic_form(omega[0], omega[1]);
            }
            batch.add(float(-pi_a2 * kept.q[n] - damp), float(wx * dx + wy * dy), attributes);
        }
        kept.size = 0;
    };
    std::int64_t j0, j1;
    cell_span(y, extent_y, sy, j0, j1);
    for (std::int64_t j = j0; j <= j1; ++j) {
        const double cell_dy = j * sy - y;  // the row's lower edge relative to the point
        RowSpan span;
        if (!row_span_2d(inverse, r2, cell_dy, cell_dy + sy, span)) continue;
        const std::int64_t i0 = floor_index((x + span.lo) / sx), i1 = floor_index((x + span.hi) / sx);
        for (std::int64_t i = i0; i <= i1; ++i) {
            if (kept.full()) evaluate_kept();
            const std::uint64_t key = cell_key_2d(i, j);
            const std::uint64_t bits = mix64(key);
            const double dx = -(i * sx - x + position_fraction(bits) * sx);  // x − x_i
            const double dy = -(cell_dy + position_fraction(bits >> 21) * sy);
            kept.push(dx, dy, 0, inverse.quadratic_form(dx, dy), r2, key + attribute_offset);
        }
    }
    evaluate_kept();
    batch.flush();
    const double gain = gain_2d_ * filter.amplitude;
    for (int c = 0; c < parameters_.channels; ++c) out[c] = float(batch.sum[c] * gain);
}

void GaborNoise::eval_sliced(const Vec3& p, const TangentFrame& frame, const GaborFilter& filter,
                             float out[max_channels]) const
{
    const double a = parameters_.bandwidth, r = radius_, r2 = r * r, pi_a2 = M_PI * a * a;
    const Symmetric2& inverse = filter.inverse_a;
    const Symmetric2& damping = filter.damping;
    const Vec3 &t = frame.t, &b = frame.b, &n = frame.n;
    // The support is the ellipsoid h² + pᵀA⁻¹p ≤ r² (thickness r along n: slicing does not
    // widen kernels, filtering widens them in the plane). Its bounding box, and a ball holding it.
    // Its extent along texture axis e is r·√((M⁻¹)_ee), M⁻¹ = n nᵀ + T A Tᵀ.
    double extent[3];
    for (int e = 0; e < 3; ++e) extent[e] = r * std::sqrt(n[e] * n[e] + filter.matrix.quadratic_form(t[e], b[e]));
    const double s = cell_3d_;
    Ellipsoid support;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            support.m[i][j] = n[i] * n[j] + inverse.xx * t[i] * t[j] + inverse.xy * (t[i] * b[j] + b[i] * t[j]) +
                              inverse.yy * b[i] * b[j];
    const double (&m)[3][3] = support.m;
    support.schur_min = Symmetric2{m[1][1] - m[0][1] * m[0][1] / m[0][0], m[1][2] - m[0][1] * m[0][2] / m[0][0],
                                   m[2][2] - m[0][2] * m[0][2] / m[0][0]}
                            .smallest_eigenvalue();

    const bool fixed = parameters_.kind == GaborKind::anisotropic;
    auto sliced = [&](const Vec3& omega, double& wx, double& wy, double& wn, double& damp) {
        const double st = dot3(t, omega), sb = dot3(b, omega);  // ω^s (eq. 6)
        wx = inverse.xx * st + inverse.xy * sb;                   // A⁻¹ω^s (eq. 10)
        wy = inverse.xy * st + inverse.yy * sb;
        wn = dot3(n, omega);
        damp = damping.quadratic_form(st, sb);
    };
    double fixed_wx = 0, fixed_wy = 0, fixed_wn = 0, fixed_damping = 0;
    if (fixed) sliced(omega_, fixed_wx, fixed_wy, fixed_wn, fixed_damping);

    Batch batch(parameters_.channels);
    Kept kept;
    auto evaluate_kept = [&] {
        for (int m = 0; m < kept.size; ++m) {
            const std::uint64_t attributes = mix64(kept.attribute_counter[m]);
            double wx = fixed_wx, wy = fixed_wy, wn = fixed_wn, damp = fixed_damping;
            if (!fixed) sliced(frequency_of(attributes), wx, wy, wn, damp);
            // Phase: the in-plane harmonic plus the slicing shift 2π h (n·ω) (eq. 6).
            batch.add(float(-pi_a2 * kept.q[m] - damp), float(wx * kept.u[m] + wy * kept.v[m] + kept.h[m] * wn), attributes);
        }
        kept.size = 0;
    };
    std::int64_t k0, k1, j0, j1;
    cell_span(p[2], extent[2], s, k0, k1);
    cell_span(p[1], extent[1], s, j0, j1);
    for (std::int64_t k = k0; k <= k1; ++k) {
        const double cell_dz = k * s - p[2];
        for (std::int64_t j = j0; j <= j1; ++j) {
            const double cell_dy = j * s - p[1];
            RowSpan span;
            if (!row_span_3d(support, r2, cell_dy, cell_dy + s, cell_dz, cell_dz + s, span)) continue;
            const std::int64_t i0 = floor_index((p[0] + span.lo) / s), i1 = floor_index((p[0] + span.hi) / s);
            for (std::int64_t i = i0; i <= i1; ++i) {
                const double cell_dx = i * s - p[0];
                if (kept.full()) evaluate_kept();
                const std::uint64_t key = cell_key_3d(i, j, k);
                const std::uint64_t bits = mix64(key);
                const double dx = -(cell_dx + position_fraction(bits) * s), dy = -(cell_dy + position_fraction(bits >> 21) * s);
                const double dz = -(cell_dz + position_fraction(bits >> 42) * s);
                const double h = n[0] * dx + n[1] * dy + n[2] * dz;
                const double pt = t[0] * dx + t[1] * dy + t[2] * dz, pb = b[0] * dx + b[1] * dy + b[2] * dz;
                kept.push(pt, pb, h, h * h + inverse.quadratic_form(pt, pb), r2, key + attribute_offset);
            }
        }
    }
    evaluate_kept();
    batch.flush();
    const double gain = gain_3d_ * filter.amplitude;
    for (int c = 0; c < parameters_.channels; ++c) out[c] = float(batch.sum[c] * gain);
}

std::vector<GaborNoise::Impulse> GaborNoise::impulses_near_2d(double x, double y) const
{
    std::vector<Impulse> impulses;
    std::int64_t i0, i1, j0, j1;
    cell_span(x, radius_, cell_x_, i0, i1);
    cell_span(y, radius_, cell_y_, j0, j1);
    for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t i = i0; i <= i1; ++i) {
            const std::uint64_t key = cell_key_2d(i, j), bits = mix64(key), attributes = mix64(key + attribute_offset);
            const Vec3 omega = frequency_of(attributes);
            Impulse impulse{{(i + position_fraction(bits)) * cell_x_, (j + position_fraction(bits >> 21)) * cell_y_, 0},
                            {omega[0], omega[1], 0}, {}};
            for (int c = 0; c < max_channels; ++c) impulse.phase[c] = phase_angle(phase_index(attributes, c));
            impulses.push_back(impulse);
        }
    return impulses;
}

std::vector<GaborNoise::Impulse> GaborNoise::impulses_near_3d(const Vec3& p) const
{
    std::vector<Impulse> impulses;
    const double s = cell_3d_;
    std::int64_t lo[3], hi[3];
    for (int e = 0; e < 3; ++e) cell_span(p[e], radius_, s, lo[e], hi[e]);
    for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            for (std::int64_t i = lo[0]; i <= hi[0]; ++i) {
                const std::uint64_t key = cell_key_3d(i, j, k), bits = mix64(key), attributes = mix64(key + attribute_offset);
                Impulse impulse{{(i + position_fraction(bits)) * s, (j + position_fraction(bits >> 21)) * s,
                                 (k + position_fraction(bits >> 42)) * s},
                                frequency_of(attributes), {}};
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
        sum += std::exp(-M_PI * a * a * d2) *
               std::cos(2 * M_PI * (impulse.omega[0] * dx + impulse.omega[1] * dy) + impulse.phase[channel]);
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
        sum += std::exp(-M_PI * a * a * d2) * std::cos(2 * M_PI * dot3(impulse.omega, d) + impulse.phase[channel]);
    }
    return sum * gain_3d_;
}

}  // namespace stochtex
