#include "models/wavelet/wavelet_noise.h"

#include "models/wavelet/wavelet_raster_kernels.h"
#include "numerics/random.h"

#include <algorithm>
#include <cassert>
#include <climits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace stochtex {

namespace {

// Tile sizes: the finest band repeats every tile_size exemplar pixels, so the 2D tile is large
// (256² floats = 256 KiB, cache-resident). The 3D tile trades period for memory (64³ = 1 MiB).
constexpr int shared_tile_2d = 256;
constexpr int shared_tile_3d = 64;
constexpr std::uint64_t shared_tile_seed = 0x5eed'2005'c00cull;

// Cook–DeRose's analysis filter for quadratic B-splines (16 taps each side) and the 2-scale
// refinement filter of the quadratic B-spline.
constexpr int analysis_radius = 16;
constexpr float analysis_filter[2 * analysis_radius] = {
    0.000334f, -0.001528f, 0.000410f,  0.003545f,  -0.000938f, -0.008233f, 0.002172f,  0.019120f,
    -0.005040f, -0.044412f, 0.011655f, 0.103311f,  -0.025936f, -0.243780f, 0.033979f,  0.655340f,
    0.655340f,  0.033979f,  -0.243780f, -0.025936f, 0.103311f,  0.011655f,  -0.044412f, -0.005040f,
    0.019120f,  0.002172f,  -0.008233f, -0.000938f, 0.003546f,  0.000410f,  -0.001528f, 0.000334f};
constexpr float refinement_filter[4] = {0.25f, 0.75f, 0.75f, 0.25f};

int wrap(int i, int n) { return ((i % n) + n) % n; }

/// from (n samples, given stride) → its projection on the half-resolution spline space,
/// upsampled back to n samples. This is the part of the noise that survives at half resolution.
/// The line is first copied with its periodic continuation on each side, so the filters index
/// it directly (no modulo per tap: the tiles are built at every start of a process, and the
/// 64³ solid tile runs this on 12 288 lines); the sums are the same, in the same order.
void down_up_sample(const float* from, float* to, int n, int stride, std::vector<float>& padded, std::vector<float>& half)
{
    padded.resize(std::size_t(n) + 2 * analysis_radius);
    for (int i = -analysis_radius; i < n + analysis_radius; ++i)
        padded[std::size_t(i + analysis_radius)] = from[wrap(i, n) * stride];
    half.resize(std::size_t(n / 2) + 2);
    for (int i = 0; i < n / 2; ++i) {
        float sum = 0;
        const float* window = &padded[std::size_t(2 * i)];  // sample 2i − radius
        for (int t = 0; t < 2 * analysis_radius; ++t) sum += analysis_filter[t] * window[t];
        half[std::size_t(i)] = sum;
    }
    half[std::size_t(n / 2)] = half[0];  // the periodic continuation the refinement reads
    half[std::size_t(n / 2) + 1] = half[1 % (n / 2)];
    for (int i = 0; i < n; ++i) {
        float sum = 0;
        for (int k = i / 2; k <= i / 2 + 1; ++k) sum += refinement_filter[i - 2 * k + 2] * half[std::size_t(k)];
        to[i * stride] = sum;
    }
}

/// Builds a periodic coefficient tile of size[0] × size[1] (× size[2] if dims = 3) cells.
std::vector<float> make_coefficients(const int* size, int dims, std::uint64_t seed)
{
    std::size_t count = 1;
    for (int axis = 0; axis < dims; ++axis) count *= std::size_t(size[axis]);
    std::vector<float> noise(count);
    SplitMix64 rng(seed);
    for (float& value : noise) value = float(rng.gaussian());

    // Subtract the half-resolution part, one axis at a time (separable filters).
    std::vector<float> smooth = noise;
    std::size_t strides[3] = {1, 1, 1};
    for (int axis = 1; axis < dims; ++axis) strides[axis] = strides[axis - 1] * std::size_t(size[axis - 1]);
    for (int axis = 0; axis < dims; ++axis) {
        const std::size_t stride = strides[axis];
        const int n = size[axis];
        std::vector<float> line(n), filtered(n), padded, half;
        for (std::size_t start = 0; start < count; ++start) {
            // Visit each line along `axis` once: starts are the indices whose axis coordinate is 0.
            if ((start / stride) % n != 0) continue;
            for (int i = 0; i < n; ++i) line[i] = smooth[start + i * stride];
            down_up_sample(line.data(), filtered.data(), n, 1, padded, half);
            for (int i = 0; i < n; ++i) smooth[start + i * stride] = filtered[i];
        }
    }
    for (std::size_t i = 0; i < count; ++i) noise[i] -= smooth[i];

    // Cook–DeRose: even and odd lattice positions have different variance after the filtering;
    // adding a copy shifted by an odd offset along every axis evens it out.
    std::vector<float> shifted(count);
    for (std::size_t i = 0; i < count; ++i) {
        std::size_t source = 0;
        for (int axis = 0; axis < dims; ++axis) {
            const int n = size[axis];
            const int coordinate = int((i / strides[axis]) % std::size_t(n));
            source += std::size_t(wrap(coordinate + n / 2 + 1, n)) * strides[axis];
        }
        shifted[i] = noise[source];
    }
    for (std::size_t i = 0; i < count; ++i) noise[i] += shifted[i];
    return noise;
}

/// Exact spatial mean of N² over one period of a 2D tile. With N = Σ c_kl B(x−k) B(y−l),
/// ∫∫N² = Σ_ab A(a) A(b) R(a, b): R the coefficients' periodic autocorrelation and A the
/// quadratic B-spline's autocorrelation at integer lags (the quintic B-spline: 11/20, 13/60,
/// 1/120 at lags 0, ±1, ±2).
double exact_variance_2d(const std::vector<float>& c, int nx, int ny)
{
    constexpr double spline_autocorrelation[5] = {1.0 / 120, 13.0 / 60, 11.0 / 20, 13.0 / 60, 1.0 / 120};
    double sum = 0;
    for (int b = -2; b <= 2; ++b)
        for (int a = -2; a <= 2; ++a) {
            double r = 0;
            for (int y = 0; y < ny; ++y) {
                const float* row = &c[std::size_t(y) * nx];
                const float* other = &c[std::size_t(wrap(y + b, ny)) * nx];
                for (int x = 0; x < nx; ++x) r += double(row[x]) * other[wrap(x + a, nx)];
            }
            sum += spline_autocorrelation[a + 2] * spline_autocorrelation[b + 2] * r;
        }
    return sum / (double(nx) * ny);
}

}  // namespace

WaveletNoise2D::WaveletNoise2D(int period_x, int period_y, std::uint64_t tile_seed)
    : nx_(period_x), ny_(period_y), inverse_nx_(1.0 / period_x), inverse_ny_(1.0 / period_y),
      mask_x_((period_x & (period_x - 1)) == 0 ? period_x - 1 : -1),
      mask_y_((period_y & (period_y - 1)) == 0 ? period_y - 1 : -1)
{
    if (period_x < 4 || period_y < 4 || period_x % 2 || period_y % 2)
        throw std::invalid_argument("wavelet noise tile: periods must be even and at least 4");
    const int size[2] = {nx_, ny_};
    coefficients_ = make_coefficients(size, 2, tile_seed);
    const int padded_width = nx_ + 3;
    padded_.resize(std::size_t(padded_width) * (ny_ + 3));
    for (int y = 0; y < ny_ + 3; ++y)
        for (int x = 0; x < padded_width; ++x)
            padded_[std::size_t(y) * padded_width + x] = coefficients_[std::size_t(wrap(y, ny_)) * nx_ + wrap(x, nx_)];
    variance_ = exact_variance_2d(coefficients_, nx_, ny_);

    for (int j = 0; j < balanced_phase_count; ++j) {
        // Bracket the root between the lowest and highest grid variance over one phase period,
        // then bisect (the variance is a smooth periodic function of the phase).
        const double period = std::ldexp(1.0, -j);
        constexpr int probes = 16;
        double lo = 0, hi = 0, v_lo = 1e300, v_hi = -1e300;
        for (int i = 0; i < probes; ++i) {
            const double phase = period * i / probes, v = grid_variance(j, phase);
            if (v < v_lo) v_lo = v, lo = phase;
            if (v > v_hi) v_hi = v, hi = phase;
        }
        for (int iteration = 0; iteration < 20; ++iteration) {
            const double mid = 0.5 * (lo + hi);
            (grid_variance(j, mid) < variance_ ? lo : hi) = mid;
        }
        balanced_phase_[j] = std::fmod(0.5 * (lo + hi) + period, period);
    }
}

double WaveletNoise2D::grid_variance(int j, double phase) const
{
    // Mean of N² over the grid {(k + phase, l + phase) · 2^-j}, on a 64×64-cell region:
    // enough points for ~0.5 % accuracy. Every tile runs this ~100 times when it is built, so
    // it is evaluated as a raster (each row's three coefficient rows combined once, each
    // column's spline once), with eval()'s arithmetic in eval()'s order: the same sum.
    constexpr int cells = 64;
    const int size = cells << j;
    const double step = std::ldexp(1.0, -j);
    std::vector<LatticeSpline> columns(static_cast<std::size_t>(size));
    std::int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (int x = 0; x < size; ++x) {
        columns[std::size_t(x)] = spline_x(x * step + phase);
        lo = std::min(lo, columns[std::size_t(x)].first), hi = std::max(hi, columns[std::size_t(x)].first + 2);
    }
    std::vector<float> combined(std::size_t(hi - lo + 1));
    const std::size_t width = padded_width();
    double sum = 0;
    for (int y = 0; y < size; ++y) {
        const LatticeSpline row = spline_y(y * step + phase);
        const float* coefficients = padded_row(row.first);
        for (std::int64_t k = lo; k <= hi; ++k) combined[std::size_t(k - lo)] = combine_rows(row, coefficients + k, width);
        for (const LatticeSpline& sx : columns) {
            const float* at = &combined[std::size_t(sx.first - lo)];
            const double value = sx.w[0] * at[0] + sx.w[1] * at[1] + sx.w[2] * at[2];
            sum += value * value;
        }
    }
    return sum / (double(size) * size);
}

const WaveletNoise2D& WaveletNoise2D::shared()
{
    static const WaveletNoise2D tile(shared_tile_2d, shared_tile_2d, shared_tile_seed);
    return tile;
}

const WaveletNoise2D& WaveletNoise2D::with_period(int period_x, int period_y)
{
    if (period_x == shared_tile_2d && period_y == shared_tile_2d) return shared();
    if (period_x > 1024 || period_y > 1024)
        throw std::invalid_argument("wavelet noise tile: periods above 1024 are not cached");
    static std::mutex mutex;
    static std::map<std::pair<int, int>, std::unique_ptr<const WaveletNoise2D>> tiles;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& tile = tiles[{period_x, period_y}];
    if (!tile) tile = std::make_unique<const WaveletNoise2D>(period_x, period_y, mix_seed(shared_tile_seed, period_x, period_y));
    return *tile;
}

WaveletNoise3D::WaveletNoise3D(int tile_size, std::uint64_t tile_seed)
    : size_(tile_size), mask_(tile_size - 1)
{
    const int size[3] = {tile_size, tile_size, tile_size};
    coefficients_ = make_coefficients(size, 3, tile_seed + 1);
    assert((tile_size & mask_) == 0 && "tile size must be a power of two");
    // Mean of N² on a grid of (2 · size)³ points, evaluated row by row (eval_row: the same values
    // as eval(), a fraction of the work), summed in eval()'s loop order.
    constexpr int sub = 2;
    double sum = 0;
    const int n = size_ * sub;
    std::vector<float> row(std::size_t(size_) + 2);
    std::vector<QuadraticBSplineWeights> columns;
    for (int i = 0; i < n; ++i) columns.emplace_back((i + 0.25) / sub);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j) {
            eval_row((j + 0.25) / sub, (k + 0.25) / sub, row.data());
            for (const QuadraticBSplineWeights& wx : columns) {
                const float* at = &row[std::size_t(wx.first & mask_)];
                const double value = wx.w[0] * at[0] + wx.w[1] * at[1] + wx.w[2] * at[2];
                sum += value * value;
            }
        }
    variance_ = sum / (double(n) * n * n);
}

float WaveletNoise3D::eval(double x, double y, double z) const
{
    const QuadraticBSplineWeights wx(x), wy(y), wz(z);
    float column[3];
    for (int i = 0; i < 3; ++i) {
        const std::size_t cx = std::size_t((wx.first + i) & mask_);
        float plane[3];
        for (int k = 0; k < 3; ++k) {
            const std::size_t slab = std::size_t((wz.first + k) & mask_) * size_;
            const float* r[3];
            for (int j = 0; j < 3; ++j) r[j] = &coefficients_[(slab + std::size_t((wy.first + j) & mask_)) * size_];
            plane[k] = wy.w[0] * r[0][cx] + wy.w[1] * r[1][cx] + wy.w[2] * r[2][cx];
        }
        column[i] = wz.w[0] * plane[0] + wz.w[1] * plane[1] + wz.w[2] * plane[2];
    }
    return wx.w[0] * column[0] + wx.w[1] * column[1] + wx.w[2] * column[2];
}

void WaveletNoise3D::eval_row(double y, double z, float* columns) const
{
    const QuadraticBSplineWeights wy(y), wz(z);
    const float* rows[9];
    for (int k = 0; k < 3; ++k) {
        const std::size_t slab = std::size_t((wz.first + k) & mask_) * size_;
        for (int j = 0; j < 3; ++j) rows[3 * k + j] = &coefficients_[(slab + std::size_t((wy.first + j) & mask_)) * size_];
    }
    wavelet_raster::combine_planes(wz.w, wy.w, rows, std::size_t(size_), columns);
    columns[size_] = columns[0];
    columns[size_ + 1] = columns[1];
}

const WaveletNoise3D& WaveletNoise3D::shared()
{
    static const WaveletNoise3D tile(shared_tile_3d, shared_tile_seed);
    return tile;
}

}  // namespace stochtex
