#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <cmath>

#include "gabor_texture.h"
#include "lrp_texture.h"
#include "ptm_texture.h"
#include "tiling_texture.h"
#include "wavelet_texture.h"

namespace stochtex {

void Texture::eval_region(const RasterRegion& region, float* rgb) const
{
    for (int j = 0; j < region.height; ++j)
        for (int i = 0; i < region.width; ++i) {
            const Rgb value = eval({region.u(i), region.v(j)}, region.footprint);
            std::copy(value.begin(), value.end(), rgb + (std::size_t(j) * region.width + i) * 3);
        }
}

std::unique_ptr<Texture> make_texture(const TextureDescription& description)
{
    validate(description, "texture description");
    if (description.model == "wavelet") return std::make_unique<WaveletTexture>(description);
    if (description.model == "gabor") return std::make_unique<GaborTexture>(description);
    if (description.model == "tiling") return std::make_unique<TilingTexture>(description);
    if (description.model == "ptm") return std::make_unique<PtmTexture>(description);
    if (description.model == "lrp") return std::make_unique<LrpTexture>(description);
    throw Error("texture description: model '" + description.model + "' has no implementation in this build");
}

std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description, const Vec2& period)
{
    validate(description, "texture description");
    for (double p : period)
        if (!(p > 0) || !std::isfinite(p)) throw Error("periodic texture: the period must be positive and finite");
    if (description.model == "wavelet") return std::make_unique<WaveletTexture>(description, period);
    if (description.model == "gabor") return std::make_unique<GaborTexture>(description, period);
    if (description.model == "tiling") return std::make_unique<TilingTexture>(description, period);
    if (description.model == "ptm") return std::make_unique<PtmTexture>(description, period);
    if (description.model == "lrp") return std::make_unique<LrpTexture>(description, period);
    throw Error("periodic texture: model '" + description.model + "' has no periodic form in this build");
}

}  // namespace stochtex
