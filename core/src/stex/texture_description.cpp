#include <stochtex/error.h>
#include <stochtex/texture_description.h>

namespace stochtex {

namespace {
constexpr ColourMode all_colour_modes[] = {ColourMode::pca, ColourMode::rgb, ColourMode::rgb_shared};
}

const char* to_string(ColourMode mode)
{
    switch (mode) {
    case ColourMode::pca: return "pca";
    case ColourMode::rgb: return "rgb";
    case ColourMode::rgb_shared: return "rgb-shared";
    }
    throw Error("invalid ColourMode value " + std::to_string(static_cast<int>(mode)));
}

ColourMode colour_mode_from_string(const std::string& name)
{
    std::string valid;
    for (ColourMode mode : all_colour_modes) {
        if (name == to_string(mode)) return mode;
        valid += (valid.empty() ? "" : ", ") + std::string(to_string(mode));
    }
    throw Error("unknown colour mode '" + name + "' (valid: " + valid + ")");
}

}  // namespace stochtex
