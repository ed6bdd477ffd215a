// stochtex — morphing between two textures of the same model (paper 000, Fig. 15).
#pragma once

#include <stochtex/texture_description.h>

namespace stochtex {

/// Interpolates a (t = 0) and b (t = 1): means, weights, histogram values and scale linearly,
/// the PCA basis by quaternion slerp after matching axis signs (so U(t) stays a rotation).
/// t = 0 and t = 1 reproduce a and b exactly. Throws Error if the models differ or t ∉ [0, 1].
TextureDescription morph(const TextureDescription& a, const TextureDescription& b, double t);

}  // namespace stochtex
