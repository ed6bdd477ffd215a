#include "models/lrp/lrp_structure_fit.h"

#include "models/lrp/discrete_spectrum.h"
#include "spectra/fft.h"
#include "models/lrp/lrp_parameters.h"
#include "models/lrp/lrp_spectrum_sampling.h"
#include "models/lrp/lrp_structure_noise.h"
#include "schema/parameter_schema.h"
#include "numerics/constants.h"

#include <stochtex/error.h>
#include <stochtex/models/lrp_parameters.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

namespace stochtex {

namespace {

/// Stored coefficients are rounded to a decimal step of about 1/1000 of the largest one: the
/// error this adds (≲ 1e-4 per cosine) stays far below the 1/256 tolerance, and the text is short.
constexpr double coefficient_resolution = 1e-3;

/// Chooses the structure's decimal step (a power of ten) and rounds every coefficient to it.
void quantise(LrpStructure& structure)
{
    double largest = 0;
    for (const LrpBlock& block : structure.blocks)
        for (const auto& channel : block.coefficients)
            for (double c : channel) largest = std::max(largest, std::abs(c));
    if (!(largest > 0)) return;
    structure.coefficient_step = std::pow(10.0, std::floor(std::log10(largest * coefficient_resolution)));
    // A .stex stores steps in [1e-12, 1] (lrp_parameters.cpp): say so here, in the photo's terms,
    // rather than let the fitted description fail validation with a step the user never chose.
    if (!(structure.coefficient_step >= 1e-12 && structure.coefficient_step <= 1))
        throw Error("lrp: the photo's structure coefficients reach " + number_text(largest) +
                    ", outside what a .stex stores (1e-9 to 1e4); scale the photo's values");
    for (LrpBlock& block : structure.blocks)
        for (auto& channel : block.coefficients)
            for (double& c : channel) c = double(std::llround(c / structure.coefficient_step)) * structure.coefficient_step;
}

struct HalfBin {
    int kx, ky;
    double energy;  // over the three channels, both bins of a pair
};

/// The half-plane bins of a size² centred spectrum (DC included when asked), by decreasing energy.
std::vector<HalfBin> bins_by_energy(const std::array<std::vector<std::complex<double>>, 3>& spectrum, int size,
                                    bool with_dc)
{
    std::vector<HalfBin> bins;
    DiscreteSpectrum layout(size);
    for (int ky = -size / 2; ky < size / 2; ++ky)
        for (int kx = -size / 2; kx < size / 2; ++kx) {
            if (kx == 0 && ky == 0 && !with_dc) continue;
            const std::size_t i = layout.index(kx, ky), m = layout.index(mirror_bin(kx, size), mirror_bin(ky, size));
            if (i < m) continue;
            double energy = 0;
            for (int c = 0; c < 3; ++c) energy += std::norm(spectrum[std::size_t(c)][i]);
            bins.push_back({kx, ky, energy * (i == m ? 1 : 2)});
        }
    std::stable_sort(bins.begin(), bins.end(), [](const HalfBin& a, const HalfBin& b) { return a.energy > b.energy; });
    return bins;
}

/// The full centred spectrum of each channel of a size² three-plane image (periodic, as is).
std::array<std::vector<std::complex<double>>, 3> spectra(const std::array<std::vector<float>, 3>& planes, int size,
                                                         bool periodic_component)
{
    std::array<std::vector<std::complex<double>>, 3> result;
    for (int c = 0; c < 3; ++c) {
        const auto half = periodic_component ? periodic_component_fft_2d(planes[std::size_t(c)], size, size)
                                             : real_fft_2d(planes[std::size_t(c)], size, size);
        result[std::size_t(c)] = full_fourier_coefficients(half, size);
    }
    return result;
}

/// The T×T image whose centred Fourier coefficients are `spectrum` restricted to `region`.
std::vector<float> restricted_image(const std::vector<std::complex<double>>& spectrum, const std::vector<char>& region,
                                    int size)
{
    const int half_width = size / 2 + 1;
    std::vector<std::complex<float>> half(std::size_t(half_width) * size);
    DiscreteSpectrum layout(size);
    for (int ky = 0; ky < size; ++ky)
        for (int kx = 0; kx < half_width; ++kx) {
            const std::size_t i = layout.index(centred_bin(kx, size), centred_bin(ky, size));
            if (region[i]) half[std::size_t(ky) * half_width + kx] = std::complex<float>(spectrum[i]);
        }
    return real_inverse_fft_2d(half, size, size);
}

/// n_R of `structure` (no placement, no turbulence) at the crop's pixels.
std::array<std::vector<float>, 3> reconstruct(const LrpStructure& structure, int size)
{
    LrpStructure plain = structure;
    plain.random_placement = false;
    plain.turbulence = 0;
    const LrpStructureNoise noise(plain, size, {}, {});
    std::vector<LrpTerms> blocks(std::size_t(noise.block_count()));
    for (int b = 0; b < noise.block_count(); ++b) noise.draw_block(b, LrpFilter{}, blocks[std::size_t(b)]);
    std::array<std::vector<float>, 3> image;
    for (auto& plane : image) plane.resize(std::size_t(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            float value[3];
            noise.eval_structure(x, y, [&](int b) { return blocks[std::size_t(b)].view(); }, value);
            for (int c = 0; c < 3; ++c) image[std::size_t(c)][std::size_t(y) * size + x] = value[c];
        }
    return image;
}

/// Blocks of side `block` whose cosines are the `cosines` strongest bins of a fit_size² window
/// of the structure image centred on the block.
LrpStructure fit_blocks(const std::array<std::vector<float>, 3>& image, int size, int block, int fit_size, int cosines)
{
    LrpStructure structure;
    structure.block_size = block;
    structure.fit_size = fit_size;
    const int per_side = size / block;
    // Window pixel n sits at ξ = origin + n; the stored phases refer to the block's lattice point
    // ξ_b = origin + (fit_size − 1)/2, so every coefficient turns by e^{2πi k·(fit_size − 1)/2 / fit_size}.
    const double reference = 0.5 * (fit_size - 1);
    std::array<std::vector<float>, 3> window;
    for (auto& plane : window) plane.resize(std::size_t(fit_size) * fit_size);
    for (int by = 0; by < per_side; ++by)
        for (int bx = 0; bx < per_side; ++bx) {
            const int origin_x = bx * block + block / 2 - fit_size / 2, origin_y = by * block + block / 2 - fit_size / 2;
            for (int c = 0; c < 3; ++c)
                for (int y = 0; y < fit_size; ++y)
                    for (int x = 0; x < fit_size; ++x) {
                        const int sx = ((origin_x + x) % size + size) % size, sy = ((origin_y + y) % size + size) % size;
                        window[std::size_t(c)][std::size_t(y) * fit_size + x] = image[std::size_t(c)][std::size_t(sy) * size + sx];
                    }
            const auto spectrum = spectra(window, fit_size, false);
            const std::vector<HalfBin> bins = bins_by_energy(spectrum, fit_size, true);
            LrpBlock out;
            DiscreteSpectrum layout(fit_size);
            for (std::size_t t = 0; t < std::min(bins.size(), std::size_t(cosines)); ++t) {
                const HalfBin& bin = bins[t];
                if (!(bin.energy > 0)) break;
                const std::size_t i = layout.index(bin.kx, bin.ky);
                const bool paired = i != layout.index(mirror_bin(bin.kx, fit_size), mirror_bin(bin.ky, fit_size));
                const double angle = 2 * kPi * (bin.kx + bin.ky) * reference / fit_size;
                const std::complex<double> turn(std::cos(angle), std::sin(angle));
                out.frequencies.push_back(bin.kx);
                out.frequencies.push_back(bin.ky);
                for (int c = 0; c < 3; ++c) {
                    const std::complex<double> coefficient = spectrum[std::size_t(c)][i] * turn * (paired ? 2.0 : 1.0);
                    out.coefficients[std::size_t(c)].push_back(coefficient.real());
                    out.coefficients[std::size_t(c)].push_back(coefficient.imag());
                }
            }
            if (out.frequencies.empty()) {  // a flat block: one zero constant
                out.frequencies = {0, 0};
                for (auto& c : out.coefficients) c = {0, 0};
            }
            structure.blocks.push_back(std::move(out));
        }
    return structure;
}

}  // namespace

double mean_colour_error(const std::array<std::vector<float>, 3>& a, const std::array<std::vector<float>, 3>& b,
                         const Matrix3& basis)
{
    double sum = 0;
    const std::size_t pixels = a[0].size();
    for (std::size_t p = 0; p < pixels; ++p) {
        const double d[3] = {double(a[0][p]) - b[0][p], double(a[1][p]) - b[1][p], double(a[2][p]) - b[2][p]};
        for (int r = 0; r < 3; ++r)
            sum += std::abs(basis[std::size_t(r)][0] * d[0] + basis[std::size_t(r)][1] * d[1] + basis[std::size_t(r)][2] * d[2]);
    }
    return sum / (3.0 * double(pixels));
}

LrpStructureFit fit_lrp_structure(const std::array<std::vector<float>, 3>& channels, int width, int height, int size,
                                  const Matrix3& basis, const LrpStructureFitOptions& options)
{
    if (size > width || size > height) throw Error("fit_lrp_structure: the crop is larger than the photo");
    if (options.cosines < 1) throw Error("fit_lrp_structure: the structure needs at least one cosine per block");
    LrpStructureFit fit;
    // The centred crop.
    std::array<std::vector<float>, 3> crop;
    const int x0 = (width - size) / 2, y0 = (height - size) / 2;
    for (int c = 0; c < 3; ++c) {
        crop[std::size_t(c)].resize(std::size_t(size) * size);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                crop[std::size_t(c)][std::size_t(y) * size + x] = channels[std::size_t(c)][std::size_t(y0 + y) * width + x0 + x];
    }
    const auto spectrum = spectra(crop, size, true);

    // R: the strongest bins (with their mirrors) until they hold the fraction r of the energy.
    const std::vector<HalfBin> bins = bins_by_energy(spectrum, size, false);
    const double total = std::accumulate(bins.begin(), bins.end(), 0.0, [](double s, const HalfBin& b) { return s + b.energy; });
    fit.region.assign(std::size_t(size) * size, 0);
    DiscreteSpectrum layout(size);
    double held = 0;
    for (const HalfBin& bin : bins) {
        if (!(held < options.energy_fraction * total)) break;
        if (std::hypot(bin.kx, bin.ky) < options.min_radius_bins) continue;
        fit.region[layout.index(bin.kx, bin.ky)] = fit.region[layout.index(mirror_bin(bin.kx, size), mirror_bin(bin.ky, size))] = 1;
        held += bin.energy;
    }
    fit.energy_fraction = total > 0 ? held / total : 0;
    for (int c = 0; c < 3; ++c) fit.structure_image[std::size_t(c)] = restricted_image(spectrum[std::size_t(c)], fit.region, size);

    // Subdivide until the windowed reconstruction is within the tolerance (Fig. 9).
    double best_error = std::numeric_limits<double>::max();
    for (int block = size; block >= std::min(size, options.min_block_size); block /= 2) {
        const int per_side = size / block;
        if (block < size && per_side * per_side * options.cosines > options.max_terms) break;
        constexpr int single_block_cosines = 9;
        // One block needs no windows (every lattice point holds the same periodic function), so
        // it affords 9 times the cosines at the cost of 9 windows of J_R.
        const int cosines = block == size ? std::min(max_lrp_terms, single_block_cosines * options.cosines) : options.cosines;
        LrpStructure candidate = fit_blocks(fit.structure_image, size, block, std::min(2 * size, options.fit_extent * block), cosines);
        quantise(candidate);
        const double error = mean_colour_error(reconstruct(candidate, size), fit.structure_image, basis);
        fit.level_errors.emplace_back(block, error);
        if (error < best_error) {
            best_error = error;
            fit.structure = std::move(candidate);
        }
        if (error < options.colour_tolerance) break;
    }
    fit.colour_error = best_error;
    fit.structure.random_placement = options.random_placement;
    fit.structure.turbulence = options.turbulence;
    return fit;
}

}  // namespace stochtex
