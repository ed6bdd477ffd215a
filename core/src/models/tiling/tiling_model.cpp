// The tiling model (paper 002) in the registry: its parameter schema (tiling_parameters),
// analysis options, fit and `stex info` lines. The maths is in tiling_noise, moment_pyramid,
// colour_map_filter, normal_map_filter and tiling_texture.
#include "models/model.h"
#include "models/tiling/tiling_exemplar.h"
#include "models/tiling/tiling_parameters.h"
#include "models/tiling/tiling_texture.h"

#include <stochtex/models/tiling_parameters.h>

#include <algorithm>

namespace stochtex {

namespace {

ModelInfo tiling_info()
{
    ModelInfo info;
    info.name = "tiling";
    info.summary = "tiling and blending of an exemplar crop stored in the .stex (Heitz–Neyret, Deliot–Heitz), "
                   "moment-filtered: any texture a crop shows, structure included; colour-mapped and phasor noise";
    info.doc = "docs/models/tiling.md";
    info.capabilities.analysis = true;
    info.capabilities.osl = true;  // colour and normal_map outputs; colour_map has no transcription
    // Gravel: PCA colour 6.2 % false colour, rgb 0.3 % (docs/models/tiling.md).
    info.automatic_colour_modes = {"pca", "rgb"};
    return info;
}

class TilingModel final : public TextureModelOf<TilingParameters, TilingTexture> {
public:
    TilingModel() : TextureModelOf(tiling_info(), tiling_schema())
    {
        declare_analysis_options(
            {integer_option("exemplar-size", 16, 1024,
                            {"auto", "px",
                             "largest exemplar side (sides powers of two); auto: 256, and 512, 1024 where smaller crops' "
                             "statistics miss the photo's (and it holds them twice per side); of those, the one whose "
                             "render --model auto's rule rates best (fidelity first, then the smaller file)"},
                            "auto"),
             choice_option("exemplar-bits", {"8", "16"}, {"8", "bits", "bits per stored exemplar sample"}),
             integer_option("filter-taps", 1, TilingParameters::max_filter_taps,
                            {std::to_string(TilingParameters::default_filter_taps), "taps per axis",
                             "the footprint estimator's taps per footprint axis, stored as filter_taps: 1 (the paper's "
                             "single per-texel estimate) renders ≈ 2.4× faster, 2 halves the filtered mean's error"}),
             number_option("blend-contrast", 1, TilingParameters::max_blend_contrast,
                           {"1", "", "blend contrast γ, stored as blend_contrast: the tiles' weights B^γ (Σ w² = 1); "
                                     "above 1 the nearest tile dominates (fewer ghosts, sharper tile borders)"})});
    }

    void validate(const TextureDescription& description, const std::string& source) const override
    {
        TextureModelOf::validate(description, source);
        validate_tiling_colour_fields(description, source);
    }

    std::string describe(const TextureDescription& description) const override { return describe_tiling(description); }

    ModelParameters fit(const FitInput& input, Provenance& provenance) const override
    {
        // The exemplar itself (a periodic crop of the decorrelated channels) is the model.
        const std::string& size_text = input.model_options.at("exemplar-size");
        const int size = size_text == "auto" ? automatic_exemplar_side : std::stoi(size_text);
        const int bits = std::stoi(input.model_options.at("exemplar-bits"));
        provenance.options.insert(provenance.options.end(), {{"exemplar_size", size_text},
                                                             {"exemplar_bits", std::to_string(bits)}});
        TilingParameters parameters =
            fit_tiling_exemplar(input.channels, input.width, input.height, input.histograms, size, bits, input.score,
                                input.choose);
        // Recorded only when not the default, so that default analyses write the files they did.
        const int taps = std::stoi(input.model_options.at("filter-taps"));
        if (taps != TilingParameters::default_filter_taps) {
            parameters.filter_taps = taps;
            provenance.options.push_back({"filter_taps", std::to_string(taps)});
        }
        // Set after the exemplar's size was chosen (its scoring renders blend with γ = 1).
        const std::string& contrast = input.model_options.at("blend-contrast");
        if (std::stod(contrast) != 1) {
            parameters.blend_contrast = std::stod(contrast);
            provenance.options.push_back({"blend_contrast", contrast});
        }
        return parameters;
    }

    std::vector<FitVariant> automatic_variants(const TextureDescription& fitted,
                                               const std::set<std::string>& given) const override
    {
        // Sharper blends keep more of the photo's structure (fewer ghosts: "Blend contrast" in
        // docs/models/tiling.md) and cost a little spectrum, so the choice weighs them, where it
        // scores structure, against the fit's own γ = 1. The exemplar is the fit's.
        if (given.count("blend-contrast")) return {};
        std::vector<FitVariant> variants;
        for (const char* contrast : {"4", "8"}) {
            FitVariant& variant = variants.emplace_back();
            variant.label = std::string("blend_contrast ") + contrast;
            variant.description = fitted;
            variant.description.parameters.get<TilingParameters>().blend_contrast = std::stod(contrast);
            variant.description.provenance.options.push_back({"blend_contrast", contrast});
        }
        return variants;
    }

    std::vector<std::vector<std::pair<std::string, std::string>>> automatic_refits(
        int width, int height, const std::set<std::string>& given) const override
    {
        // A 512² exemplar where the automatic size keeps a smaller one: its sizing asks for a
        // photo that holds the exemplar twice per side, so a photo 512 px across (palm bark,
        // 512 × 2048) never gets one, though its bands are longer than 256 px.
        if (given.count("exemplar-size") || std::min(width, height) < 512) return {};
        return {{{"exemplar-size", "512"}}};
    }

    ModelParameters morph(const TextureDescription&, const TextureDescription&, double) const override
    {
        // Blending two exemplars image-wise would not give a texture "between" them.
        throw Error("morph: tiling textures are exemplar images and cannot be morphed");
    }
};

}  // namespace

const Model& tiling_model()
{
    static const TilingModel model;
    return model;
}

}  // namespace stochtex
