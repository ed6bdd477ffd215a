#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/stex_file.h>

#include "band_leakage.h"
#include "band_power.h"
#include "colour_basis.h"
#include "gabor_fit.h"
#include "lrp_fit.h"
#include "gaussian.h"
#include "histogram_map.h"
#include "tiling_exemplar.h"
#include "wavelet_noise.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace stochtex {

namespace {

// "auto" histogram mode turns matching on for a channel when the fitted map is closer to the
// photo's histogram than the best Gaussian by more than this fraction of the channel's σ
// (1-Wasserstein). Below it the map only adds cost and a non-linearity under filtering.
constexpr double histogram_benefit_threshold = 0.02;

std::string format_number(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

bool decide_histogram(HistogramMode mode, const EmpiricalDistribution& distribution, const HistogramMap& map)
{
    if (mode != HistogramMode::automatic) return mode == HistogramMode::on;
    const double mean = distribution.mean(), sigma = distribution.stddev();
    const double gaussian_w1 =
        relative_w1_to_model(distribution, [&](double p) { return mean + sigma * inverse_normal_cdf(p); });
    const MonotoneCubic curve(map.z, map.value);
    const double mapped_w1 = relative_w1_to_model(distribution, [&](double p) { return curve(inverse_normal_cdf(p)); });
    return gaussian_w1 - mapped_w1 > histogram_benefit_threshold;
}

LrpFitOptions lrp_fit_options(const AnalysisOptions& options)
{
    if (options.lrp_cosines < 1 || options.lrp_cosines > 256)
        throw Error("lrp: J (cosines) must be in [1, 256], got " + std::to_string(options.lrp_cosines));
    if (options.lrp_strata < 1 || options.lrp_strata > 16)
        throw Error("lrp: L (strata) must be in [1, 16], got " + std::to_string(options.lrp_strata));
    if (!(options.lrp_structure >= 0 && options.lrp_structure < 1))
        throw Error("lrp: r (structure energy fraction) must be in [0, 1), got " + format_number(options.lrp_structure));
    if (!(options.lrp_turbulence < 0 || std::isfinite(options.lrp_turbulence)))
        throw Error("lrp: turbulence must be a finite number of exemplar pixels");
    LrpFitOptions fit;
    fit.cosines = options.lrp_cosines;
    fit.strata = options.lrp_strata;
    fit.structure_fraction = options.lrp_structure;
    fit.random_placement = options.lrp_placement;
    fit.turbulence = options.lrp_turbulence;
    fit.seed = options.seed;
    return fit;
}

}  // namespace

const char* to_string(HistogramMode mode)
{
    switch (mode) {
    case HistogramMode::off: return "off";
    case HistogramMode::on: return "on";
    case HistogramMode::automatic: return "auto";
    }
    return "?";
}

HistogramMode histogram_mode_from_string(const std::string& name)
{
    for (HistogramMode mode : {HistogramMode::off, HistogramMode::on, HistogramMode::automatic})
        if (name == to_string(mode)) return mode;
    throw Error("unknown histogram mode '" + name + "' (expected off, on or auto)");
}

const char* to_string(PsdEstimator estimator)
{
    return estimator == PsdEstimator::periodic ? "periodic" : "periodic-smooth";
}

PsdEstimator psd_estimator_from_string(const std::string& name)
{
    for (PsdEstimator estimator : {PsdEstimator::periodic, PsdEstimator::periodic_smooth})
        if (name == to_string(estimator)) return estimator;
    throw Error("unknown PSD estimator '" + name + "' (expected periodic or periodic-smooth)");
}

TextureDescription analyze(const Image& photo, const AnalysisOptions& options, const ProgressCallback& progress)
{
    const auto& models = known_models();
    if (std::find(models.begin(), models.end(), options.model) == models.end())
        throw Error("unknown model '" + options.model + "'");
    if (options.model != "wavelet" && options.model != "gabor" && options.model != "tiling" && options.model != "lrp")
        throw Error("model '" + options.model + "' cannot analyse photos in this build");
    if (photo.channels != 3) throw Error("analysis needs an RGB image");
    const int band_count_supported = supported_band_count(photo.width, photo.height);
    if (band_count_supported < 1)
        throw Error("image is " + std::to_string(photo.width) + "x" + std::to_string(photo.height) +
                    ", too small to analyse (at least 4x4)");
    if (options.histogram_knots < 4 || options.histogram_knots > 64)
        throw Error("histogram knots must be in [4, 64], got " + std::to_string(options.histogram_knots));
    if (options.max_bands < 0) throw Error("band count must not be negative");
    if (!(options.unit_size_m > 0) || !std::isfinite(options.unit_size_m))
        throw Error("unit size must be a positive number of metres");
    if (!(options.gabor_impulses >= 1 && options.gabor_impulses <= 256))
        throw Error("impulses per kernel must be in [1, 256], got " + format_number(options.gabor_impulses));
    if (!(options.gabor_bandwidth == 0 || (options.gabor_bandwidth >= 1.0 / 16 && options.gabor_bandwidth <= 16)))
        throw Error("Gabor bandwidth must be 0 (fitted) or in [0.0625, 16], got " + format_number(options.gabor_bandwidth));
    const int band_count =
        options.max_bands > 0 ? std::min(options.max_bands, band_count_supported) : band_count_supported;
    auto report = [&](double fraction, const char* stage) {
        if (progress) progress(fraction, stage);
    };

    TextureDescription description;
    description.model = options.model;
    description.seed = options.seed;
    description.pixels_per_unit = photo.width;
    description.unit_size_m = options.unit_size_m;
    description.colour_mode = options.colour_mode;

    // §7 step 1–2: mean, then decorrelation.
    report(0.0, "colour");
    const ColourBasis colour = fit_colour_basis(photo, options.colour_mode);
    description.mean = colour.mean;
    description.basis = colour.basis;
    std::array<std::vector<float>, 3> channels = decorrelate(photo, colour);

    // Step 3 per channel: optional Gaussianisation.
    for (int c = 0; c < 3; ++c) {
        report((c + 0.1) / 3, "histogram");
        std::vector<float>& channel = channels[c];
        const EmpiricalDistribution distribution(channel);
        // A channel without variance (e.g. the chroma axes of a grey photo) has nothing to map.
        if (distribution.stddev() > 1e-7) {
            HistogramMap map = fit_histogram_map(distribution, options.histogram_knots);
            if (decide_histogram(options.histogram, distribution, map)) {
                gaussianize(channel, distribution);
                description.histograms[c] = std::move(map);
            }
        }
    }
    // Step 4: the model's spectral parameters.
    report(0.5, "spectrum");
    if (options.model == "gabor") {
        GaborFitOptions fit;
        fit.kind = options.gabor_kind;
        fit.impulses_per_kernel = options.gabor_impulses;
        fit.bandwidth = options.gabor_bandwidth;
        fit.octaves = band_count;
        description.gabor = fit_gabor_octaves(channels, photo.width, photo.height, fit);
    } else if (options.model == "lrp") {
        description.lrp = fit_lrp(channels, photo.width, photo.height, colour.basis, lrp_fit_options(options));
    } else if (options.model == "tiling") {
        // The exemplar itself (a periodic crop of the decorrelated channels) is the model.
        description.tiling = fit_tiling_exemplar(channels, photo.width, photo.height, description.histograms,
                                                 options.tiling_exemplar_size, options.tiling_exemplar_bits);
    } else {
        // Band weights (eq. 9, with the bands' measured overlap undone: band_leakage.h).
        const double band_variance = WaveletNoise2D::shared().variance();
        WaveletParameters wavelet;
        for (int c = 0; c < 3; ++c) {
            const std::vector<double> power = band_powers(channels[c], photo.width, photo.height, band_count, options.psd);
            wavelet.band_weights[c] =
                solve_band_weights(power, band_variance, leakage_corrected_band_count(photo.width, photo.height));
        }
        description.wavelet = std::move(wavelet);
    }

    Provenance& provenance = description.provenance;
    provenance.source = options.source_name;
    provenance.source_width = photo.width;
    provenance.source_height = photo.height;
    provenance.input_colour_space = options.input_colour_space;
    provenance.tool = "stochtex " STOCHTEX_VERSION;
    provenance.options = {{"model", options.model},
                          {"colour", to_string(options.colour_mode)},
                          {"histogram", to_string(options.histogram)},
                          {"knots", std::to_string(options.histogram_knots)}};
    auto& recorded = provenance.options;
    if (options.model == "gabor")  // (the PSD estimator is the wavelet fit's: not recorded)
        recorded.insert(recorded.end(), {{"octaves", std::to_string(band_count)},
                                         {"gabor_kind", to_string(options.gabor_kind)},
                                         {"impulses", format_number(options.gabor_impulses)},
                                         {"bandwidth", options.gabor_bandwidth > 0 ? format_number(options.gabor_bandwidth) : "auto"}});
    else if (options.model == "lrp")
        recorded.insert(recorded.end(), {{"J", std::to_string(options.lrp_cosines)},
                                         {"L", std::to_string(options.lrp_strata)},
                                         {"r", format_number(options.lrp_structure)},
                                         {"placement", options.lrp_placement ? "on" : "off"},
                                         {"turbulence", options.lrp_turbulence >= 0 ? format_number(options.lrp_turbulence) : "auto"}});
    else if (options.model == "tiling")
        recorded.insert(recorded.end(), {{"exemplar_size", std::to_string(options.tiling_exemplar_size)},
                                         {"exemplar_bits", std::to_string(options.tiling_exemplar_bits)}});
    else
        recorded.insert(recorded.end(), {{"psd", to_string(options.psd)}, {"bands", std::to_string(band_count)}});
    recorded.insert(recorded.end(), {{"seed", std::to_string(options.seed)}, {"unit_size_m", format_number(options.unit_size_m)}});
    report(1.0, "done");
    validate(description, options.source_name.empty() ? "analysis" : options.source_name);
    return description;
}

}  // namespace stochtex
