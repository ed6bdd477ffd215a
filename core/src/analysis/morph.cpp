#include <stochtex/error.h>
#include <stochtex/morph.h>
#include <stochtex/stex_file.h>

#include <stochtex/channel_map.h>

#include "numerics/interpolation.h"
#include "colour/chroma_given_brightness.h"
#include "colour/histogram_map.h"
#include "models/model.h"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>

namespace stochtex {

namespace {

Eigen::Matrix3d to_eigen(const std::array<std::array<double, 3>, 3>& m)
{
    Eigen::Matrix3d result;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) result(r, c) = m[r][c];
    return result;
}

/// A channel's map sampled at the knots `z`; a Gaussian channel (no map) is the line σ·z.
std::vector<double> map_values_at(const HistogramMap& map, double sigma, const std::vector<double>& z)
{
    std::vector<double> values;
    if (map.enabled()) {
        const MonotoneCubic curve(map.z, map.value);
        for (double knot : z) values.push_back(curve(knot));
    } else {
        for (double knot : z) values.push_back(sigma * knot);
    }
    return values;
}

}  // namespace

TextureDescription morph(const TextureDescription& a, const TextureDescription& b, double t)
{
    if (!(t >= 0 && t <= 1)) throw Error("morph: t must be in [0, 1], got " + std::to_string(t));
    if (a.model != b.model)
        throw Error("morph: cannot morph a '" + a.model + "' texture into a '" + b.model + "' texture");
    const Model& model = model_of(a, "morph");  // an unknown model is an error, never a pass-through
    if (!model.info().capabilities.morph) {
        model.morph(a, b, t);  // throws the model's reason
        throw Error("morph: model '" + a.model + "' cannot be morphed");
    }
    if (a.colour_mode != b.colour_mode)
        throw Error(std::string("morph: colour modes differ (") + to_string(a.colour_mode) + " vs " +
                    to_string(b.colour_mode) + ")");
    // Joint colour is interpolated only between textures that both have it (t = 0 and 1 too).
    require_joint_colour_in_both_or_neither(a.chroma_given_brightness, b.chroma_given_brightness);
    if (t == 0) return a;
    if (t == 1) return b;

    // Match b's axes to a's: an axis and its negation describe the same channel once that
    // channel's histogram is mirrored. Flipping an odd number of axes would make det = −1, so
    // then the least aligned flip is undone (that pair is nearly orthogonal anyway).
    TextureDescription aligned = b;
    const Eigen::Matrix3d basis_a = to_eigen(a.basis);
    Eigen::Matrix3d basis_b = to_eigen(b.basis);
    int flips = 0, least_aligned = -1;
    for (int c = 0; c < 3; ++c) {
        const double alignment = basis_a.col(c).dot(basis_b.col(c));
        if (alignment < 0) {
            ++flips;
            if (least_aligned < 0 || std::abs(alignment) < std::abs(basis_a.col(least_aligned).dot(basis_b.col(least_aligned))))
                least_aligned = c;
        }
    }
    for (int c = 0; c < 3; ++c) {
        const bool flip = basis_a.col(c).dot(basis_b.col(c)) < 0 && !(flips % 2 == 1 && c == least_aligned);
        if (!flip) continue;
        basis_b.col(c) = -basis_b.col(c);
        if (aligned.histograms[c].enabled()) aligned.histograms[c] = mirrored(aligned.histograms[c]);
        flip_joint_colour_axis(aligned.chroma_given_brightness, c);
    }

    TextureDescription result = a;
    const Eigen::Quaterniond qa(basis_a), qb(basis_b);
    const Eigen::Matrix3d basis = qa.slerp(t, qb).normalized().toRotationMatrix();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) result.basis[r][c] = basis(r, c);
    for (int c = 0; c < 3; ++c) result.mean[c] = lerp(a.mean[c], aligned.mean[c], t);
    // Scale: geometric, so a morph between 512 and 2048 pixels per unit passes through 1024.
    result.pixels_per_unit = std::exp(lerp(std::log(a.pixels_per_unit), std::log(aligned.pixels_per_unit), t));
    result.unit_size_m = lerp(a.unit_size_m, aligned.unit_size_m, t);

    result.parameters = model.morph(a, aligned, t);
    for (int c = 0; c < 3; ++c) {
        const HistogramMap& ha = a.histograms[c];
        const HistogramMap& hb = aligned.histograms[c];
        if (!ha.enabled() && !hb.enabled()) continue;
        // Interpolate the two maps on one set of knots (a's, else b's).
        const std::vector<double>& z = ha.enabled() ? ha.z : hb.z;
        const std::vector<double> va = map_values_at(ha, channel_sigma(a, c), z);
        const std::vector<double> vb = map_values_at(hb, channel_sigma(aligned, c), z);
        HistogramMap& map = result.histograms[c];
        map.z = z;
        map.value.resize(z.size());
        for (std::size_t k = 0; k < z.size(); ++k) map.value[k] = lerp(va[k], vb[k], t);
    }

    result.chroma_given_brightness = morphed_joint_colour(a.chroma_given_brightness, aligned.chroma_given_brightness, t);

    std::ostringstream source;
    source << "morph(" << a.provenance.source << ", " << b.provenance.source << ", t=" << t << ")";
    result.provenance.source = source.str();
    result.provenance.options = {{"morph_t", std::to_string(t)}};
    validate(result, "morph result");
    return result;
}

}  // namespace stochtex
