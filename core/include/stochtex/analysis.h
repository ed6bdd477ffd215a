// stochtex — analysis by example: a photo in, a TextureDescription out.
#pragma once

#include <stochtex/image.h>
#include <stochtex/progress.h>
#include <stochtex/texture_description.h>

#include <cstdint>
#include <string>

namespace stochtex {

enum class HistogramMode { off, on, automatic };
const char* to_string(HistogramMode mode);
HistogramMode histogram_mode_from_string(const std::string& name);  // throws Error

/// How the photo's power spectrum is estimated (docs/models/wavelet.md, "PSD estimator").
enum class PsdEstimator {
    periodic,         ///< raw periodogram of the photo as if it tiled (paper 000)
    periodic_smooth,  ///< Moisan's periodic + smooth decomposition: no "+"-shaped edge leak
};
const char* to_string(PsdEstimator estimator);
PsdEstimator psd_estimator_from_string(const std::string& name);  // throws Error

struct AnalysisOptions {
    std::string model = "wavelet";
    ColourMode colour_mode = ColourMode::pca;
    HistogramMode histogram = HistogramMode::automatic;
    int histogram_knots = 10;       ///< knots of each histogram map (≥ 4)
    PsdEstimator psd = PsdEstimator::periodic;
    int max_bands = 0;              ///< keep at most this many (finest) bands; 0 = all the photo supports
                                    ///< (gabor: octaves, the same count)
    // gabor model (docs/models/gabor.md)
    GaborKind gabor_kind = GaborKind::isotropic;
    double gabor_impulses = 16;     ///< impulses per kernel, 1 … 256
    double gabor_bandwidth = 0;     ///< a/F of the octaves; 0: chosen by the fit
    // tiling model (docs/models/tiling.md)
    int tiling_exemplar_size = 256; ///< the exemplar: a centred crop, sides the largest powers of two ≤ this
    int tiling_exemplar_bits = 8;   ///< 8 or 16 bits per stored sample
    // lrp model (docs/models/lrp.md)
    int lrp_cosines = 50;           ///< J: cosines per window over all strata and the structure, 1 … 256
    int lrp_strata = 8;             ///< L: random-phase strata, 1 … 16
    double lrp_structure = 0.1;     ///< r: energy share of the fixed-phase structure, [0, 1); 0: noise only
    bool lrp_placement = true;      ///< random placement of the structure
    double lrp_turbulence = -1;     ///< turbulence σ in exemplar pixels; < 0: automatic
    std::uint32_t seed = 1;
    double unit_size_m = 1.0;
    std::string source_name;        ///< recorded in the provenance
    std::string input_colour_space; ///< recorded in the provenance
};

/// Analyses a scene-linear RGB photo (read_image_linear). Throws Error for unusable input
/// (too small, non-finite values, unknown model).
TextureDescription analyze(const Image& photo, const AnalysisOptions& options,
                           const ProgressCallback& progress = {});

}  // namespace stochtex
