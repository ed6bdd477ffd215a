// stochtex — relightable textures: polynomial texture maps (PTM) fitted to photos of one surface
// under known lights, synthesised in the space of reflectance functions, relit for any light
// (paper 004, Hel-Or, Malzbender & Gelb; docs/models/ptm.md).
//
// Light directions are unit vectors in the image's frame: x to the right, y to the top of the
// image, z out of the surface towards the camera (z > 0). A PTM is a function of the light's
// projection (l_u, l_v) = (x, y) on the surface.
#pragma once

#include <stochtex/footprint.h>
#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/progress.h>
#include <stochtex/texture_description.h>
#include <stochtex/models/ptm_parameters.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace stochtex {

/// A PTM's coefficient maps in the orthonormal Legendre basis (ψ-space, legendre_basis.h).
/// Per texel, lrgb: the 6 coefficients b0 … b5 of the luminance function, then the chroma
/// factors R, G, B (colour = luminance · chroma); rgb: 6 coefficients for R, then G, then B.
/// Luminance is Rec.709 luma of scene-linear RGB.
struct PtmMaps {
    PtmColour colour = PtmColour::lrgb;
    Image coefficients;  ///< channels: ptm_channel_count(colour)
    int width() const { return coefficients.width; }
    int height() const { return coefficients.height; }
};
int ptm_channel_count(PtmColour colour);
/// Channel names in coefficient files: "Y.b0" … "Y.b5", "chroma.R" … (lrgb); "R.b0" … "B.b5" (rgb).
std::vector<std::string> ptm_channel_names(PtmColour colour);
/// Channels that are Legendre coefficients of one function (matched and cut by synthesis):
/// the first 6 (lrgb) or all 18 (rgb).
int ptm_function_channel_count(PtmColour colour);

// ---- Input: photos under known lights ----------------------------------------------------------

/// Photos of one surface from one fixed camera, each under one directional light.
struct LightSet {
    std::vector<std::string> images;  ///< paths, resolved against the sidecar's folder
    std::vector<Vec3> directions;     ///< unit vectors, z > 0
};
/// Reads a light sidecar: ".lp" (the RTI light-position list: a count, then "image x y z" per
/// line) or ".json" ({"lights": [{"image": …, "direction": [x, y, z]}, …]}). Strict: every
/// problem is an Error naming the file and the line or field (docs/models/ptm.md, "Input").
LightSet read_light_set(const std::string& path);
/// The same for sidecar text already in memory: `path` names it in errors, chooses the format by
/// its extension and is the folder image names resolve against (what read_light_set() calls).
LightSet parse_light_set(const std::string& text, const std::string& path);
/// Reads the photos of a light set for fit_ptm(), scene-linear (read_image_linear() with
/// `options`, each at least min_size a side). They must be all colour or all grey (grey is
/// replicated into RGB) and of one size: a grey photo among colour ones is a wrong export whose
/// light would get a wrong chroma, so it is an Error naming both photos, as is a size mismatch.
std::vector<Image> read_light_set_photos(const LightSet& lights, const ImageReadOptions& options = {}, int min_size = 8);
/// Writes an .lp file; image paths are written relative to the file's folder where possible.
void write_light_set(const std::string& path, const LightSet& lights);
/// `count` directions spread evenly over the hemisphere above `min_elevation_degrees`
/// (a golden-angle spiral in equal-area rings), rotated by `azimuth_offset_degrees`.
std::vector<Vec3> spiral_light_directions(int count, double min_elevation_degrees, double azimuth_offset_degrees = 0);
/// Checks a light direction (finite, unit length within 1 %, z > 0) and returns it normalised;
/// `what` names it in the error.
Vec3 checked_light_direction(const Vec3& direction, const std::string& what);

// ---- Fitting ----------------------------------------------------------------------------------------

struct PtmFit {
    PtmMaps maps;
    double data_rms = 0;  ///< RMS of the photos' values (the scale of the errors below)
    double rmse = 0;      ///< fit residual over all photos, texels and channels (scene-linear)
    /// Leave-one-light-out: each photo predicted by the PTM fitted to the other photos.
    double loo_rmse = 0;
    std::vector<double> loo_rmse_per_light;
};
/// Least-squares PTM per texel with one shared pseudo-inverse (paper 004 §V). lrgb adds a
/// per-texel chroma, the least-squares factor given the fitted luminance. Needs ≥ 6 photos of
/// equal size whose directions determine a biquadratic (not all on a line or a conic); throws
/// Error otherwise.
PtmFit fit_ptm(const std::vector<Image>& photos, const std::vector<Vec3>& directions, PtmColour colour,
               const ProgressCallback& progress = {});

// ---- Relighting and derived maps -------------------------------------------------------------------

/// The maps lit by `light`: scene-linear RGB, negative radiance clamped to 0.
Image relight(const PtmMaps& maps, const Vec3& light);

enum class NormalEstimator {
    /// The best Lambertian fit ρ·(n·l) to each texel's PTM over the disk of light directions:
    /// linear in the coefficients, robust where the PTM is not concave.
    lambertian,
    /// The light direction maximising the PTM (Malzbender et al. 2001); falls back to
    /// `lambertian` where the biquadratic has no interior maximum.
    ptm_maximum,
};
const char* to_string(NormalEstimator estimator);
NormalEstimator normal_estimator_from_string(const std::string& name);  // throws Error

/// Per texel: a unit normal (x right, y up, z out of the surface) and a diffuse albedo, for
/// renderers without PTM support.
struct SurfaceMaps {
    Image normals;  ///< 3 channels, the normal's components in [−1, 1]
    Image albedo;   ///< scene-linear RGB
};
SurfaceMaps estimate_surface_maps(const PtmMaps& maps, NormalEstimator estimator);
/// Writes normals as a data image, 0.5 + 0.5·n per channel (the common tangent-space encoding,
/// OpenGL's y-up), never colour-converted: 8-bit for PNG/TIFF-8, float for EXR.
void write_normal_map(const std::string& path, const Image& normals);

// ---- Synthesis in ψ-space ------------------------------------------------------------------------

enum class SeamMode {
    min_cut,  ///< minimum-error boundary cut through each overlap (Efros & Freeman 2001)
    blend,    ///< linear cross-fade across each overlap (paper 004 §VI)
};
const char* to_string(SeamMode mode);
SeamMode seam_mode_from_string(const std::string& name);  // throws Error

struct PtmSynthesisOptions {
    int width = 512, height = 512;  ///< output size in texels (tileable: rounded up to whole steps)
    int block = 40;                 ///< block side in texels
    int overlap = 8;                ///< overlap between neighbouring blocks, 1 … block/2
    bool tileable = false;          ///< the output wraps without a seam (periodic boundary)
    SeamMode seam = SeamMode::min_cut;
    /// A block is accepted when its neighbourhood distance d ≤ (1 + relative_tolerance)·d_min
    /// + n·(absolute_tolerance·σ)², n the neighbourhood's texel count and σ² the exemplar's
    /// per-texel ψ variance; one accepted block is drawn at random (paper 004 eq. 9's δ).
    double relative_tolerance = 0.1;
    double absolute_tolerance = 0.05;
    /// true: exhaustive search (the reference for exactness and speed); false: projection-kernel
    /// rejection search, which returns the same candidates (paper 004 §VII).
    bool brute_force = false;
    std::uint32_t seed = 1;
};

struct PtmSynthesisReport {
    int width = 0, height = 0;         ///< the output's size
    int blocks = 0;
    long long positions = 0;           ///< candidate positions, summed over searches
    std::vector<long long> surviving;  ///< candidates left after each bound level, summed
    long long exact_distances = 0;     ///< full neighbourhood distances computed
    double search_seconds = 0, total_seconds = 0;
};
/// Block synthesis (image quilting) of the exemplar's coefficient maps in ψ-space: raster
/// order, causal overlaps, min-cut or blended seams, random choice among near-best blocks.
PtmMaps synthesize_ptm(const PtmMaps& exemplar, const PtmSynthesisOptions& options,
                       PtmSynthesisReport* report = nullptr, const ProgressCallback& progress = {});

// ---- Unbounded: tiling and blending of the coefficient fields -------------------------------------

struct PtmUnboundedOptions {
    /// The triangle grid's edge in maps widths (of the shorter side): the tiling model's default,
    /// 1/(2√3) (Deliot–Heitz), hexagonal tiles ≈ 0.58 maps widths across.
    double triangle_edge = 0.28867513459481287;
    /// Replace every coefficient channel by its periodic component (Moisan) first, so that tiles
    /// cut across the maps' edges show no seam. Linear and the same for every channel, so the
    /// functions stay coherent. Off for maps that already tile (`ptm synthesize --tileable`).
    bool make_periodic = true;
    std::uint32_t seed = 1;  ///< the tile offsets
};
/// Each coefficient channel replaced by its periodic component (keeps every channel's mean).
PtmMaps periodic_ptm_maps(const PtmMaps& maps);
/// An unbounded, random-access version of a ptm description (docs/models/ptm.md, "Unbounded"):
/// its maps tiled and blended with one set of tile offsets and variance-preserving weights for
/// all coefficient fields, mean-centred. Same light; seed and grid from `options`.
TextureDescription make_unbounded_ptm(const TextureDescription& ptm, const PtmUnboundedOptions& options);

// ---- Evaluation against a known truth (relief_shading.h) ----------------------------------------

/// A relit image against the truth under the same light, on Rec.709 luma.
struct RelitComparison {
    double mean_truth = 0, mean_test = 0, sigma_truth = 0, sigma_test = 0;
    double w1 = 0;          ///< 1-Wasserstein distance of the luma distributions / σ truth
    double log_psd_db = 0;  ///< log_psd_distance_db of the radial spectra
    SpectralOrientation orientation_truth, orientation_test;
    double pixel_rmse = -1;  ///< RMS difference over RGB when the images have one size, else −1
    double mean_error() const { return std::fabs(mean_test / mean_truth - 1); }
    double sigma_error() const { return std::fabs(sigma_test / sigma_truth - 1); }
    /// Difference of the spectra's dominant directions, in [0°, 90°].
    double orientation_error_degrees() const;
};
RelitComparison compare_relit(const Image& truth, const Image& test);

/// Angles between estimated and true unit normals (3-channel images of one size), degrees.
struct NormalErrors {
    double mean = 0, median = 0, percentile_90 = 0;
};
NormalErrors compare_normals(const Image& estimated, const Image& truth);
/// Mean of |estimate − truth| / truth over all texels and channels (albedo maps of one size).
double mean_relative_error(const Image& estimate, const Image& truth);

// ---- The .stex ptm model ----------------------------------------------------------------------------

/// A description of the ptm model holding `maps`, evaluated for `light`; one texture unit is
/// the maps' width.
TextureDescription make_ptm_description(PtmMaps maps, const Vec3& light);

}  // namespace stochtex
