// stochtex — OIIO's names for gamma-encoded colour spaces (colour_space_names.h).
#include "image/colour_space_names.h"

#include <OpenImageIO/oiioversion.h>

#include <cctype>
#include <cmath>
#include <cstdio>

namespace stochtex {

namespace {

bool all_digits(const std::string& text)
{
    if (text.empty()) return false;
    for (const char c : text)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    return true;
}

}  // namespace

double encoding_gamma(const std::string& colour_space)
{
    // OIIO 2.x: "Gamma" and a number ("Gamma2.2", "Gamma1.8").
    if (colour_space.rfind("Gamma", 0) == 0 && colour_space.size() > 5) {
        std::size_t used = 0;
        try {
            const double gamma = std::stod(colour_space.substr(5), &used);
            return used == colour_space.size() - 5 && gamma > 0 ? gamma : 0;
        } catch (...) {
            return 0;
        }
    }
    // OIIO 3.x: "g" and the gamma's digits without the point, then "_rec709" or "_rec709_scene".
    for (const char* suffix : {"_rec709", "_rec709_scene"}) {
        const std::string tail(suffix);
        if (colour_space.size() <= tail.size() + 2 || colour_space[0] != 'g' ||
            colour_space.compare(colour_space.size() - tail.size(), tail.size(), tail) != 0)
            continue;
        const std::string digits = colour_space.substr(1, colour_space.size() - tail.size() - 1);
        if (all_digits(digits)) return std::stod(digits.substr(0, 1) + "." + digits.substr(1));
    }
    return 0;
}

std::string oiio_colour_space_name(const std::string& colour_space)
{
    const double gamma = encoding_gamma(colour_space);
    if (gamma == 0) return colour_space;
#if OIIO_VERSION_MAJOR >= 3
    if (std::abs(gamma - 1.8) < 1e-6) return "g18_rec709";
    if (std::abs(gamma - 2.2) < 1e-6) return "g22_rec709";
    return {};
#else
    if (colour_space.rfind("Gamma", 0) == 0) return colour_space;  // already OIIO 2.x's own name
    char name[32];
    std::snprintf(name, sizeof name, "Gamma%.2g", gamma);  // OIIO 2.x's "Gamma{:.2}"
    return name;
#endif
}

}  // namespace stochtex
