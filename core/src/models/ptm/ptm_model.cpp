// The ptm model (paper 004) in the registry: its parameter schema (ptm_stex_fields), the
// coefficient file beside the .stex, the light direction and `stex info` lines. PTMs are fitted
// from photos under known lights (`stex ptm fit`, ptm_fit), not from one photo.
#include "models/model.h"
#include "models/ptm/ptm_stex_fields.h"
#include "models/ptm/ptm_texture.h"
#include "numerics/random.h"

#include <stochtex/models/ptm.h>

#include <stochtex/models/ptm_parameters.h>

namespace stochtex {

namespace {

ModelInfo ptm_info()
{
    ModelInfo info;
    info.name = "ptm";
    info.summary = "relightable polynomial texture maps (Malzbender et al.; Hel-Or et al.): fitted to photos under known "
                   "lights, quilted in ψ-space, relit for any light";
    info.doc = "docs/models/ptm.md";
    info.capabilities.light_direction = true;
    return info;
}

class PtmModel final : public TextureModelOf<PtmParameters, PtmTexture> {
public:
    PtmModel() : TextureModelOf(ptm_info(), ptm_schema()) {}

    void validate(const TextureDescription& description, const std::string& source) const override
    {
        validate_ptm_colour_fields(description, source);
        TextureModelOf::validate(description, source);
    }
    TextureDescription write_beside(const std::string& stex_path, const TextureDescription& description) const override
    {
        return write_ptm_coefficients_beside(stex_path, description);
    }

    std::string describe(const TextureDescription& description) const override { return describe_ptm(description); }

    TextureDescription example() const override
    {
        // 16² texels of random reflectance functions (a bright constant term, small slopes).
        PtmMaps maps;
        maps.colour = PtmColour::lrgb;
        maps.coefficients = Image(16, 16, ptm_channel_count(maps.colour));
        SplitMix64 random(7);
        for (std::size_t i = 0; i < maps.coefficients.pixel_count(); ++i) {
            float* texel = &maps.coefficients.pixels[i * maps.coefficients.channels];
            texel[0] = float(1.0 + 0.2 * random.uniform());
            for (int k = 1; k < 6; ++k) texel[k] = float(0.08 * random.gaussian());
            for (int c = 0; c < 3; ++c) texel[6 + c] = float(0.7 + 0.6 * random.uniform());
        }
        return make_ptm_description(std::move(maps), {0.6, 0, 0.8});
    }

    Vec3 light(const TextureDescription& description) const override { return parameters(description).light; }
    void set_light(TextureDescription& description, const Vec3& unit_direction) const override
    {
        description.parameters.get<PtmParameters>().light = unit_direction;
    }
};

}  // namespace

const Model& ptm_model()
{
    static const PtmModel model;
    return model;
}

}  // namespace stochtex
