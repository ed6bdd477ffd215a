// stochtex — the texture description: everything a .stex file holds, in memory.
//
// A description is model-independent data (colour, histograms, seed, scale, provenance) plus
// exactly one model's parameters (held as ModelParameters; each model's struct is in
// stochtex/models/). The file format is documented in docs/stex-format.md; the
// reader (stex_file.h) validates every field, so a TextureDescription obtained from a file is
// always usable by make_texture().
#pragma once

#include <any>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

namespace stochtex {

/// How colour is modelled (paper 000, §6 and Fig. 7).
enum class ColourMode {
    pca,         ///< decorrelated channels (principal axes of the RGB covariance) — the default
    rgb,         ///< R, G, B synthesised independently with different offsets (Fig. 7b)
    rgb_shared,  ///< R, G, B with the same offsets: perfectly correlated channels (Fig. 7c)
};
const char* to_string(ColourMode mode);
ColourMode colour_mode_from_string(const std::string& name);  // throws Error

/// A monotone map from a standard-normal variate z to a channel value: the channel's inverse
/// CDF composed with the normal CDF, Q(Φ(z)), as a monotone cubic (Fritsch–Carlson) through the
/// knots. Outside [z.front(), z.back()] the end values hold (no extrapolation).
/// An empty map means "no histogram matching": the channel stays Gaussian.
struct HistogramMap {
    std::vector<double> z;      ///< strictly increasing knot positions, symmetric about 0
    std::vector<double> value;  ///< non-decreasing channel values at the knots
    bool enabled() const { return !z.empty(); }
};

/// Chroma given brightness (the "joint colour" of `stex analyze --joint-colour`): decorrelated
/// channels 1 and 2 (the chroma axes) as y_c = location_c(z_0) + scale_c(z_0) · r_c, where z_0 is
/// channel 0's standard-normal variate and r_c channel c's own (histogram-mapped) noise. The
/// curves are piecewise linear through knots z (uniform, symmetric about 0), constant beyond
/// the end knots. A photo whose dark and bright parts have different hues (grey-blue and yellow
/// stones) keeps them together; three independent channels would mix them into colours the
/// photo never had. Empty: the channels are independent (y_c = r_c).
struct ChromaGivenBrightness {
    std::vector<double> z;
    std::array<std::vector<double>, 2> location;  ///< channels 1 and 2, at the knots
    std::array<std::vector<double>, 2> scale;     ///< channels 1 and 2, at the knots (> 0)
    bool enabled() const { return !z.empty(); }
};

/// A small image stored inside a .stex file: `channels` planes of width × height samples
/// quantised to `bits` (8 or 16). Sample q of channel c stands for
/// ranges[c][0] + q / (2^bits − 1) · (ranges[c][1] − ranges[c][0]).
struct QuantisedImage {
    int width = 0, height = 0, channels = 0, bits = 8;
    std::vector<std::array<double, 2>> ranges;
    std::vector<std::uint16_t> samples;  ///< planes [c][y][x]
    double value(int channel, int x, int y) const;
};

/// One model's parameters, whatever the model: a value (copies are deep) holding the parameter
/// struct of the model the description names (stochtex/models/<name>_parameters.h), or nothing.
/// Which struct belongs to which model is the model registry's knowledge (stochtex/model.h).
class ModelParameters {
public:
    ModelParameters() = default;
    template <class Parameters, class = std::enable_if_t<!std::is_same_v<std::decay_t<Parameters>, ModelParameters>>>
    ModelParameters(Parameters value) : value_(std::move(value)) {}

    bool empty() const { return !value_.has_value(); }
    void reset() { value_.reset(); }
    template <class Parameters>
    bool holds() const { return std::any_cast<Parameters>(&value_) != nullptr; }
    /// The parameters as `Parameters`; throws Error if they are of another model (or absent).
    template <class Parameters>
    Parameters& get() { return *checked(std::any_cast<Parameters>(&value_)); }
    template <class Parameters>
    const Parameters& get() const { return *checked(std::any_cast<Parameters>(&value_)); }
    /// The held struct's type (typeid(void) when empty), for the registry.
    const std::type_info& type() const { return value_.type(); }

private:
    template <class T>
    static T* checked(T* value)
    {
        if (!value) wrong_type();
        return value;
    }
    [[noreturn]] static void wrong_type();
    std::any value_;
};

/// How image consumers (the OIIO plugin) present the texture: a virtual image that is one
/// period of the periodic texture, MIP-mapped down to 1 × 1. Optional in a .stex file; these
/// defaults apply when it is absent, and open-time hints override any field.
struct ImageLayout {
    int width = 16384;
    int height = 16384;
    int tile_width = 64;
    int tile_height = 64;
    /// Exemplar pixels per level-0 pixel (1: the photo's own pixel scale; 2: zoomed out ×2).
    double scale = 1.0;
    /// "RGB", "RGBA" (alpha 1) or "Y" (Rec.709 luminance).
    std::string channels = "RGB";
};

/// How one candidate scored when `analyze --model auto` chose the model (stochtex/analysis.h):
/// the metrics of its render against the photo (stochtex/metrics.h) and the size of its file.
struct ModelScore {
    std::string model;
    std::string colour = "pca";               ///< the colour mode it was fitted with
    bool joint_colour = false;                ///< with joint colour (chroma given brightness)
    /// A variant of the model's fit the choice also tried (Model::automatic_variants), as the
    /// provenance options it adds, "name value" joined by ", " ("blend_contrast 8"); empty: the fit.
    std::string variant;
    double penalty = 0;                       ///< fidelity_penalty(): lower is closer to the photo
    double radial_log_psd_db = 0;             ///< mean over RGB
    double polar_log_psd_db = 0;              ///< 2D (oriented) log-PSD distance of luma
    double w1_sigma = 0;                      ///< the worst RGB channel's W1/σ
    double false_colour_rate = 0;             ///< a fraction
    double gradient_orientation_degrees = 0;
    double gradient_magnitude_w1 = 0;
    /// Portilla–Simoncelli structure distance (StructureDistance::total); NaN where the choice did
    /// not score it.
    double structure_distance = std::numeric_limits<double>::quiet_NaN();
    long long bytes = 0;                      ///< its .stex file (embedded images included)
};

/// Where a description came from: enough to reproduce the analysis.
struct Provenance {
    std::string source;              ///< file name of the photo (no directories)
    int source_width = 0;
    int source_height = 0;
    std::string input_colour_space;  ///< colour space the photo was decoded from
    std::string tool;                ///< "stochtex <version>"
    /// Analysis options as name/value strings, in a fixed order (kept for round-trip identity).
    std::vector<std::pair<std::string, std::string>> options;
    /// `--model auto`: every candidate's score, in registry order (empty when a model was named).
    std::vector<ModelScore> model_choice;
};

struct TextureDescription {
    static constexpr int current_version = 1;

    int version = current_version;
    std::string model;  ///< a registered model (stochtex/model.h: known_models())
    std::uint32_t seed = 1;

    /// Exemplar pixels per texture unit: a render at units_per_pixel = 1/pixels_per_unit shows
    /// the texture at the photo's own pixel scale.
    double pixels_per_unit = 512;
    /// Physical size of one texture unit in metres (for scenes); informational for the core.
    double unit_size_m = 1.0;

    // Colour (scene-linear Rec.709). rgb = mean + basis · y, y the decorrelated channels.
    std::string colour_space = "lin_rec709";
    ColourMode colour_mode = ColourMode::pca;
    std::array<double, 3> mean{0, 0, 0};
    /// basis[row][col]; column c is the RGB direction of decorrelated channel c. Orthonormal,
    /// det +1, columns sorted by decreasing variance (identity in the RGB modes).
    std::array<std::array<double, 3>, 3> basis{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    /// Per decorrelated channel; each may be disabled (empty).
    std::array<HistogramMap, 3> histograms;
    /// Chroma channels conditioned on brightness (pca colour mode only); empty: independent.
    ChromaGivenBrightness chroma_given_brightness;

    Provenance provenance;

    /// The "image" block; absent: ImageLayout's defaults.
    std::optional<ImageLayout> image;

    /// The parameters of the model named by `model` (its struct, and no other model's).
    ModelParameters parameters;
};

}  // namespace stochtex
