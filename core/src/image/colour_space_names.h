// stochtex — OIIO's names for gamma-encoded colour spaces, across its majors (issue 31).
//
// A photo's colour space comes from the file as the OIIO that read it names it, and a PNG with
// a gAMA chunk is named differently by each major: OIIO 2.x says "Gamma2.2" (and converts any
// "GammaX.Y"), OIIO 3.x says "g22_rec709_scene" and knows only "g18_rec709" and "g22_rec709"
// (with or without "_scene"): "Gamma2.2" is "not found" there, and so is a 2.4 or 2.6 gamma by
// any name. These helpers translate to what the linked OIIO knows; the gammas it has no name for
// are plain powers (Rec.709 primaries, the scene-linear primaries), applied by the caller.
#pragma once

#include <string>

namespace stochtex {

/// The exponent of a pure-power encoding named the OIIO 2.x or 3.x way, else 0.
double encoding_gamma(const std::string& colour_space);

/// `colour_space` as the OIIO stochtex is built with names it; unchanged if it is not a gamma
/// encoding. Empty when that OIIO has no name for that gamma.
std::string oiio_colour_space_name(const std::string& colour_space);

}  // namespace stochtex
