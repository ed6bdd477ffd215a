// The wavelet model's procedural POV-Ray form: the texture as SDL that POV-Ray evaluates itself
// (docs/pov.md). Compiled into the POV-Ray front-end, not the core.
//
//   rgb(p) = mean + Σ_c U[:, c] · f_c(z_c(p)),   z_c(p) = Σ_k a_ck · (N(R_ck p · 2^ℓ_ck + o_ck) − μ)
//
// N is POV-Ray's noise, whose mean μ, variance and spectrum were measured (pov_noise_calibration).
// The core fits the octaves' frequencies 2^ℓ and weights so that z_c has the channel's spectrum
// (fit_octaves) and exactly unit variance, which is what the histogram map f_c expects. f_c and
// the signed basis column U[:, c] become one colour_map over the clamped, normalised z_c; the
// three channels and the mean are summed with `average` (POV-Ray 3.7 has no additive pigment),
// every colour scaled by the entry count. R and o are random per octave and channel, drawn at
// parse time from NAME_Seed, so a scene can change the seed without regenerating the include.
#include <stochtex/channel_map.h>
#include <stochtex/error.h>
#include <stochtex/models/channel_spectrum.h>
#include <stochtex/models/wavelet_parameters.h>
#include <stochtex/pov/pov_noise_calibration.h>
#include <stochtex/pov/pov_procedural_form.h>
#include <stochtex/pov/sdl_text.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

namespace stochtex::pov {

namespace {

/// The colour_map covers z in [−z_range, z_range]. Histogram maps are constant beyond their end
/// knots (±3), and a Gaussian channel loses only the 6e-5 of its values beyond ±4 (clamped).
constexpr double z_range = 4;
/// Colour-map knots stay within this fraction of σ_M of the histogram map (a 10-bit display
/// step is ~0.001 of the range): far below the analysis's own error.
constexpr double colour_map_tolerance = 0.002;
/// POV-Ray 3.7's limit on colour_map entries.
constexpr int max_colour_map_entries = 256;
/// Octaves whose weight is below this fraction of the channel's largest are left out.
constexpr double negligible_octave = 1e-3;

/// `average` divides by the entry count: three channels and the mean.
constexpr double average_entries = 4;

struct ChannelOctaves {
    OctaveFit fit;
    double sigma = 0;
    std::vector<int> used;  ///< octaves with non-negligible weight
};
using Channels = std::array<ChannelOctaves, 3>;

std::string fmt(const char* pattern, double a, double b = 0)
{
    char text[160];
    std::snprintf(text, sizeof text, pattern, a, b);
    return text;
}

/// The identifier of channel c's octave k; in rgb-shared mode the channels share their octaves.
struct OctaveNames {
    std::string prefix;
    bool shared_noise;
    std::string operator()(int c, int k) const
    {
        return shared_noise ? prefix + "_Octave_" + std::to_string(k)
                            : prefix + "_Octave_" + std::to_string(c) + "_" + std::to_string(k);
    }
};

/// Each channel's octaves of POV-Ray's noise fitted to its spectrum (a constant channel has none).
Channels fit_channels(const TextureDescription& description, int octave_count)
{
    const PovNoiseCalibration& noise = pov_noise_calibration();
    const bool shared_noise = description.colour_mode == ColourMode::rgb_shared;
    const double finest = std::log2(description.pixels_per_unit);
    Channels channels;
    for (int c = 0; c < 3; ++c) {
        channels[c].sigma = channel_sigma(description, c);
        if (!(channels[c].sigma > 0)) continue;  // a constant channel: no noise at all
        // rgb-shared: every channel uses channel 0's noises (same frequencies and offsets).
        const bool fixed = shared_noise && c > 0 && !channels[0].fit.weight.empty();
        const double shift = fixed ? channels[0].fit.log2_frequency[0] - finest : 0;
        channels[c].fit = fixed ? fit_octaves(channel_spectrum(description, c), channels[c].sigma * channels[c].sigma,
                                              noise.spectrum, noise.variance, finest, octave_count, shift, shift)
                                : fit_octaves(channel_spectrum(description, c), channels[c].sigma * channels[c].sigma,
                                              noise.spectrum, noise.variance, finest, octave_count);
        const auto& w = channels[c].fit.weight;
        const double largest = *std::max_element(w.begin(), w.end());
        for (int k = 0; k < octave_count; ++k)
            if (w[std::size_t(k)] > negligible_octave * largest) channels[c].used.push_back(k);
    }
    return channels;
}

/// The include's header comment: usage, knobs, how it is made, what is exact and the fit's error.
std::string documentation(const TextureDescription& description, const PovIncludeOptions& options, const Channels& channels)
{
    const std::string& n = options.name;
    std::string doc = include_preamble(description, options);
    doc += "\nKnobs (#declare before the #include to override):\n"
           "  " + n + "_Scale   POV-Ray units per texture unit (default: the photo's width in metres)\n"
           "  " + n + "_Seed    any integer: draws the octaves' random rotations and offsets (a different\n"
           "              but statistically identical texture)\n"
           "  " + n + "_Clamp   on: clamp the final colour to [0, 1] (evaluates the pigment 3 times);\n"
           "              off (default): like the core, rare values in the Gaussian tails may leave [0, 1]\n"
           "  " + n + "_Finish  the finish of " + n + " (default: ambient 0, diffuse 1: the pigment is an albedo)\n\n"
           "How it is made. Each decorrelated colour channel c is a sum of octaves of POV-Ray's noise\n"
           "N = f_noise_generator(p, 2), each randomly rotated and offset:\n"
           "  z_c = sum_k a_ck (N(R_ck p 2^l_ck + o_ck) - mu),\n"
           "with frequencies and weights fitted by the core to the channel's spectrum, using the\n"
           "measured mean, variance and spectrum of N (pov/calibration). z_c has unit variance; a\n"
           "colour_map over t = 1/2 + z_c/8 (clamped to [0, 1]: POV-Ray would wrap function values)\n"
           "holds the channel's histogram map times its signed colour-basis column, and `average`\n"
           "adds the three channels and the mean, every colour scaled by 4.\n"
           "Exact: mean colour, colour basis, each channel's variance; histogram maps to within\n" +
           fmt("%.3g", colour_map_tolerance) + " sigma. Approximated: the spectrum (POV-Ray's noise is broader than a\n"
           "wavelet band; fit error per channel below), the noise's marginal distribution (Perlin\n"
           "noise is slightly lighter-tailed than a Gaussian), no anti-aliasing (POV-Ray\n"
           "supersamples: render with +A), and it is a solid texture: planar slices show its\n"
           "statistics, not pixel-for-pixel the core's 2D render.\n"
           "Spectral fit, RMS error per channel (dB):";
    for (int c = 0; c < 3; ++c) doc += channels[c].sigma > 0 ? fmt(" %.2f", channels[c].fit.rms_error_db) : " (constant)";
    return doc + "\n";
}

/// The knobs, the mean colour, and POV-Ray's noise with the macro that makes one random octave.
std::string knobs_and_noise(const TextureDescription& description, const std::string& n)
{
    const PovNoiseCalibration& noise = pov_noise_calibration();
    std::string sdl = "// ---- Knobs -------------------------------------------------------------------------\n";
    sdl += sdl_knob(n + "_Scale", sdl_number(description.unit_size_m), "POV-Ray units per texture unit");
    sdl += sdl_knob(n + "_Seed", std::to_string(description.seed), "random rotations and offsets of the octaves");
    sdl += sdl_knob(n + "_Clamp", "off", "on: final colour clamped to [0, 1]");
    sdl += sdl_knob(n + "_Finish", "finish { ambient 0 diffuse 1 }", "the finish of " + n);

    const Rgb mean = make_texture(description)->mean();
    sdl += "\n#declare " + n + "_Mean = rgb " + sdl_vector({mean[0], mean[1], mean[2]}) +
           ";  // the texture's expected colour\n";

    sdl += "\n// ---- POV-Ray's noise, as measured (" + noise.povray_version + ") ---------------------\n";
    sdl += "#declare " + n + "_Noise = function { internal(78) }  // f_noise_generator (as functions.inc has it)\n";
    sdl += "#declare " + n + "_Noise_Mean = " + sdl_number(noise.mean) + ";  // measured; variance " +
           sdl_number(noise.variance) + "\n";
    sdl += "#declare " + n + "_Random = seed(" + n + "_Seed);\n";
    sdl += "// One octave at Frequency lattice cells per texture unit. The random rotation hides the\n"
           "// noise's axis-aligned lattice and, with the random offset, decorrelates the octaves.\n"
           "#macro " + n + "_Octave(Frequency)\n"
           "  #local Angles = 360 * <rand(" + n + "_Random), rand(" + n + "_Random), rand(" + n + "_Random)>;\n"
           "  #local Cx = Frequency * vrotate(x, Angles);\n"
           "  #local Cy = Frequency * vrotate(y, Angles);\n"
           "  #local Cz = Frequency * vrotate(z, Angles);\n"
           "  // Functions take floats, not vector components: unpack the rotation matrix.\n"
           "  #local R11 = Cx.x; #local R12 = Cy.x; #local R13 = Cz.x;\n"
           "  #local R21 = Cx.y; #local R22 = Cy.y; #local R23 = Cz.y;\n"
           "  #local R31 = Cx.z; #local R32 = Cy.z; #local R33 = Cz.z;\n"
           "  // Offsets keep the noise's arguments positive and far from its lattice origin.\n"
           "  #local O1 = 1000 + 1000 * rand(" + n + "_Random);\n"
           "  #local O2 = 1000 + 1000 * rand(" + n + "_Random);\n"
           "  #local O3 = 1000 + 1000 * rand(" + n + "_Random);\n"
           "  function { " + n + "_Noise(R11*x + R12*y + R13*z + O1, R21*x + R22*y + R23*z + O2, R31*x + R32*y + R33*z + O3, " +
           std::to_string(noise.generator) + ") }\n"
           "#end\n";
    return sdl;
}

/// One #declare per octave in use, each drawn once (rgb-shared: the channels share them).
std::string octave_declarations(const Channels& channels, const OctaveNames& octave, const std::string& n)
{
    std::string sdl;
    std::set<std::string> declared;
    for (int c = 0; c < 3; ++c) {
        if (!(channels[c].sigma > 0)) continue;
        for (int k : channels[c].used) {
            if (!declared.insert(octave(c, k)).second) continue;
            const double frequency = std::exp2(channels[c].fit.log2_frequency[std::size_t(k)]);
            sdl += "#declare " + octave(c, k) + " = " + n + "_Octave(" + sdl_number(frequency) + ");\n";
        }
    }
    return sdl;
}

/// Channel c: its t function (z_c normalised to [0, 1]) and its pigment, a colour_map from t to
/// average_entries · U[:, c] · f_c(z); a constant channel is one colour.
std::string channel_pigment(const TextureDescription& description, const Channels& channels, int c,
                            const OctaveNames& octave, const std::string& n)
{
    const ChannelOctaves& channel = channels[c];
    std::string sdl = "\n";
    // t = 1/2 + z/(2 z_range): the channel's weights a_ck = w_ck / (σ_M · 2 z_range).
    if (channel.sigma > 0) {
        const double to_t = 1.0 / (channel.sigma * 2 * z_range);
        sdl += "#declare " + n + "_T" + std::to_string(c) + " = function { min(1, max(0, 0.5";
        for (int k : channel.used)
            sdl += "\n    + " + sdl_number(channel.fit.weight[std::size_t(k)] * to_t) + " * (" + octave(c, k) +
                   "(x, y, z) - " + n + "_Noise_Mean)";
        sdl += "))\n}\n";
    }
    const auto basis_column = [&](double y) {
        return std::array<double, 3>{average_entries * description.basis[0][c] * y,
                                     average_entries * description.basis[1][c] * y,
                                     average_entries * description.basis[2][c] * y};
    };
    sdl += "#declare " + n + "_Channel_" + std::to_string(c) + " = pigment {\n";
    if (!(channel.sigma > 0)) return sdl + "  rgb " + sdl_vector(basis_column(channel_value(description, c, 0))) + "\n}\n";
    const auto polyline = channel_value_polyline(description, c, -z_range, z_range, colour_map_tolerance * channel.sigma,
                                                 max_colour_map_entries);
    sdl += "  function { " + n + "_T" + std::to_string(c) + "(x, y, z) }\n  color_map {\n";
    for (const auto& [z, y] : polyline)
        sdl += "    [" + sdl_number((z + z_range) / (2 * z_range)) + " rgb " + sdl_vector(basis_column(y)) + "]\n";
    return sdl + "  }\n}\n";
}

/// The three channels and the mean averaged, scaled by the knob, optionally clamped; the texture.
std::string pigment_sum(const TextureDescription& description, const std::string& n)
{
    std::string sdl = "\n// ---- Sum of the channels and the mean; scale; optional clamp -------------------------\n";
    sdl += "#declare " + n + "_Pigment_Unclamped = pigment {\n  average\n  pigment_map {\n";
    for (int c = 0; c < 3; ++c) sdl += "    [1 " + n + "_Channel_" + std::to_string(c) + "]\n";
    sdl += "    [1 rgb " +
           sdl_vector({average_entries * description.mean[0], average_entries * description.mean[1],
                       average_entries * description.mean[2]}) +
           "]\n  }\n";
    sdl += "  scale " + n + "_Scale * <1, -1, 1>  // v runs along -y, as in images\n}\n";
    sdl += "#if (" + n + "_Clamp)\n"
           "  // Functions of a pigment see its colour before output; clamp each component and rebuild.\n"
           "  #declare " + n + "_Unclamped = function { pigment { " + n + "_Pigment_Unclamped } }\n"
           "  #declare " + n + "_Pigment = pigment {\n    average\n    pigment_map {\n"
           "      [1 function { min(1, max(0, " + n + "_Unclamped(x, y, z).red)) } color_map { [0 rgb 0] [1 rgb <3, 0, 0>] }]\n"
           "      [1 function { min(1, max(0, " + n + "_Unclamped(x, y, z).green)) } color_map { [0 rgb 0] [1 rgb <0, 3, 0>] }]\n"
           "      [1 function { min(1, max(0, " + n + "_Unclamped(x, y, z).blue)) } color_map { [0 rgb 0] [1 rgb <0, 0, 3>] }]\n"
           "    }\n  }\n"
           "#else\n"
           "  #declare " + n + "_Pigment = pigment { " + n + "_Pigment_Unclamped }\n"
           "#end\n";
    sdl += "\n#declare " + n + " = texture { pigment { " + n + "_Pigment } finish { " + n + "_Finish } }\n";
    return sdl;
}

PovInclude wavelet_procedural_include(const TextureDescription& description, const PovIncludeOptions& options)
{
    // Joint colour's chroma is location(z_0) + scale(z_0) · r_c: a product of two patterns, which
    // POV-Ray's pattern and colour-map blending cannot form (it can only add them).
    if (description.chroma_given_brightness.enabled())
        throw Error("POV-Ray procedural include: this texture has joint colour (colour.chroma_given_brightness: its "
                    "chroma depends on its brightness), and POV-Ray cannot multiply two patterns to express it; use "
                    "stex pov --mode baked (an image map), or analyse the photo with --joint-colour off");
    const std::string& n = options.name;
    const int bands = int(description.parameters.get<WaveletParameters>().band_weights[0].size());
    // One coarser octave than bands: POV-Ray's noise is broader than a wavelet band, and the
    // fit may use it for the lowest frequencies (or give it weight 0).
    const Channels channels = fit_channels(description, bands + 1);
    const OctaveNames octave{n, description.colour_mode == ColourMode::rgb_shared};

    PovInclude result;
    std::string sdl = sdl_include_begin(n, documentation(description, options, channels));
    sdl += knobs_and_noise(description, n);
    sdl += "\n// ---- Channels: octaves, z_c normalised to t in [0, 1], colour maps ------------------\n";
    sdl += octave_declarations(channels, octave, n);
    result.summary = "procedural: POV-Ray noise octaves fitted to each channel's spectrum, RMS error";
    for (int c = 0; c < 3; ++c) {
        sdl += channel_pigment(description, channels, c, octave, n);
        result.summary += channels[c].sigma > 0 ? fmt(" %.2f", channels[c].fit.rms_error_db) : " (constant)";
    }
    result.summary += " dB";
    sdl += pigment_sum(description, n);
    sdl += sdl_include_end(n);
    result.text = std::move(sdl);
    return result;
}

const PovProceduralFormRegistration registration({"wavelet", wavelet_procedural_include});

}  // namespace

}  // namespace stochtex::pov
