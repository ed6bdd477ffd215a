// The lrp model (paper 003) in the registry: its parameter schema (lrp_parameters), analysis
// options, fit and `stex info` lines. The maths is in lrp_window, lrp_noise,
// lrp_spectrum_sampling, lrp_leakage, lrp_structure_* and lrp_texture.
#include "colour/colour_basis.h"
#include "models/lrp/lrp_fit.h"
#include "models/lrp/lrp_parameters.h"
#include "models/lrp/lrp_texture.h"
#include "models/model.h"

#include <stochtex/models/lrp_parameters.h>

namespace stochtex {

namespace {

ModelInfo lrp_info()
{
    ModelInfo info;
    info.name = "lrp";
    info.summary = "local random-phase noise (Gilet et al. 2014): any power spectrum, anisotropic ones included, plus a "
                   "share of the photo's own phases for structure; 2D only";
    info.doc = "docs/models/lrp.md";
    info.capabilities.analysis = true;
    info.capabilities.joint_colour = true;
    return info;
}

class LrpModel final : public TextureModelOf<LrpParameters, LrpTexture> {
public:
    LrpModel() : TextureModelOf(lrp_info(), lrp_schema())
    {
        declare_analysis_options(
            {integer_option("J", 1, 256,
                            {"50", "cosines", "cosine budget per window over all strata and the structure (cost: about "
                                              "9(J + L) sine/cosine and window evaluations per sample)"}),
             integer_option("L", 1, 16, {"8", "strata", "random-phase strata of equal energy, at most 15 besides the lowest octave's (the paper's 4 measured worse than 8)"}),
             number_option("r", 0, 1,
                           {"0.1", "", "share of the spectrum's energy reproduced with the photo's own phases (structure); "
                                       "0: noise by example only"},
                           "", true),
             choice_option("placement", {"on", "off"},
                           {"on", "", "random placement of the structure (breaks its periodicity; blocks of half a crop, "
                                      "cross-faded)"}),
             number_option("turbulence", 0, max_lrp_spectrum_size,
                           {"auto", "exemplar px", "turbulence of the structure: standard deviation of the displacement, "
                                                   "or auto (a tenth of the structure's mean wavelength)"},
                           "auto")});
    }

    std::string describe(const TextureDescription& description) const override { return describe_lrp(description); }

    ModelParameters fit(const FitInput& input, Provenance& provenance) const override
    {
        const std::map<std::string, std::string>& options = input.model_options;
        LrpFitOptions fit;
        fit.cosines = std::stoi(options.at("J"));
        fit.strata = std::stoi(options.at("L"));
        fit.structure_fraction = std::stod(options.at("r"));
        fit.random_placement = options.at("placement") == "on";
        fit.turbulence = options.at("turbulence") == "auto" ? -1 : std::stod(options.at("turbulence"));
        fit.seed = input.options.seed;
        provenance.options.insert(provenance.options.end(), {{"J", options.at("J")},
                                                             {"L", options.at("L")},
                                                             {"r", recorded_option(options, "r")},
                                                             {"placement", options.at("placement")},
                                                             {"turbulence", recorded_option(options, "turbulence")}});
        return fit_lrp(input.channels, input.width, input.height, input.colour.basis, fit);
    }

    ModelParameters morph(const TextureDescription&, const TextureDescription&, double) const override
    {
        throw Error("morph: lrp textures cannot be morphed (their frequency tables do not interpolate)");
    }
};

}  // namespace

const Model& lrp_model()
{
    static const LrpModel model;
    return model;
}

}  // namespace stochtex
