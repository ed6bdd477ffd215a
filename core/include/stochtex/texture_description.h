// stochtex — the texture description: everything a .stex file holds, in memory.
//
// A description is model-independent data (colour, histograms, seed, scale, provenance) plus
// exactly one model's parameters. The file format is documented in docs/stex-format.md; the
// reader (stex_file.h) validates every field, so a TextureDescription obtained from a file is
// always usable by make_texture().
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
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

/// Multiresolution wavelet noise by example (paper 000).
struct WaveletParameters {
    /// band_weights[c][j]: weight of band j for channel c. Band j = 0 is the finest: its
    /// frequencies lie in [1/4, 1/2) cycles per exemplar pixel; band j covers [2^-(j+2), 2^-(j+1)).
    std::array<std::vector<double>, 3> band_weights;
};

/// Which frequencies the kernels of a Gabor noise draw (paper 001, Fig. 4). F is an octave's
/// frequency; `direction` is GaborParameters::direction.
enum class GaborKind {
    isotropic,    ///< ω uniform on the sphere |ω| = F: every slice looks alike (granite, sand)
    anisotropic,  ///< ω = F·direction for every kernel: oriented (wood grain, brushed metal)
    hybrid,       ///< ω uniform on the circle |ω| = F in the plane normal to `direction`
};
const char* to_string(GaborKind kind);
GaborKind gabor_kind_from_string(const std::string& name);  // throws Error

/// Random-phase Gabor noise octaves (paper 001, with paper 000's colour and histogram model).
/// Channel c is Σ_k weights[c][k] · n_k, n_k a solid random-phase Gabor noise of unit variance
/// whose kernels have frequency |ω| = frequencies[k] and bandwidth a = bandwidth · frequencies[k].
struct GaborParameters {
    GaborKind kind = GaborKind::isotropic;
    /// Unit vector in solid texture space (u, v, w): the frequency direction (anisotropic) or the
    /// normal of the frequency plane (hybrid); unused by isotropic noise.
    std::array<double, 3> direction{0, 0, 1};
    /// a / F, the same for every octave (so octaves are scaled copies of one another).
    double bandwidth = 1;
    /// Mean number of impulses whose kernel (5 % envelope radius) covers a point: quality vs cost.
    double impulses_per_kernel = 16;
    /// Octave frequencies F_k in cycles per exemplar pixel.
    std::vector<double> frequencies;
    /// weights[c][k]: standard deviation of octave k in channel c (as many as frequencies).
    std::array<std::vector<double>, 3> weights;
};

/// What the blended channels of a tiling texture are (docs/models/tiling.md).
enum class TilingOutput {
    colour,      ///< 3 decorrelated colour channels: histogram maps, then rgb = mean + basis · y
    colour_map,  ///< 2 noises in [0, 1] indexing a 2D colour map (colour-mapped noise vector field)
    normal_map,  ///< 2 slopes (∂h/∂x, ∂h/∂y) per exemplar pixel: a normal map, LEAN-filtered
};
const char* to_string(TilingOutput output);
TilingOutput tiling_output_from_string(const std::string& name);  // throws Error

/// A small image stored inside a .stex file: `channels` planes of width × height samples
/// quantised to `bits` (8 or 16). Sample q of channel c stands for
/// ranges[c][0] + q / (2^bits − 1) · (ranges[c][1] − ranges[c][0]).
struct QuantisedImage {
    int width = 0, height = 0, channels = 0, bits = 8;
    std::vector<std::array<double, 2>> ranges;
    std::vector<std::uint16_t> samples;  ///< planes [c][y][x]
    double value(int channel, int x, int y) const;
};

/// Tiling and blending of an exemplar (paper 002 §1: Heitz–Neyret 2018, Deliot–Heitz 2019).
struct TilingParameters {
    TilingOutput output = TilingOutput::colour;
    /// Edge of the triangle grid in exemplar widths (of the shorter side); 1/(2√3) is Deliot–Heitz's.
    double triangle_edge = 0.28867513459481287;
    /// Periodic, sides powers of two. colour: 3 channels y (histogram-Gaussianised or centred);
    /// colour_map: 2 noises in [0, 1]; normal_map: 2 slopes.
    QuantisedImage exemplar;
    /// colour_map only (else empty): S as 3 channels of sRGB-encoded values in [0, 1]; x follows
    /// noise 0, y noise 1.
    QuantisedImage colour_map;
};

/// How a PTM models colour (paper 004 builds on Malzbender et al.'s PTMs, which have both).
enum class PtmColour {
    lrgb,  ///< one luminance function per texel times a per-texel chroma (9 numbers per texel)
    rgb,   ///< one function per colour channel (18 numbers per texel)
};
const char* to_string(PtmColour colour);
PtmColour ptm_colour_from_string(const std::string& name);  // throws Error

struct PtmMaps;  // stochtex/ptm.h

/// A polynomial texture map (paper 004): per texel a reflectance function of the light
/// direction, evaluated for `light`. The coefficient maps live in a float EXR beside the .stex
/// (docs/stex-format.md, "ptm"); read_stex loads them, write_stex writes them.
struct PtmParameters {
    PtmColour colour = PtmColour::lrgb;
    /// File name of the coefficient maps beside the .stex (no directories). write_stex names
    /// it after the .stex it writes: "<stem>.ptm.exr".
    std::string coefficient_file;
    /// Unit light direction the texture is evaluated for: x to the image's right, y to its top,
    /// z out of the surface (z > 0). Open-time hint: stex:light (stochtex/lighting.h).
    std::array<double, 3> light{0, 0, 1};
    /// The maps (shared by copies of the description; never modified once loaded).
    std::shared_ptr<const PtmMaps> maps;
    /// Unbounded (docs/models/ptm.md, "Unbounded"): the maps — periodic — tiled and blended over
    /// a triangle grid (the tiling model's, seeded by the description's seed), all coefficient
    /// fields with the same tiles; false: the maps repeat.
    bool unbounded = false;
    /// The grid's triangle edge in maps widths (of the shorter side), unbounded only.
    double triangle_edge = 0.28867513459481287;
};

/// One stratum of local random-phase noise (paper 003, §4; docs/models/lrp.md): a part of the
/// spectrum holding an equal share of its energy, with its own lattice of windows, sampled by
/// sub-strata. Every lattice point draws one frequency per sub-stratum, with random phases.
struct LrpStratum {
    /// Δ_S: lattice spacing (and window size), exemplar pixels.
    double spacing = 1;
    /// Standard deviation of the stratum's noise in each decorrelated channel.
    std::array<double, 3> sigma{0, 0, 0};
    /// substrata[j]: frequency bins kx0, ky0, kx1, ky1, … of sub-stratum j, in units of
    /// 1 / spectrum_size cycles per exemplar pixel, on one half of the symmetric spectrum. A
    /// lattice point draws one of them uniformly and jitters it within its bin.
    std::vector<std::vector<int>> substrata;
};

/// One block of the fixed-phase structure: per channel c,
/// Σ_t coefficients[c][2t]·cos θ_t − coefficients[c][2t+1]·sin θ_t, θ_t = 2π k_t·(x − x_b) / fit_size,
/// x_b the block's centre (its window's lattice point).
struct LrpBlock {
    std::vector<int> frequencies;                     ///< kx0, ky0, kx1, ky1, …
    std::array<std::vector<double>, 3> coefficients;  ///< per channel: re0, im0, re1, im1, …
};

/// The fixed-phase region R of texture by example (paper 003, §5): the strongest frequencies of
/// a spectrum_size² crop of the photo, reproduced blockwise; the crop repeats every spectrum_size
/// exemplar pixels, broken by random placement and turbulence.
struct LrpStructure {
    int block_size = 0;  ///< B, exemplar pixels: the crop holds (spectrum_size / B)² blocks
    int fit_size = 0;    ///< E: block frequencies are k / E cycles per exemplar pixel
    bool random_placement = true;  ///< shift blocks of half a crop by random offsets (blended)
    double turbulence = 0;         ///< standard deviation of the displacement, exemplar pixels; 0: none
    /// The blocks' coefficients are stored in files as integer multiples of this step (rounded
    /// on writing): short text, and a round trip that changes nothing.
    double coefficient_step = 1e-4;
    std::vector<LrpBlock> blocks;  ///< row-major
};

/// Local random-phase noise (paper 003): random-phase strata plus an optional fixed-phase structure.
struct LrpParameters {
    int spectrum_size = 256;  ///< T: frequency bins are k / T cycles per exemplar pixel
    std::vector<LrpStratum> strata;
    std::optional<LrpStructure> structure;  ///< absent: noise by example only (r = 0)
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

/// Where a description came from: enough to reproduce the analysis.
struct Provenance {
    std::string source;              ///< file name of the photo (no directories)
    int source_width = 0;
    int source_height = 0;
    std::string input_colour_space;  ///< colour space the photo was decoded from
    std::string tool;                ///< "stochtex <version>"
    /// Analysis options as name/value strings, in a fixed order (kept for round-trip identity).
    std::vector<std::pair<std::string, std::string>> options;
};

struct TextureDescription {
    static constexpr int current_version = 1;

    int version = current_version;
    std::string model;  ///< one of known_models()
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

    Provenance provenance;

    /// The "image" block; absent: ImageLayout's defaults.
    std::optional<ImageLayout> image;

    // Model parameters: exactly the one named by `model` is set.
    std::optional<WaveletParameters> wavelet;
    std::optional<GaborParameters> gabor;
    std::optional<TilingParameters> tiling;
    std::optional<PtmParameters> ptm;
    std::optional<LrpParameters> lrp;
};

/// Model names accepted in .stex files and by `stex analyze --model`.
const std::vector<std::string>& known_models();

}  // namespace stochtex
