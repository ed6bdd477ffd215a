// The wavelet model (paper 000) in the registry: its parameter schema, analysis options, fit,
// morph and `stex info` lines. The maths is in wavelet_noise, spectra/band_power, band_leakage and
// wavelet_texture.
#include "numerics/interpolation.h"
#include "spectra/band_power.h"
#include "models/info_text.h"
#include "models/model.h"
#include "models/wavelet/band_leakage.h"
#include "models/wavelet/wavelet_noise.h"
#include "models/wavelet/wavelet_texture.h"

#include <stochtex/models/wavelet_parameters.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace stochtex {

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

namespace {

/// Band j has frequencies around 2^-(j+2) cycles per pixel: 24 bands reach past any image size.
constexpr std::size_t max_bands = 24;

ParameterSchema<WaveletParameters> wavelet_schema()
{
    ParameterSchema<WaveletParameters> schema;
    schema.channel_numbers(
        "band_weights", &WaveletParameters::band_weights,
        {"", "", "band_weights[c][j] is the weight of band j for decorrelated channel c. The three channels have the "
                 "same number of bands, 1 to 24; every weight is ≥ 0. Band 0 is the finest: its frequencies lie in "
                 "[1/4, 1/2) cycles per exemplar pixel; band j covers [2^-(j+2), 2^-(j+1)).",
         "1 to 24 bands, each ≥ 0"},
        [](const WaveletParameters& p, const std::string& key_path, const std::string& source) {
            const auto& weights = p.band_weights;
            for (std::size_t channel = 0; channel < 3; ++channel) {
                const std::string path = json_path(key_path, channel);
                const std::size_t bands = weights[channel].size();
                if (bands < 1 || bands > max_bands)
                    json_fields::fail(source, path,
                                      "expected 1 to " + std::to_string(max_bands) + " bands, got " + std::to_string(bands));
                if (bands != weights[0].size())
                    json_fields::fail(source, path,
                                      "has " + std::to_string(bands) + " bands but channel 0 has " +
                                          std::to_string(weights[0].size()));
                for (std::size_t band = 0; band < bands; ++band) {
                    check_float_finite(weights[channel][band], json_path(path, band), source);
                    if (weights[channel][band] < 0)
                        json_fields::fail(source, json_path(path, band),
                                          "weights must not be negative, got " + number_text(weights[channel][band]));
                }
            }
        });
    return schema;
}

ModelInfo wavelet_info()
{
    ModelInfo info;
    info.name = "wavelet";
    info.summary = "multiresolution wavelet noise by example (Lagae et al. 2009): isotropic stochastic textures, 2D and "
                   "solid, band-limited anti-aliasing; ~2 kB";
    info.doc = "docs/models/wavelet.md";
    info.capabilities.analysis = true;
    info.capabilities.solid = true;
    info.capabilities.morph = true;
    info.capabilities.pov_procedural = true;
    info.capabilities.osl = true;
    info.capabilities.gaussian_channels = true;
    info.capabilities.joint_colour = true;
    return info;
}

class WaveletModel final : public TextureModelOf<WaveletParameters, WaveletTexture> {
public:
    WaveletModel() : TextureModelOf(wavelet_info(), wavelet_schema())
    {
        declare_analysis_options({choice_option(
            "psd", {"periodic", "periodic-smooth"},
            {"periodic", "",
             "power spectrum estimator: periodic (the paper's periodogram; chosen by measurement) or periodic-smooth "
             "(Moisan: no edge leak on non-tileable photos)"})});
    }


    std::string describe(const TextureDescription& d) const override
    {
        std::ostringstream out;
        const double band_variance = WaveletNoise2D::shared().variance();
        out << "sigma_N^2    " << info_text("%.4f (2D band), %.4f (3D band)", band_variance, WaveletNoise3D::shared().variance())
            << "\n";
        out << "band  cycles/exemplar px     w[0]      w[1]      w[2]\n";
        const auto& w = parameters(d).band_weights;
        for (std::size_t j = 0; j < w[0].size(); ++j)
            out << info_text("%4.0f  [1/%-5.0f, 1/%-5.0f)", double(j), std::ldexp(1.0, int(j) + 2), std::ldexp(1.0, int(j) + 1))
                << info_text("  %8.5f  %8.5f  %8.5f", w[0][j], w[1][j], w[2][j]) << "\n";
        for (int c = 0; c < 3; ++c) out << "sigma_M[" << c << "]   " << info_text("%.5f", wavelet_channel_sigma(w[c])) << "\n";
        return out.str();
    }

    ModelParameters fit(const FitInput& input, Provenance& provenance) const override
    {
        // Band weights (eq. 9, with the bands' measured overlap undone: band_leakage.h).
        const PsdEstimator psd = psd_estimator_from_string(input.model_options.at("psd"));
        const double band_variance = WaveletNoise2D::shared().variance();
        WaveletParameters wavelet;
        for (int c = 0; c < 3; ++c) {
            const std::vector<double> power = band_powers(input.channels[c], input.width, input.height, input.band_count, psd);
            wavelet.band_weights[c] =
                solve_band_weights(power, band_variance, leakage_corrected_band_count(input.width, input.height));
        }
        provenance.options.insert(provenance.options.end(),
                                  {{"psd", to_string(psd)}, {"bands", std::to_string(input.band_count)}});
        return wavelet;
    }

    ModelParameters morph(const TextureDescription& a, const TextureDescription& b, double t) const override
    {
        const auto& wa = parameters(a).band_weights;
        const auto& wb = parameters(b).band_weights;
        WaveletParameters result;
        for (int c = 0; c < 3; ++c) {
            // Band j means the same frequency (cycles per exemplar pixel) in both; a missing
            // band has weight 0.
            const std::size_t count = std::max(wa[c].size(), wb[c].size());
            std::vector<double>& w = result.band_weights[c];
            w.assign(count, 0.0);
            for (std::size_t j = 0; j < count; ++j)
                w[j] = lerp(j < wa[c].size() ? wa[c][j] : 0.0, j < wb[c].size() ? wb[c][j] : 0.0, t);
        }
        return result;
    }

    double channel_sigma(const TextureDescription& description, int channel) const override
    {
        return wavelet_channel_sigma(parameters(description).band_weights[channel]);
    }
};

}  // namespace

const Model& wavelet_model()
{
    static const WaveletModel model;
    return model;
}

}  // namespace stochtex
