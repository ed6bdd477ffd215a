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
