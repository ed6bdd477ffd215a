#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <cmath>

#include "models/model.h"

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
    return model_of(description).make_texture(description);
}

std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description, const Vec2& period)
{
    validate(description, "texture description");
    for (double p : period)
        if (!(p > 0) || !std::isfinite(p)) throw Error("periodic texture: the period must be positive and finite");
    return model_of(description).make_periodic_texture(description, period);
}

}  // namespace stochtex
