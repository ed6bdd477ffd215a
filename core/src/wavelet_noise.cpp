#include "wavelet_noise.h"

#include "random.h"

#include <cassert>

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
void down_up_sample(const float* from, float* to, int n, int stride)
{
    std::vector<float> half(n / 2);
    for (int i = 0; i < n / 2; ++i) {
        float sum = 0;
        for (int k = 2 * i - analysis_radius; k < 2 * i + analysis_radius; ++k)
            sum += analysis_filter[k - 2 * i + analysis_radius] * from[wrap(k, n) * stride];
        half[i] = sum;
    }
    for (int i = 0; i < n; ++i) {
        float sum = 0;
        for (int k = i / 2; k <= i / 2 + 1; ++k)
            sum += refinement_filter[i - 2 * k + 2] * half[wrap(k, n / 2)];
        to[i * stride] = sum;
    }
}

/// Builds a d-dimensional periodic coefficient tile (d = 2 or 3).
std::vector<float> make_coefficients(int n, int dims, std::uint64_t seed)
{
    const std::size_t count = dims == 2 ? std::size_t(n) * n : std::size_t(n) * n * n;
    std::vector<float> noise(count);
    SplitMix64 rng(seed);
    for (float& value : noise) value = float(rng.gaussian());

    // Subtract the half-resolution part, one axis at a time (separable filters).
    std::vector<float> smooth = noise;
    std::vector<float> line(n), filtered(n);
    const std::size_t strides[3] = {1, std::size_t(n), std::size_t(n) * n};
    for (int axis = 0; axis < dims; ++axis) {
        const std::size_t stride = strides[axis];
        for (std::size_t start = 0; start < count; ++start) {
            // Visit each line along `axis` once: starts are the indices whose axis coordinate is 0.
            if ((start / stride) % n != 0) continue;
            for (int i = 0; i < n; ++i) line[i] = smooth[start + i * stride];
            down_up_sample(line.data(), filtered.data(), n, 1);
            for (int i = 0; i < n; ++i) smooth[start + i * stride] = filtered[i];
        }
    }
    for (std::size_t i = 0; i < count; ++i) noise[i] -= smooth[i];

    // Cook–DeRose: even and odd lattice positions have different variance after the filtering;
    // adding a copy shifted by an odd offset evens it out.
    const int shift = n / 2 + 1;
    std::vector<float> shifted(count);
    if (dims == 2) {
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                shifted[std::size_t(y) * n + x] = noise[std::size_t(wrap(y + shift, n)) * n + wrap(x + shift, n)];
    } else {
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    shifted[(std::size_t(z) * n + y) * n + x] =
                        noise[(std::size_t(wrap(z + shift, n)) * n + wrap(y + shift, n)) * n + wrap(x + shift, n)];
    }
    for (std::size_t i = 0; i < count; ++i) noise[i] += shifted[i];
    return noise;
}

}  // namespace

WaveletNoise2D::WaveletNoise2D(int tile_size, std::uint64_t tile_seed)
    : size_(tile_size), mask_(tile_size - 1), coefficients_(make_coefficients(tile_size, 2, tile_seed))
{
    assert((tile_size & mask_) == 0 && "tile size must be a power of two");
    // σ_N²: mean of N² on a 4×4-per-cell grid over one period. The integrand is a smooth
    // periodic function, so this regular average is accurate to far below sampling noise.
    constexpr int sub = 4;
    double sum = 0;
    for (int j = 0; j < size_ * sub; ++j)
        for (int i = 0; i < size_ * sub; ++i) {
            const double value = eval((i + 0.5) / sub, (j + 0.5) / sub);
            sum += value * value;
        }
    variance_ = sum / (double(size_) * size_ * sub * sub);

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
    // enough points for ~0.5 % accuracy at a cost of ~4^j · 4096 evaluations.
    constexpr int cells = 64;
    const int per_cell = 1 << j;
    const double step = std::ldexp(1.0, -j);
    double sum = 0;
    for (int y = 0; y < cells * per_cell; ++y)
        for (int x = 0; x < cells * per_cell; ++x) {
            const double value = eval(x * step + phase, y * step + phase);
            sum += value * value;
        }
    return sum / (double(cells) * per_cell * cells * per_cell);
}

float WaveletNoise2D::eval(double x, double y) const
{
    const QuadraticBSplineWeights wx(x), wy(y);
    float result = 0;
    for (int j = 0; j < 3; ++j) {
        const float* row = &coefficients_[std::size_t((wy.first + j) & mask_) * size_];
        const float row_sum = wx.w[0] * row[(wx.first) & mask_] + wx.w[1] * row[(wx.first + 1) & mask_] +
                              wx.w[2] * row[(wx.first + 2) & mask_];
        result += wy.w[j] * row_sum;
    }
    return result;
}

const WaveletNoise2D& WaveletNoise2D::shared()
{
    static const WaveletNoise2D tile(shared_tile_2d, shared_tile_seed);
    return tile;
}

WaveletNoise3D::WaveletNoise3D(int tile_size, std::uint64_t tile_seed)
    : size_(tile_size), mask_(tile_size - 1), coefficients_(make_coefficients(tile_size, 3, tile_seed + 1))
{
    assert((tile_size & mask_) == 0 && "tile size must be a power of two");
    constexpr int sub = 2;
    double sum = 0;
    const int n = size_ * sub;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double value = eval((i + 0.25) / sub, (j + 0.25) / sub, (k + 0.25) / sub);
                sum += value * value;
            }
    variance_ = sum / (double(n) * n * n);
}

float WaveletNoise3D::eval(double x, double y, double z) const
{
    const QuadraticBSplineWeights wx(x), wy(y), wz(z);
    float result = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t plane = std::size_t((wz.first + k) & mask_) * size_;
        float plane_sum = 0;
        for (int j = 0; j < 3; ++j) {
            const float* row = &coefficients_[(plane + ((wy.first + j) & mask_)) * size_];
            plane_sum += wy.w[j] * (wx.w[0] * row[wx.first & mask_] + wx.w[1] * row[(wx.first + 1) & mask_] +
                                    wx.w[2] * row[(wx.first + 2) & mask_]);
        }
        result += wz.w[k] * plane_sum;
    }
    return result;
}

const WaveletNoise3D& WaveletNoise3D::shared()
{
    static const WaveletNoise3D tile(shared_tile_3d, shared_tile_seed);
    return tile;
}

}  // namespace stochtex
