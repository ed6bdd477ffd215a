// stochtex — analysis by example: a photo in, a TextureDescription out.
#pragma once

#include <stochtex/image.h>
#include <stochtex/progress.h>
#include <stochtex/texture_description.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace stochtex {

enum class HistogramMode { off, on, automatic };
const char* to_string(HistogramMode mode);
HistogramMode histogram_mode_from_string(const std::string& name);  // throws Error

/// `AnalysisOptions::model` that lets the analysis choose: every registered model that can
/// analyse photos is fitted, its render (at the photo's pixel scale, at most 384² pixels) is
/// compared with the photo (stochtex/metrics.h: fidelity_penalty), and the lowest penalty
/// wins; candidates within model_choice_tolerance of it count as equally faithful and the one
/// with the smallest file is kept (a photo wavelet serves well keeps its 2 kB texture). Every
/// candidate's scores go into the provenance (Provenance::model_choice).
inline constexpr const char* automatic_model = "auto";
inline constexpr double model_choice_tolerance = 0.10;

struct AnalysisOptions {
    /// A registered model that can analyse photos (stochtex/model.h), or automatic_model. The
    /// library's default stays the one cheap model; `stex analyze` defaults to automatic_model.
    std::string model = "wavelet";
    ColourMode colour_mode = ColourMode::pca;
    /// automatic_model only: fit each model with every colour mode it declares worth trying
    /// (ModelInfo::automatic_colour_modes) instead of colour_mode alone — for when the user
    /// did not choose one (`stex analyze` without --colour).
    bool try_colour_modes = false;
    /// Joint colour (pca mode, models with Gaussian channels): the chroma channels conditioned on
    /// brightness (TextureDescription::chroma_given_brightness), which keeps colours the photo
    /// never had from appearing. Off by default: POV-Ray's procedural mode cannot express it,
    /// and it costs some models spectrum fidelity on some photos (docs/models/README.md).
    bool joint_colour = false;
    /// automatic_model only: fit each model that can carry joint colour both with and without it
    /// (pca colour), so that the scores decide — for when the user did not choose
    /// (`stex analyze --joint-colour auto`, its default). Overrides joint_colour for those models.
    bool try_joint_colour = false;
    /// automatic_model only: score the candidates with the structure distance as a seventh term
    /// of the fidelity penalty (FidelityTargets::structure_distance = 0.25; docs/metrics.md,
    /// "Structure"), and with it the refits and variants a model offers (Model::automatic_refits,
    /// automatic_variants: tiling's 512² exemplar, blend contrast γ = 4 and 8). Off by default: on
    /// the shared photos the choice it makes misses the acceptance targets (docs/metrics.md, "In
    /// the automatic choice"), and it costs ≈ 3× the time.
    bool structure_in_choice = false;
    HistogramMode histogram = HistogramMode::automatic;
    int histogram_knots = 10;       ///< knots of each histogram map (≥ 4)
    int max_bands = 0;              ///< keep at most this many (finest) bands; 0 = all the photo supports
                                    ///< (gabor: octaves, the same count)
    /// The model's own options as name → text, as a command line gives them ("impulses" → "8");
    /// each model declares its options (ModelInfo::analysis_options: range, default, doc), and
    /// an option it does not declare is an error.
    std::vector<std::pair<std::string, std::string>> model_options;
    std::uint32_t seed = 1;
    double unit_size_m = 1.0;
    std::string source_name;        ///< recorded in the provenance
    std::string input_colour_space; ///< recorded in the provenance
};

/// The largest |pixel value| analyze() accepts (scene-linear): the photo's spectra are float,
/// and (2^26 pixels × 1e10)² is still within float range.
constexpr double max_analysis_value = 1e10;

/// Analyses a scene-linear RGB photo (read_image_linear). Throws Error for unusable input
/// (too small, non-finite values or values beyond ±max_analysis_value, unknown model).
TextureDescription analyze(const Image& photo, const AnalysisOptions& options,
                           const ProgressCallback& progress = {});

/// Which row of description.provenance.model_choice the description is (the same model, colour
/// mode and joint colour, and the variant whose options its provenance carries, else the row
/// without a variant); -1 when none is (a model was named, the table is empty).
int chosen_model_score(const TextureDescription& description);

/// The score table of a description whose model analysis chose (empty when a model was named):
/// one row per candidate, the chosen one marked, and the rule.
std::string format_model_choice(const TextureDescription& description);

}  // namespace stochtex
