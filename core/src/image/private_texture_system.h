// stochtex — a TextureSystem of one's own (not OIIO's shared one) from either OIIO major.
//
// OIIO 2.x's TextureSystem::create() returns a raw pointer that must go back to destroy();
// OIIO 3.x's returns a shared_ptr. This owner type hides the difference, so the OIIO codec, the
// plugin's tests and the TextureSystem bench are one source for both (issue 31).
#pragma once

#include <OpenImageIO/texture.h>

#include <memory>

namespace stochtex {

#if OIIO_VERSION_MAJOR >= 3
using PrivateTextureSystem = std::shared_ptr<OIIO::TextureSystem>;
#else
struct TextureSystemDestroyer {
    void operator()(OIIO::TextureSystem* system) const { OIIO::TextureSystem::destroy(system); }
};
using PrivateTextureSystem = std::unique_ptr<OIIO::TextureSystem, TextureSystemDestroyer>;
#endif

/// A new TextureSystem with its own image cache, freed when the owner goes.
inline PrivateTextureSystem make_private_texture_system()
{
    return PrivateTextureSystem(OIIO::TextureSystem::create(false));
}

}  // namespace stochtex
