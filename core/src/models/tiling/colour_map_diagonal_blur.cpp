#include "models/tiling/colour_map_diagonal_blur.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace stochtex {

namespace {

/// The bilinear map at texel coordinates (x, y), clamped to its texel centres (ColourMapFilter::fetch).
double bilinear(const std::vector<float>& rgb, int size, double x, double y, int c)
{
    x = std::clamp(x, 0.0, double(size - 1)), y = std::clamp(y, 0.0, double(size - 1));
    const int x0 = std::min(int(x), size - 2), y0 = std::min(int(y), size - 2);
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int xi, int yi) { return double(rgb[(std::size_t(yi) * size + std::size_t(xi)) * 3 + std::size_t(c)]); };
    return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) + (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}

}  // namespace

std::vector<std::vector<float>> diagonal_blurs(const std::vector<float>& rgb, int size, int sign, int levels)
{
    // Half-step Simpson weights of each level: offset j/2 steps, j = −m…m, Gaussian × (1 on
    // whole steps, 2 on half steps: Simpson's 2/6 and 4/6), normalised.
    std::vector<std::vector<double>> weights;
    int reach = 0;  // whole steps the widest level reads on either side
    for (int k = 1; k <= levels; ++k) {
        const double sigma = std::ldexp(1.0, k - 1);
        const int m = 2 * int(std::ceil(4 * sigma));
        std::vector<double> w;
        double total = 0;
        for (int j = -m; j <= m; ++j) {
            const double s = 0.5 * j / sigma;
            w.push_back(std::exp(-0.5 * s * s) * (j % 2 == 0 ? 1 : 2));
            total += w.back();
        }
        for (double& v : w) v /= total;
        weights.push_back(std::move(w));
        reach = std::max(reach, m / 2 + 1);
    }
    std::vector<std::vector<float>> out(std::size_t(levels), std::vector<float>(std::size_t(size) * size * 3 + 1, 0.0f));
    // One line of the diagonal at a time: texels (x0 + i, y0 + sign · i), i < n. The path's
    // values at whole steps (`whole`) and half steps (`half`), `reach` steps past either end.
    const std::size_t span = std::size_t(size + 2 * reach);
    std::vector<double> whole(span), half(span), sum(span);
    for (int line = 0; line < 2 * size - 1; ++line) {
        int x0, y0, n;
        if (sign > 0) {  // x − y = line − (size − 1)
            const int c = line - (size - 1);
            x0 = std::max(c, 0), y0 = std::max(-c, 0), n = size - std::abs(c);
        } else {  // x + y = line
            x0 = std::max(0, line - (size - 1)), y0 = std::min(line, size - 1), n = std::min(line, 2 * size - 2 - line) + 1;
        }
        for (int c = 0; c < 3; ++c) {
            for (std::size_t q = 0; q < std::size_t(n + 2 * reach); ++q) {
                const double s = double(q) - reach;
                whole[q] = bilinear(rgb, size, x0 + s, y0 + sign * s, c);
                half[q] = bilinear(rgb, size, x0 + s + 0.5, y0 + sign * (s + 0.5), c);
            }
            for (int k = 0; k < levels; ++k) {
                const std::vector<double>& w = weights[std::size_t(k)];
                const int m = int(w.size() / 2);
                std::fill(sum.begin(), sum.begin() + n, 0.0);
                // Offset j/2: whole[i + j/2 + reach] for even j, half[i + (j − 1)/2 + reach] for odd j;
                // outputs vectorise along the line.
                for (int j = -m; j <= m; ++j) {
                    const double wj = w[std::size_t(j + m)];
                    const int q = (j - (j & 1)) / 2 + reach;  // floor(j / 2) + reach
                    const double* __restrict source = ((j & 1) ? half.data() : whole.data()) + q;
                    double* __restrict target = sum.data();
                    for (int i = 0; i < n; ++i) target[i] += wj * source[i];
                }
                float* table = out[std::size_t(k)].data();
                for (int i = 0; i < n; ++i)
                    table[(std::size_t(y0 + sign * i) * size + std::size_t(x0 + i)) * 3 + std::size_t(c)] = float(sum[std::size_t(i)]);
            }
        }
    }
    return out;
}

}  // namespace stochtex
