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

const char* to_string(GaborKind kind)
{
    switch (kind) {
    case GaborKind::isotropic: return "isotropic";
    case GaborKind::anisotropic: return "anisotropic";
    case GaborKind::hybrid: return "hybrid";
    }
    throw Error("invalid GaborKind value " + std::to_string(static_cast<int>(kind)));
}

GaborKind gabor_kind_from_string(const std::string& name)
{
    for (GaborKind kind : {GaborKind::isotropic, GaborKind::anisotropic, GaborKind::hybrid})
        if (name == to_string(kind)) return kind;
    throw Error("unknown Gabor kind '" + name + "' (valid: isotropic, anisotropic, hybrid)");
}

const std::vector<std::string>& known_models()
{
    static const std::vector<std::string> models{"wavelet", "gabor", "tiling", "lrp", "ptm"};
    return models;
}

}  // namespace stochtex
