#include <stochtex/analysis.h>
#include <stochtex/error.h>
#include <stochtex/stex_file.h>

#include "analysis/model_choice.h"
#include "colour/chroma_given_brightness.h"
#include "colour/colour_basis.h"
#include "colour/gaussian.h"
#include "colour/histogram_map.h"
#include "models/model.h"
#include "spectra/band_power.h"
#include "schema/parameter_schema.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
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

TextureDescription analyze(const Image& photo, const AnalysisOptions& options, const ProgressCallback& progress)
{
    if (options.model == automatic_model) return analyze_choosing_model(photo, options, progress);
    return analyze_one_model(photo, options, progress, nullptr);
}

TextureDescription analyze_one_model(const Image& photo, const AnalysisOptions& options,
                                     const ProgressCallback& progress, const ComparisonReference* prepared_photo)
{
    const Model& model = model_named(options.model, "analysis", "--model");
    if (!model.info().capabilities.analysis) throw Error("model '" + options.model + "' cannot analyse photos");
    // The model's own options first: a typo costs nothing.
    std::map<std::string, std::string> model_options = parse_model_options(model, options.model_options);
    if (photo.channels != 3) throw Error("analysis needs an RGB image");
    const int band_count_supported = supported_band_count(photo.width, photo.height);
    if (band_count_supported < 1)
        throw Error("image is " + std::to_string(photo.width) + "x" + std::to_string(photo.height) +
                    ", too small to analyse (at least 4x4)");
    // Spectra are float: a bin's power is up to (pixel count × value)², which for the largest
    // photo read (2^26 pixels) stays within float range while values stay within 1e10. Beyond
    // it the fits see infinities and NaNs (a photo × 1e18 crashed the Gabor fit).
    for (float value : photo.pixels)
        if (!(std::abs(value) <= max_analysis_value))
            throw Error((options.source_name.empty() ? std::string("photo") : options.source_name) +
                        ": pixel values must be finite and within ±1e10 (scene-linear) for analysis, got " +
                        number_text(value));
    if (options.histogram_knots < 4 || options.histogram_knots > 64)
        throw Error("histogram knots must be in [4, 64], got " + std::to_string(options.histogram_knots));
    if (options.max_bands < 0) throw Error("band count must not be negative");
    if (!(options.unit_size_m > 0) || !std::isfinite(options.unit_size_m))
        throw Error("unit size must be a positive number of metres");
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
    // Joint colour replaces the chroma channels by what brightness leaves of them, before their
    // histograms and spectra are fitted.
    const bool joint_colour = options.joint_colour && options.colour_mode == ColourMode::pca &&
                              model.info().capabilities.joint_colour;
    if (joint_colour) description.chroma_given_brightness = fit_chroma_given_brightness(channels);

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
    if (description.chroma_given_brightness.enabled()) provenance.options.emplace_back("joint_colour", "on");

    // Step 4: the model's own parameters (and its provenance options).
    report(0.5, "spectrum");
    // The photo's side of the comparison, unless the caller brought it, is made at the first
    // score and kept for the others.
    std::once_flag photo_side_made;
    std::optional<ComparisonReference> photo_side;
    const auto score = [&](const ModelParameters& parameters, int max_side) {
        if (!prepared_photo) std::call_once(photo_side_made, [&] { photo_side.emplace(photo, /*with_structure=*/false); });
        TextureDescription candidate = description;
        candidate.parameters = parameters;
        return score_against_photo(candidate, prepared_photo ? *prepared_photo : *photo_side, max_side);
    };
    const FitInput input{channels, photo.width, photo.height, colour, description.histograms, band_count, options,
                         std::move(model_options), score, chosen_by_rule};
    description.parameters = model.fit(input, provenance);
    provenance.options.insert(provenance.options.end(),
                              {{"seed", std::to_string(options.seed)}, {"unit_size_m", format_number(options.unit_size_m)}});
    report(1.0, "done");
    validate(description, options.source_name.empty() ? "analysis" : options.source_name);
    return description;
}

}  // namespace stochtex
