// Deterministic random numbers: SplitMix64 (Steele et al. 2014). Tiny, fast, statistically
// good for seeding and for the handful of draws a texture needs (tiles, offsets); every
// sequence is a pure function of its seed, so textures are reproducible everywhere.
#pragma once

#include "numerics/constants.h"

#include <cmath>
#include <cstdint>

namespace stochtex {

class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next()
    {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1) with 53 random bits.
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }
    /// Standard normal (Box–Muller; one value per call keeps the sequence simple).
    double gaussian()
    {
        const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
    }

private:
    std::uint64_t state_;
};

/// Mixes several integers into one seed (for per-band, per-channel streams).
inline std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b, std::uint64_t c = 0)
{
    SplitMix64 mixer(a * 0x9e3779b97f4a7c15ull ^ (b + 0x632be59bd9b4e019ull) ^ (c * 0xd6e8feb86659fd93ull));
    return mixer.next();
}

}  // namespace stochtex
