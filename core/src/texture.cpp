#include <stochtex/error.h>
#include <stochtex/stex_file.h>
#include <stochtex/texture.h>

#include "wavelet_texture.h"

namespace stochtex {

std::unique_ptr<Texture> make_texture(const TextureDescription& description)
{
    validate(description, "texture description");
    if (description.model == "wavelet") return std::make_unique<WaveletTexture>(description);
    throw Error("texture description: model '" + description.model + "' has no implementation in this build");
}

}  // namespace stochtex
