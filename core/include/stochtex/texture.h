// stochtex — a procedural texture ready to evaluate.
//
// Built once from a TextureDescription (which is validated), then evaluated from any number of
// threads: every method is const and a pure function of (description, point, footprint), so
// the same seed always gives bit-identical values whatever the thread count.
#pragma once

#include <stochtex/footprint.h>
#include <stochtex/texture_description.h>

#include <array>
#include <memory>

namespace stochtex {

using Rgb = std::array<float, 3>;

class Texture {
public:
    virtual ~Texture() = default;

    /// Filtered 2D value at (u, v) in texture units; the footprint is the pixel's Jacobian.
    virtual Rgb eval(const Vec2& uv, const Footprint2D& footprint) const = 0;
    /// Filtered solid (3D) value at a surface point.
    virtual Rgb eval_solid(const SurfacePoint& point) const = 0;
    /// The texture's expected value: what infinite minification converges to.
    virtual Rgb mean() const = 0;

    const TextureDescription& description() const { return description_; }

protected:
    explicit Texture(TextureDescription description) : description_(std::move(description)) {}

private:
    TextureDescription description_;
};

/// Creates the model named by description.model. Throws Error if the description is invalid.
std::unique_ptr<Texture> make_texture(const TextureDescription& description);

/// The same texture made periodic in 2D: eval() repeats with period (period[0], period[1])
/// texture units, so an image covering exactly one period tiles without a seam (the OIIO
/// plugin's virtual image, baked maps). Each band's frequency is snapped so that a whole number
/// of its lattice cells fits the period (≤ 0.1 % change for bands ≥ 512 cells per period);
/// bands too coarse to fit the period at all are treated as filtered away (the histogram map
/// accounts for their variance, as for minification). eval_solid() is not periodic.
/// Throws Error if the model has no periodic form or the period is not positive and finite.
std::unique_ptr<Texture> make_periodic_texture(const TextureDescription& description, const Vec2& period);

}  // namespace stochtex
