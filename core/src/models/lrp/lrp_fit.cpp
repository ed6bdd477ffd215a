#include "models/lrp/lrp_fit.h"

#include "models/lrp/lrp_leakage.h"
#include "models/lrp/lrp_spectrum_sampling.h"

#include <stochtex/error.h>
#include <stochtex/models/lrp_parameters.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

namespace {

/// Fraction of R's mean wavelength used as the automatic turbulence.
constexpr double turbulence_per_wavelength = 0.1;

}  // namespace

double lrp_automatic_turbulence(const std::vector<char>& region, const DiscreteSpectrum& power)
{
    double weighted = 0, total = 0;
    const int size = power.size;
    for (int ky = -size / 2; ky < size / 2; ++ky)
        for (int kx = -size / 2; kx < size / 2; ++kx) {
            const std::size_t i = power.index(kx, ky);
            if (!region[i] || (kx == 0 && ky == 0)) continue;
            weighted += power.power[i] * size / std::hypot(kx, ky);
            total += power.power[i];
        }
    return total > 0 ? turbulence_per_wavelength * weighted / total : 0;
}

LrpParameters fit_lrp(const std::array<std::vector<float>, 3>& channels, int width, int height, const Matrix3& basis,
                      const LrpFitOptions& options, LrpFitReport* report)
{
    if (options.cosines < 1 || options.cosines > 256) throw Error("lrp: the cosine budget J must be in [1, 256]");
    if (options.strata < 1 || options.strata > 16) throw Error("lrp: the stratum count L must be in [1, 16]");
    if (!(options.structure_fraction >= 0 && options.structure_fraction < 1))
        throw Error("lrp: the structure's energy fraction r must be in [0, 1)");
    const int size = welch_size(width, height, options.max_spectrum_size);
    if (size < 8) throw Error("lrp: the photo is too small (at least 9x9 pixels)");

    LrpFitReport local;
    LrpFitReport& out = report ? *report : local;
    DiscreteSpectrum sum(size);
    for (int c = 0; c < 3; ++c) {
        out.channel_spectra[std::size_t(c)] = welch_psd(channels[std::size_t(c)], width, height, size);
        for (std::size_t i = 0; i < sum.power.size(); ++i) sum.power[i] += out.channel_spectra[std::size_t(c)].power[i];
    }

    LrpParameters parameters;
    parameters.spectrum_size = size;
    int random_cosines = options.cosines;
    std::vector<char> excluded;
    if (options.structure_fraction > 0) {
        LrpStructureFitOptions structure;
        structure.energy_fraction = options.structure_fraction;
        structure.cosines = std::max(1, int(std::lround(options.structure_fraction * options.cosines)));
        structure.max_terms = std::max(options.max_structure_terms, structure.cosines);
        structure.random_placement = options.random_placement;
        // Placement cells of half a crop hold wavelengths up to T/2: the lowest octave (|k| < 2)
        // goes to the random-phase strata (their own stratum with options.resolve).
        if (options.random_placement && options.resolve > 0) structure.min_radius_bins = 2;
        out.structure = fit_lrp_structure(channels, width, height, size, basis, structure);
        out.structure->structure.turbulence =
            options.turbulence >= 0 ? options.turbulence : lrp_automatic_turbulence(out.structure->region, sum);
        parameters.structure = out.structure->structure;
        excluded = out.structure->region;
        random_cosines = std::max(1, options.cosines - structure.cosines);
    }
    LrpSamplingOptions sampling;
    sampling.strata = options.strata;
    sampling.cosines = random_cosines;
    sampling.representatives = options.representatives;
    sampling.coverage = options.coverage;
    sampling.resolve = options.resolve;
    sampling.octave_span = options.octave_span;
    sampling.power_weighted = options.power_weighted;
    sampling.seed = options.seed;
    StratifiedSpectrum strata = stratify_spectrum(
        sum, {&out.channel_spectra[0], &out.channel_spectra[1], &out.channel_spectra[2]}, excluded, sampling);
    if (options.leakage_correction)
        correct_stratum_leakage(strata.strata, strata.label,
                                {&out.channel_spectra[0], &out.channel_spectra[1], &out.channel_spectra[2]}, options.match_rings);
    parameters.strata = std::move(strata.strata);
    out.stratum_of_bin = std::move(strata.label);
    if (parameters.strata.empty() && !parameters.structure) throw Error("lrp: the photo has no variance to model");
    return parameters;
}

LrpParameters lrp_for_spectrum(const DiscreteSpectrum& spectrum, int cosines, int strata, double spacing,
                               std::uint64_t seed, std::vector<int>* stratum_of_bin)
{
    LrpSamplingOptions sampling;
    sampling.strata = strata;
    sampling.cosines = cosines;
    sampling.seed = seed;
    sampling.spacing = spacing;
    StratifiedSpectrum result = stratify_spectrum(spectrum, {&spectrum, nullptr, nullptr}, {}, sampling);
    correct_stratum_leakage(result.strata, result.label, {&spectrum, nullptr, nullptr});
    if (stratum_of_bin) *stratum_of_bin = std::move(result.label);
    LrpParameters parameters;
    parameters.spectrum_size = spectrum.size;
    parameters.strata = std::move(result.strata);
    return parameters;
}

}  // namespace stochtex
