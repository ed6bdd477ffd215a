// The gabor model (paper 001) in the registry: its parameter schema, analysis options, fit,
// morph and `stex info` lines. The maths is in gabor_kernel, gabor_noise, gabor_statistics,
// gabor_fit and gabor_texture.
#include "numerics/interpolation.h"
#include "models/gabor/gabor_fit.h"
#include "models/gabor/gabor_noise.h"
#include "models/gabor/gabor_texture.h"
#include "models/info_text.h"
#include "models/model.h"
#include "numerics/constants.h"

#include <stochtex/models/gabor_parameters.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace stochtex {

const char* to_string(GaborKind kind)
{
    switch (kind) {
    case GaborKind::isotropic: return "isotropic";
    case GaborKind::anisotropic: return "anisotropic";
    case GaborKind::hybrid: return "hybrid";
    case GaborKind::oriented: return "oriented";
    }
    throw Error("invalid GaborKind value " + std::to_string(static_cast<int>(kind)));
}

GaborKind gabor_kind_from_string(const std::string& name)
{
    for (GaborKind kind : {GaborKind::isotropic, GaborKind::anisotropic, GaborKind::hybrid, GaborKind::oriented})
        if (name == to_string(kind)) return kind;
    throw Error("unknown Gabor kind '" + name + "' (valid: isotropic, anisotropic, hybrid, oriented)");
}

namespace {

constexpr std::size_t max_octaves = 24;
constexpr double unit_tolerance = 1e-4;
// Gabor octaves: frequencies above 1 cycle per exemplar pixel are finer than twice the photo's
// Nyquist frequency (a description that wants them uses a larger pixels_per_unit); the lower
// bound keeps the impulse cells' indices finite at any texture coordinate. Bandwidth and
// impulse count bound the cost of an evaluation. Functions, not globals: the registry builds
// this model during other files' static initialisation (a test model registering itself), when
// a global's std::string may not be constructed yet (g++ 16's order crashed there).
const NumberRange& frequency_range()
{
    static const NumberRange range{1e-6, 1, ""};
    return range;
}
const NumberRange& bandwidth_range()
{
    static const NumberRange range{1.0 / 16, 16, ""};
    return range;
}
const NumberRange& impulse_range()
{
    static const NumberRange range{1, 256, ""};
    return range;
}
const NumberRange& orientation_range()
{
    static const NumberRange range{-90, 90, "degrees"};
    return range;
}
const NumberRange& fraction_range()
{
    static const NumberRange range{0, 1, ""};
    return range;
}

/// One optional per-octave array of the oriented kind: present exactly when the kind is oriented
/// (checked with the frequencies, which every file has), each value in `range`.
void per_octave_numbers(ParameterSchema<GaborParameters>& schema, const char* key,
                        std::vector<double> GaborParameters::*member, const NumberRange& range, const char* unit,
                        const char* doc)
{
    using P = GaborParameters;
    ParameterInfo info{key, "array of numbers", "one per octave, each in " + range.text(), "", unit, doc, {}};
    schema.optional_custom(
        info, [member](const P& p) { return !(p.*member).empty(); },
        [member](const json_fields::Field& f, P& p, const ReadContext&) { p.*member = f.numbers(); },
        [member](const P& p) { return json_fields::Json(p.*member); },
        [member, range](const P& p, const std::string& path, const std::string& source) {
            for (std::size_t k = 0; k < (p.*member).size(); ++k)
                check_in_range((p.*member)[k], range, json_path(path, k), source);
        });
}

ParameterSchema<GaborParameters> gabor_schema()
{
    using P = GaborParameters;
    ParameterSchema<P> schema;
    schema.enumeration("kind", &P::kind, to_string, gabor_kind_from_string,
                       {GaborKind::isotropic, GaborKind::anisotropic, GaborKind::hybrid, GaborKind::oriented},
                       {"isotropic", "", "Which frequencies the kernels draw: isotropic (uniform on the sphere |ω| = F), "
                                         "anisotropic (ω = F·direction), hybrid (uniform on the circle |ω| = F in the "
                                         "plane normal to direction) or oriented (per octave, a share of the kernels "
                                         "along that octave's orientation, the others isotropic)."});
    schema.numbers("direction", &P::direction, {}, {"[0, 0, 1]", "", "A unit vector (length within 1e-4 of 1) in solid texture space "
                                                                   "(u, v, w): the frequency direction (anisotropic) or the normal "
                                                                   "of the frequency plane (hybrid). Unused by isotropic noise, but "
                                                                   "still a unit vector.",
                                                     "unit vector"},
                   [](const P& p, const std::string& path, const std::string& source) {
                       double length2 = 0;
                       for (double d : p.direction) length2 += d * d;
                       if (!(std::fabs(std::sqrt(length2) - 1) <= unit_tolerance))
                           json_fields::fail(source, path,
                                             "must be a unit vector (length within " + number_text(unit_tolerance) +
                                                 " of 1), its length is " + number_text(std::sqrt(length2)));
                   });
    schema.number("bandwidth", &P::bandwidth, bandwidth_range(),
                  {"1", "", "Kernel bandwidth relative to its frequency, a/F, the same for every octave."});
    schema.number("impulses_per_kernel", &P::impulses_per_kernel, impulse_range(),
                  {"16", "impulses", "Mean number of kernels overlapping a point (within the 5 % envelope radius): "
                                    "quality vs cost, which grows linearly with it."});
    schema.numbers("frequencies", &P::frequencies,
                   {"", "cycles / exemplar px", "Octave frequencies F_k. stochtex writes them finest first, an octave apart, "
                                                         "but any order and spacing is valid.",
                    "1 to 24, each in [1e-06, 1]"},
                   [](const P& p, const std::string& path, const std::string& source) {
                       const std::size_t octaves = p.frequencies.size();
                       if (octaves < 1 || octaves > max_octaves)
                           json_fields::fail(source, path,
                                             "expected 1 to " + std::to_string(max_octaves) + " octaves, got " +
                                                 std::to_string(octaves));
                       for (std::size_t k = 0; k < octaves; ++k)
                           check_in_range(p.frequencies[k], frequency_range(), json_path(path, k), source);
                       // The oriented kind's per-octave arrays: there exactly when the kind is oriented.
                       const std::string parent = path.substr(0, path.rfind('.'));
                       const bool oriented = p.kind == GaborKind::oriented;
                       for (const auto& [key, values] : {std::pair{"orientations", &p.orientations},
                                                         std::pair{"oriented_fractions", &p.oriented_fractions}}) {
                           if (!oriented && !values->empty())
                               json_fields::fail(source, json_path(parent, key), "is only valid with kind oriented");
                           if (oriented && values->size() != octaves)
                               json_fields::fail(source, json_path(parent, key),
                                                 values->empty() ? std::string("is required by kind oriented (one per octave)")
                                                                 : "has " + std::to_string(values->size()) +
                                                                       " values but frequencies has " +
                                                                       std::to_string(octaves) + " octaves");
                       }
                   });
    schema.channel_numbers(
        "weights", &P::weights,
        {"", "", "weights[c][k]: the standard deviation of octave k in decorrelated channel c; as many per channel "
                 "as frequencies.",
         "each ≥ 0"},
        [](const P& p, const std::string& key_path, const std::string& source) {
            const std::size_t octaves = p.frequencies.size();
            for (std::size_t channel = 0; channel < 3; ++channel) {
                const std::string path = json_path(key_path, channel);
                const std::vector<double>& weights = p.weights[channel];
                if (weights.size() != octaves)
                    json_fields::fail(source, path,
                                      "has " + std::to_string(weights.size()) + " weights but frequencies has " +
                                          std::to_string(octaves) + " octaves");
                for (std::size_t k = 0; k < octaves; ++k) {
                    check_float_finite(weights[k], json_path(path, k), source);
                    if (weights[k] < 0)
                        json_fields::fail(source, json_path(path, k), "weights must not be negative, got " + number_text(weights[k]));
                }
            }
        });
    per_octave_numbers(schema, "orientations", &P::orientations, orientation_range(), "degrees",
                       "Kind oriented only (required there, absent otherwise): per octave, the angle of the oriented "
                       "kernels' frequency ω in the (u, v) plane, from u towards v (ω and −ω are the same noise).");
    per_octave_numbers(schema, "oriented_fractions", &P::oriented_fractions, fraction_range(), "",
                       "Kind oriented only (required there, absent otherwise): per octave, the share of the kernels "
                       "that are oriented (the others isotropic): 0 isotropic, 1 all along orientations[k].");
    return schema;
}

ModelInfo gabor_info()
{
    ModelInfo info;
    info.name = "gabor";
    info.summary = "random-phase Gabor noise octaves (Lagae & Drettakis 2011): solid textures sliced by the surface, "
                   "filtered analytically; isotropic, anisotropic or hybrid";
    info.doc = "docs/models/gabor.md";
    info.capabilities.analysis = true;
    info.capabilities.solid = true;
    info.capabilities.morph = true;
    info.capabilities.gaussian_channels = true;
    info.capabilities.joint_colour = true;
    info.capabilities.osl = true;
    return info;
}

/// `p`, as kind oriented with every fraction 0 (the same noise) when it is isotropic and `other` is
/// oriented.
GaborParameters as_oriented_if(const GaborParameters& p, GaborKind other)
{
    GaborParameters result = p;
    if (p.kind == GaborKind::isotropic && other == GaborKind::oriented) {
        result.kind = GaborKind::oriented;
        result.orientations.assign(p.frequencies.size(), 0.0);
        result.oriented_fractions.assign(p.frequencies.size(), 0.0);
    }
    return result;
}

class GaborModel final : public TextureModelOf<GaborParameters, GaborTexture> {
public:
    GaborModel() : TextureModelOf(gabor_info(), gabor_schema())
    {
        AnalysisOption bandwidth = number_option(
            "bandwidth", 1.0 / 16, 16, {"auto", "", "kernel bandwidth a / F; auto (or 0): chosen by the fit"}, "auto");
        // 0 was the spelling of "auto" before options were declared; it stays accepted.
        bandwidth.canonical = [](const std::string& text) {
            if (text == "auto") return text;
            char* end = nullptr;
            const double value = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != 0 || !(value == 0 || (value >= bandwidth_range().min && value <= bandwidth_range().max)))
                throw Error("Gabor bandwidth must be 0 (fitted) or in [0.0625, 16], got " + text);
            return value == 0 ? std::string("auto") : text;
        };
        bandwidth.info.range = "auto, 0 or [0.0625, 16]";
        declare_analysis_options(
            {choice_option("gabor-kind", {"auto", "isotropic", "anisotropic", "hybrid", "oriented"},
                           {"auto", "",
                            "auto (isotropic, with oriented octaves where the photo's spectrum shows an orientation: "
                            "kind oriented), isotropic (frequencies on a sphere: slices alike in every direction), "
                            "anisotropic (one orientation for all octaves, measured from the photo: wood, brushed "
                            "metal), hybrid (frequencies in the (u, v) plane) or oriented (auto, kept oriented even "
                            "where no octave is)"}),
             number_option("impulses", 1, 256, {"16", "impulses", "impulses per kernel (quality vs speed; ~16 looks Gaussian)"}),
             bandwidth});
    }


    std::string describe(const TextureDescription& d) const override
    {
        std::ostringstream out;
        const GaborParameters& g = parameters(d);
        out << "gabor        " << to_string(g.kind);
        if (g.kind == GaborKind::anisotropic || g.kind == GaborKind::hybrid)
            out << info_text(g.kind == GaborKind::anisotropic ? ", frequency direction (%.3f, %.3f, %.3f)"
                                                           : ", frequency plane normal (%.3f, %.3f, %.3f)",
                          g.direction[0], g.direction[1], g.direction[2]);
        out << "; bandwidth a/F " << info_text("%.3g", g.bandwidth) << ", " << info_text("%.3g", g.impulses_per_kernel)
            << " impulses per kernel\n";
        const bool oriented = g.kind == GaborKind::oriented;
        out << "octave  cycles/px  wavelength px  kernel radius px     w[0]      w[1]      w[2]"
            << (oriented ? "  oriented  angle °" : "") << "\n";
        for (std::size_t k = 0; k < g.frequencies.size(); ++k) {
            const double f = g.frequencies[k];
            out << info_text("%6.0f  %9.5f  %13.1f", double(k), f, 1 / f)
                << info_text("  %16.1f", GaborNoise::support_radius(g.bandwidth * f))
                << info_text("  %8.5f  %8.5f  %8.5f", g.weights[0][k], g.weights[1][k], g.weights[2][k]);
            if (oriented) out << info_text("  %8.2f  %7.1f", g.oriented_fractions[k], g.orientations[k]);
            out << "\n";
        }
        for (int c = 0; c < 3; ++c)
            out << "sigma_M[" << c << "]   " << info_text("%.5f", gabor_channel_sigma(g.weights[c]))
                << " (octaves have unit variance, 2D and sliced)\n";
        return out.str();
    }

    ModelParameters fit(const FitInput& input, Provenance& provenance) const override
    {
        const std::map<std::string, std::string>& options = input.model_options;
        GaborFitOptions fit;
        const std::string& kind = options.at("gabor-kind");
        fit.kind = kind == "auto" ? GaborKind::oriented : gabor_kind_from_string(kind);
        fit.isotropic_if_unoriented = kind == "auto";
        fit.impulses_per_kernel = std::stod(options.at("impulses"));
        fit.bandwidth = options.at("bandwidth") == "auto" ? 0 : std::stod(options.at("bandwidth"));
        fit.octaves = input.band_count;
        // (The PSD estimator is the wavelet fit's: not recorded.)
        provenance.options.insert(provenance.options.end(), {{"octaves", std::to_string(input.band_count)},
                                                             {"gabor_kind", options.at("gabor-kind")},
                                                             {"impulses", recorded_option(options, "impulses")},
                                                             {"bandwidth", recorded_option(options, "bandwidth")}});
        return fit_gabor_octaves(input.channels, input.width, input.height, fit);
    }

    /// k-th octave to k-th octave, frequencies and bandwidth geometrically (a morph between 0.1
    /// and 0.4 cycles per pixel passes through 0.2), weights linearly, the direction by
    /// normalised lerp after aligning signs (ω and −ω describe the same random-phase noise).
    ModelParameters morph(const TextureDescription& da, const TextureDescription& db, double t) const override
    {
        // An isotropic texture is an oriented one without oriented kernels: the two morph.
        const GaborParameters a = as_oriented_if(parameters(da), parameters(db).kind);
        const GaborParameters b = as_oriented_if(parameters(db), parameters(da).kind);
        if (a.kind != b.kind)
            throw Error(std::string("morph: Gabor kinds differ (") + to_string(a.kind) + " vs " + to_string(b.kind) + ")");
        GaborParameters result = a;
        result.bandwidth = std::exp(lerp(std::log(a.bandwidth), std::log(b.bandwidth), t));
        result.impulses_per_kernel = lerp(a.impulses_per_kernel, b.impulses_per_kernel, t);
        const double sign =
            a.direction[0] * b.direction[0] + a.direction[1] * b.direction[1] + a.direction[2] * b.direction[2] < 0 ? -1 : 1;
        double length = 0;
        for (int i = 0; i < 3; ++i) {
            result.direction[i] = lerp(a.direction[i], sign * b.direction[i], t);
            length += result.direction[i] * result.direction[i];
        }
        for (double& d : result.direction) d /= std::sqrt(length);
        // A missing octave has weight 0 at the other texture's frequency.
        const std::size_t count = std::max(a.frequencies.size(), b.frequencies.size());
        result.frequencies.resize(count);
        for (std::size_t k = 0; k < count; ++k) {
            const double fa = k < a.frequencies.size() ? a.frequencies[k] : b.frequencies[k];
            const double fb = k < b.frequencies.size() ? b.frequencies[k] : a.frequencies[k];
            result.frequencies[k] = std::exp(lerp(std::log(fa), std::log(fb), t));
        }
        if (a.kind == GaborKind::oriented) {
            // Fractions linearly, orientations by their doubled angles (θ and θ + 180° are one
            // orientation); a missing octave is isotropic at the other texture's orientation.
            result.orientations.resize(count), result.oriented_fractions.resize(count);
            for (std::size_t k = 0; k < count; ++k) {
                const double pa = k < a.frequencies.size() ? a.oriented_fractions[k] : 0.0;
                const double pb = k < b.frequencies.size() ? b.oriented_fractions[k] : 0.0;
                const double ta = (k < a.frequencies.size() ? a.orientations[k] : b.orientations[k]) * kPi / 90;
                const double tb = (k < b.frequencies.size() ? b.orientations[k] : a.orientations[k]) * kPi / 90;
                const double x = lerp((pa + 1e-9) * std::cos(ta), (pb + 1e-9) * std::cos(tb), t);
                const double y = lerp((pa + 1e-9) * std::sin(ta), (pb + 1e-9) * std::sin(tb), t);
                result.oriented_fractions[k] = lerp(pa, pb, t);
                result.orientations[k] = std::atan2(y, x) * 90 / kPi;
            }
        }
        for (int c = 0; c < 3; ++c) {
            result.weights[c].assign(count, 0.0);
            for (std::size_t k = 0; k < count; ++k)
                result.weights[c][k] = lerp(k < a.weights[c].size() ? a.weights[c][k] : 0.0,
                                            k < b.weights[c].size() ? b.weights[c][k] : 0.0, t);
        }
        return result;
    }

    double channel_sigma(const TextureDescription& description, int channel) const override
    {
        return gabor_channel_sigma(parameters(description).weights[channel]);
    }
};

}  // namespace

const Model& gabor_model()
{
    static const GaborModel model;
    return model;
}

}  // namespace stochtex
