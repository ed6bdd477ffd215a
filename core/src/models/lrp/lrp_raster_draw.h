// A lattice row's terms drawn lane-parallel (lrp_raster_draw.cpp, Highway, dispatched to the best
// instruction set of the CPU at run time): the lattice points of the row are the lanes.
//
// LrpStratumNoise::draw's random numbers are counter-based — term t of a point takes SplitMix64's
// outputs 2t + 1 and 2t + 2 from the point's seed, mix(seed + n·γ) — so every point's and every
// term's draw is independent of the others. The kernels repeat draw()'s integer and IEEE
// operations lane by lane (64-bit lanes for the random bits and the frequencies, which draw()
// takes in double; float lanes of the same count for the coefficients), without fused
// multiply-add: the same bits as draw() on every target, at any vector width. The tables it
// reads pack two 32-bit values per 64-bit entry: one gather fetches both.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stochtex::lrp_raster {

/// One lattice row's draw: term t of point w goes to [t · stride + w] of each output plane,
/// for w < count and t < terms (lanes up to the next multiple of 16 past `count` are written too,
/// with values of no meaning: the caller clears them).
struct TermRow {
    const std::uint64_t* seed = nullptr;  ///< per point: draw()'s SplitMix64 seed (readable to a multiple of 16)
    std::size_t count = 0;
    int terms = 0;
    const std::uint32_t* first = nullptr;  ///< sub-stratum t's bins: [first[t], first[t + 1])
    const std::uint64_t* bins = nullptr;   ///< every bin's kx, ky as int32 bits, kx in the low half
    double inverse_size = 0;
    double period[2] = {0, 0};  ///< periodic: frequencies snap to multiples of 1/period (both > 0), else zeros
    float amplitude[3] = {0, 0, 0};
    bool shared_phase = false;
    int phase_bits = 0;              ///< PhaseTable::bits: channel c's phase at bits [c · phase_bits, …) unless shared
    const std::uint64_t* phases = nullptr;  ///< PhaseTable's cosine, sine as float bits, cosine in the low half
    const float* response = nullptr;  ///< the filter's response per [t · stride + w]; null: 1 (no filter)
    std::size_t stride = 0;
    float* fx = nullptr;
    float* fy = nullptr;
    double* fx_exact = nullptr;  ///< the frequencies before their rounding to float (for the filter), or null
    double* fy_exact = nullptr;
    float* re[3] = {nullptr, nullptr, nullptr};
    float* im[3] = {nullptr, nullptr, nullptr};
};

/// fx, fy (and fx_exact, fy_exact where given) of every term: draw()'s bin, jitter and snap.
void draw_frequencies(const TermRow& row);

/// re, im of every term: draw()'s phases times amplitude · response.
void draw_coefficients(const TermRow& row);

}  // namespace stochtex::lrp_raster
