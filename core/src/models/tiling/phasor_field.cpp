#include "models/tiling/phasor_field.h"

#include "numerics/random.h"

#include <stochtex/error.h>

#include <cmath>
#include <complex>

namespace stochtex {

std::array<std::vector<float>, 2> phasor_field(const PhasorFieldOptions& options)
{
    const int n = options.size;
    if (n < 16 || (n & (n - 1))) throw Error("phasor field: size must be a power of two ≥ 16");
    if (!(options.frequency > 0 && options.frequency <= 0.5)) throw Error("phasor field: frequency must be in (0, 0.5] cycles per pixel");
    // Kernel: exp(−π a² r²) falls to 1 % at r = sqrt(ln 100 / π) / a; a = f/2 spans ~2.5 wavelengths.
    const double a = 0.5 * options.frequency;
    const double radius = std::sqrt(std::log(100.0) / M_PI) / a;
    const double kernel_area = M_PI * radius * radius;
    const int impulses = std::max(1, int(std::lround(options.impulses_per_kernel * double(n) * n / kernel_area)));
    std::vector<std::complex<double>> field(std::size_t(n) * n, 0.0);
    SplitMix64 rng(mix_seed(options.seed, 0x9a50, 0));
    const int reach = int(std::ceil(radius));
    for (int k = 0; k < impulses; ++k) {
        const double cx = n * rng.uniform(), cy = n * rng.uniform();
        const double angle = options.orientation + options.orientation_spread * (rng.uniform() - 0.5);
        const double fx = options.frequency * std::cos(angle), fy = options.frequency * std::sin(angle);
        const double phase = 2 * M_PI * rng.uniform();
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx) {
                // Pixel centres around the impulse; the wrapped pixel receives the kernel.
                const int px = int(std::floor(cx)) + dx, py = int(std::floor(cy)) + dy;
                const double rx = px + 0.5 - cx, ry = py + 0.5 - cy;
                const double r2 = rx * rx + ry * ry;
                if (r2 > radius * radius) continue;
                const double envelope = std::exp(-M_PI * a * a * r2);
                const double theta = 2 * M_PI * (fx * rx + fy * ry) + phase;
                field[std::size_t((py % n + n) % n) * n + std::size_t((px % n + n) % n)] +=
                    envelope * std::complex<double>(std::cos(theta), std::sin(theta));
            }
    }
    std::array<std::vector<float>, 2> pair;
    for (auto& plane : pair) plane.resize(field.size());
    for (std::size_t i = 0; i < field.size(); ++i) {
        const double phi = std::arg(field[i]);
        pair[0][i] = float(0.5 + 0.5 * std::sin(phi));
        pair[1][i] = float(0.5 + 0.5 * std::cos(phi));
    }
    return pair;
}

}  // namespace stochtex
