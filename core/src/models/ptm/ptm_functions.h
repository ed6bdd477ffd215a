// One texel of a PTM as functions of the light direction (shared by relighting, normal
// estimation and the ptm texture).
#pragma once

#include "models/ptm/legendre_basis.h"

#include <stochtex/footprint.h>
#include <stochtex/texture_description.h>
#include <stochtex/models/ptm_parameters.h>

#include <array>

namespace stochtex {

/// Rec.709 luma of scene-linear RGB: the luminance of lrgb PTMs and of the normal estimate.
constexpr double luma_weights[3] = {0.2126, 0.7152, 0.0722};

/// The R, G and B reflectance functions of one texel (its ptm_channel_count floats), each as
/// Legendre coefficients. lrgb: the luminance function scaled by each chroma factor — exact,
/// so an lrgb texel and its rgb form relight identically before clamping.
std::array<legendre::Terms, 3> texel_colour_functions(PtmColour colour, const float* texel);

/// The Legendre basis at a light direction's projection (l_u, l_v) = (x, y).
inline legendre::Terms basis_at(const Vec3& light) { return legendre::legendre(light[0], light[1]); }

}  // namespace stochtex
