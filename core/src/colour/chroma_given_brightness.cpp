#include "colour/chroma_given_brightness.h"

#include "colour/gaussian.h"
#include "colour/histogram_map.h"
#include "numerics/interpolation.h"

#include <stochtex/error.h>

#include <algorithm>
#include <cmath>

namespace stochtex {

bool has_joint_colour_to_fit(const std::array<std::vector<float>, 3>& channels)
{
    if (channels[0].empty()) return false;
    const double chroma_sigma = std::max(EmpiricalDistribution(channels[1]).stddev(), EmpiricalDistribution(channels[2]).stddev());
    return EmpiricalDistribution(channels[0]).stddev() > 1e-7 && chroma_sigma > 1e-7;
}

ChromaGivenBrightness fit_chroma_given_brightness(std::array<std::vector<float>, 3>& channels, int knots, double z_max)
{
    ChromaGivenBrightness curves;
    const std::vector<float>& brightness = channels[0];
    const std::size_t n = brightness.size();
    if (knots < 2 || !has_joint_colour_to_fit(channels)) return curves;
    const EmpiricalDistribution distribution(brightness);
    const std::array<double, 2> chroma_sigma{EmpiricalDistribution(channels[1]).stddev(),
                                             EmpiricalDistribution(channels[2]).stddev()};

    // u: brightness as a standard-normal variate (ranks), what the model's channel 0 is.
    std::vector<float> u(n);
    const double lowest = 0.5 / double(n);
    for (std::size_t i = 0; i < n; ++i)
        u[i] = float(inverse_normal_cdf(std::clamp(distribution.cdf(brightness[i]), lowest, 1 - lowest)));

    // Moments in fine bins of u (0.02 wide), then a Gaussian kernel over the bins per knot:
    // O(pixels + knots · bins), not O(pixels · knots).
    const double step = 2 * z_max / (knots - 1), bandwidth = step;
    constexpr double bin_width = 0.02;
    const double u_low = -z_max - 4 * bandwidth;
    const int bins = int(std::ceil((2 * z_max + 8 * bandwidth) / bin_width));
    std::vector<double> count(bins, 0), sum[2], square[2];
    for (int c = 0; c < 2; ++c) sum[c].assign(bins, 0), square[c].assign(bins, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const int bin = std::clamp(int((u[i] - u_low) / bin_width), 0, bins - 1);
        count[bin] += 1;
        for (int c = 0; c < 2; ++c) {
            const double y = channels[c + 1][i];
            sum[c][bin] += y;
            square[c][bin] += y * y;
        }
    }
    curves.z.resize(knots);
    for (int c = 0; c < 2; ++c) curves.location[c].resize(knots), curves.scale[c].resize(knots);
    for (int k = 0; k < knots; ++k) {
        const double z = k == knots - 1 ? z_max : -z_max + k * step;  // exactly symmetric ends
        curves.z[k] = z;
        double weight = 0, first[2] = {0, 0}, second[2] = {0, 0};
        for (int bin = 0; bin < bins; ++bin) {
            if (count[bin] == 0) continue;
            const double t = (u_low + (bin + 0.5) * bin_width - z) / bandwidth;
            const double w = std::exp(-0.5 * t * t);
            weight += w * count[bin];
            for (int c = 0; c < 2; ++c) first[c] += w * sum[c][bin], second[c] += w * square[c][bin];
        }
        for (int c = 0; c < 2; ++c) {
            const double mean = weight > 0 ? first[c] / weight : 0;
            const double variance = weight > 0 ? second[c] / weight - mean * mean : 0;
            // A floor keeps the residual finite where a chroma channel is (locally) constant.
            // (Raising it to 0.05–0.3 σ changed nothing measurable but gravel's false colour, for the worse.)
            const double floor = std::max(1e-3 * chroma_sigma[c], 1e-9);
            curves.location[c][k] = mean;
            curves.scale[c][k] = std::sqrt(std::max(variance, floor * floor));
        }
    }

    // The residuals keep their channel's typical spread (the RMS of scale_c over the photo), not
    // a unit one: the scale curves are divided by it. The texture is the same either way, but
    // models that fit all channels' spectra together (gabor's orientations, lrp's strata) weigh
    // each by its energy, and unit-spread chroma residuals (concrete's chroma σ ~ 0.01 against
    // brightness's 0.06) would outweigh brightness there and set its orientations and strata.
    const ChromaConditioning fitted(curves);
    double spread_squared[2] = {0, 0};
    for (std::size_t i = 0; i < n; ++i) {
        double location[2], scale[2];
        fitted.curves_at(u[i], 0, location, scale);
        for (int c = 0; c < 2; ++c) spread_squared[c] += scale[c] * scale[c];
    }
    for (int c = 0; c < 2; ++c) {
        const double spread = std::sqrt(spread_squared[c] / double(n));
        for (double& scale : curves.scale[c]) scale /= spread;
    }

    const ChromaConditioning conditioning(curves);
    for (std::size_t i = 0; i < n; ++i) {
        double location[2], scale[2];
        conditioning.curves_at(u[i], 0, location, scale);
        for (int c = 0; c < 2; ++c) channels[c + 1][i] = float((channels[c + 1][i] - location[c]) / scale[c]);
    }
    return curves;
}

void require_independent_channels(const TextureDescription& description, const std::string& what,
                                  const std::string& alternative)
{
    if (description.chroma_given_brightness.enabled())
        throw Error(what + ": this texture has joint colour (colour.chroma_given_brightness: its chroma depends on its "
                           "brightness), which this output cannot express channel by channel; " + alternative +
                    ", or analyse the photo with --joint-colour off");
}

void flip_joint_colour_axis(ChromaGivenBrightness& curves, int axis)
{
    if (!curves.enabled()) return;
    if (axis == 0) {
        // z_0 → −z_0: the same curves read from the other end, on knots symmetric about 0.
        for (std::size_t k = 0; k < curves.z.size(); ++k)
            if (std::abs(curves.z[k] + curves.z[curves.z.size() - 1 - k]) > 1e-9 * (1 + std::abs(curves.z[k])))
                throw Error("morph: joint colour's knots are not symmetric about 0, so its brightness axis cannot be "
                            "flipped to match the other texture's");
        for (int c = 0; c < 2; ++c) {
            std::reverse(curves.location[c].begin(), curves.location[c].end());
            std::reverse(curves.scale[c].begin(), curves.scale[c].end());
        }
    } else {
        // y_c → −y_c = −location_c + scale_c · (−r_c): the residual's map is mirrored with it.
        for (double& value : curves.location[axis - 1]) value = -value;
    }
}

void require_joint_colour_in_both_or_neither(const ChromaGivenBrightness& a, const ChromaGivenBrightness& b)
{
    if (a.enabled() != b.enabled())
        throw Error(std::string("morph: only the ") + (a.enabled() ? "first" : "second") +
                    " texture has joint colour (colour.chroma_given_brightness), and its chroma residuals cannot be "
                    "interpolated with the other's chroma values; analyse both photos with the same --joint-colour");
}

ChromaGivenBrightness morphed_joint_colour(const ChromaGivenBrightness& a, const ChromaGivenBrightness& b, double t)
{
    require_joint_colour_in_both_or_neither(a, b);
    if (!a.enabled()) return {};
    ChromaGivenBrightness result;
    result.z = a.z;
    const ChromaConditioning resample_b(b);
    // One texture's curves at knot k of the result: its own values on the same knots.
    const auto at_knot = [&](const ChromaGivenBrightness& curves, std::size_t k, double location[2], double scale[2]) {
        if (curves.z == result.z) {
            for (int c = 0; c < 2; ++c) location[c] = curves.location[c][k], scale[c] = curves.scale[c][k];
        } else {
            resample_b.curves_at(result.z[k], 0, location, scale);  // only b's knots can differ
        }
    };
    for (int c = 0; c < 2; ++c) result.location[c].resize(result.z.size()), result.scale[c].resize(result.z.size());
    for (std::size_t k = 0; k < result.z.size(); ++k) {
        double location_a[2], scale_a[2], location_b[2], scale_b[2];
        at_knot(a, k, location_a, scale_a);
        at_knot(b, k, location_b, scale_b);
        for (int c = 0; c < 2; ++c) {
            result.location[c][k] = lerp(location_a[c], location_b[c], t);
            result.scale[c][k] = lerp(scale_a[c], scale_b[c], t);
        }
    }
    return result;
}

ChromaConditioning::ChromaConditioning(const ChromaGivenBrightness& curves)
    : z_(curves.z), location_(curves.location), scale_(curves.scale)
{
    if (z_.size() >= 2) inverse_step_ = double(z_.size() - 1) / (z_.back() - z_.front());
    else z_.clear();
}

double ChromaConditioning::curve(const std::vector<double>& values, double z) const
{
    // Uniform knots (validated): the segment by one multiplication.
    const double position = (z - z_.front()) * inverse_step_;
    if (!(position > 0)) return values.front();
    const std::size_t last = values.size() - 1;
    if (position >= double(last)) return values.back();
    const std::size_t i = std::size_t(position);
    const double s = position - double(i);
    return values[i] + s * (values[i + 1] - values[i]);
}

void ChromaConditioning::curves_at(double z0, double dropped0, double location[2], double scale[2]) const
{
    location[0] = location[1] = scale[0] = scale[1] = 0;
    if (dropped0 < 1e-4) {
        for (int c = 0; c < 2; ++c) location[c] = curve(location_[c], z0), scale[c] = curve(scale_[c], z0);
    } else {
        const GaussHermite& rule = GaussHermite::standard_normal();
        for (int i = 0; i < GaussHermite::count; ++i) {
            const double z = z0 + dropped0 * rule.node[i];
            for (int c = 0; c < 2; ++c) {
                location[c] += rule.weight[i] * curve(location_[c], z);
                scale[c] += rule.weight[i] * curve(scale_[c], z);
            }
        }
    }
}

void ChromaConditioning::apply(double z0, double dropped0, double& y1, double& y2) const
{
    double location[2], scale[2];
    curves_at(z0, dropped0, location, scale);
    y1 = location[0] + scale[0] * y1;
    y2 = location[1] + scale[1] * y2;
}

}  // namespace stochtex
