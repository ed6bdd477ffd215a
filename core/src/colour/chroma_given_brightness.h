// Joint colour: the chroma channels conditioned on brightness (TextureDescription's
// chroma_given_brightness; docs/models/README.md, "False colour").
//
// Three decorrelated channels synthesised independently reproduce each channel's histogram but
// not how they go together: where the photo's dark stones are grey-blue and its bright ones
// yellow, independent channels also make bright blue and dark red, colours the photo never had
// (14.5 % of gravel's pixels, by false_colour_rate()). A location–scale model of each chroma
// channel given the brightness channel's standard-normal variate z_0,
//     y_c = location_c(z_0) + scale_c(z_0) · r_c,     c = 1, 2,
// keeps hue and saturation tied to brightness. r_c is what remains of the chroma channel once
// brightness is accounted for; the models synthesise it as before (its spectrum, its histogram
// map), independently of z_0. Filtering keeps its meaning: with the kept and dropped parts
// independent, E[y_c] = E[location_c(z_0 + d_0 Z)] + E[scale_c(z_0 + d_0 Z′)] · E[r_c], each a
// one-dimensional Gauss–Hermite expectation like the histogram maps'.
#pragma once

#include <stochtex/texture_description.h>

#include <array>
#include <string>
#include <vector>

namespace stochtex {

/// Whether the decorrelated channels have joint colour to fit: brightness varies and so does a
/// chroma channel (a grey photo's chroma axes are constant). fit_chroma_given_brightness() fits
/// curves exactly when this holds.
bool has_joint_colour_to_fit(const std::array<std::vector<float>, 3>& channels);

/// Fits the curves to a photo's decorrelated channels (pca mode) and replaces channels 1 and 2
/// by their residuals r_c = (y_c − location_c(u)) / scale_c(u), u = Φ⁻¹(F_0(y_0)) (scale_c in
/// units of its RMS over the photo, so that r_c keeps its channel's typical spread), which the
/// histogram maps and the models' spectra are then fitted to. Knots are uniform in
/// [−z_max, z_max]; each is a Gaussian-kernel regression over its neighbourhood (bandwidth: the
/// knot spacing). Returns an empty description (channels unchanged) when brightness or both
/// chroma channels are constant.
ChromaGivenBrightness fit_chroma_given_brightness(std::array<std::vector<float>, 3>& channels, int knots = 49,
                                                  double z_max = 3.0);

/// Throws Error naming `what` when the description has joint colour: for the front-ends that
/// rebuild the colour stage channel by channel (POV-Ray's colour maps) and cannot express a
/// chroma channel that depends on brightness; `alternative` says what to use instead.
void require_independent_channels(const TextureDescription& description, const std::string& what,
                                  const std::string& alternative);

/// The curves after decorrelated axis `axis` of their texture is negated (morph's alignment of
/// two bases): brightness (0) reverses them in z, a chroma axis negates its location. No-op
/// without joint colour. The knots must be symmetric about 0, as fitted ones are (else Error).
void flip_joint_colour_axis(ChromaGivenBrightness& curves, int axis);

/// Knot-by-knot interpolation of two textures' curves (morph); both with joint colour, or neither
/// (else Error naming the one that has it; morph checks first, so that t = 0 and 1 refuse too). Curves on other knots than a's are resampled onto a's: linear in between, so that
/// is exact when the knots coincide (they do for every analysis: 49 knots on [−3, 3]).
///
/// Why not one texture with joint colour and one without, the latter as location 0, scale 1? That
/// is its colour stage (y_c = 0 + 1 · r_c), but its chroma maps give the chroma values themselves
/// where the other's give residuals in units of its own scale curve: interpolating the scales and
/// the maps separately multiplies two midpoints (with unit-spread residuals, as they were first
/// fitted, the chroma spread at t = 0.5 came out 8× either texture's: σ 0.19–0.23 against
/// 0.027). Rescaling one side's residual needs its histogram map or its model's channel gain,
/// which not every texture has in a model-independent form.
ChromaGivenBrightness morphed_joint_colour(const ChromaGivenBrightness& a, const ChromaGivenBrightness& b, double t);
/// Throws Error (naming the texture that has it) unless both or neither has joint colour.
void require_joint_colour_in_both_or_neither(const ChromaGivenBrightness& a, const ChromaGivenBrightness& b);

/// Evaluation of the curves (uniform knots, linear interpolation, constant beyond the ends).
class ChromaConditioning {
public:
    ChromaConditioning() = default;
    explicit ChromaConditioning(const ChromaGivenBrightness& curves);

    bool enabled() const { return !z_.empty(); }
    /// y1, y2 (channel 1 and 2's own values r_c) become location + scale · r_c at brightness z0,
    /// averaged over the brightness detail filtering removed (dropped0, in σ_M units).
    void apply(double z0, double dropped0, double& y1, double& y2) const;
    /// The curves of channels 1 and 2 at brightness z0, averaged over dropped0 as apply() does.
    void curves_at(double z0, double dropped0, double location[2], double scale[2]) const;

private:
    double curve(const std::vector<double>& values, double z) const;

    std::vector<double> z_;
    std::array<std::vector<double>, 2> location_, scale_;
    double inverse_step_ = 0;
};

}  // namespace stochtex
