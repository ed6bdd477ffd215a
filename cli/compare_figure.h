// The figure `stex compare -o` writes (and `stex batch --compare`): photo beside synthesis, their
// radial PSDs and luma histograms, their 2D luma power spectra and the structure distance.
#pragma once

#include <stochtex/image.h>
#include <stochtex/metrics.h>
#include <stochtex/progress.h>
#include <stochtex/texture_description.h>

#include <string>

namespace stex_cli {

/// The texture rendered at the photo's pixel scale from its origin, `width`×`height` pixels:
/// what compare measures against the photo. `threads` as RenderSettings::threads.
stochtex::Image render_at_photo_scale(const stochtex::TextureDescription& description, int width, int height,
                                      int threads = 0, const stochtex::ProgressCallback& progress = {});

struct CompareFigure {
    stochtex::Image image;
    double db_lo = 0, db_hi = 0;  ///< the spectra's colour scale
};

/// The figure of `report` = compare_images(photo, synthesis), two 512-pixel columns (photo left,
/// synthesis right, captioned with the given names): the images, their radial luma power spectra
/// and luma histograms, their 2D luma power spectra on one dB scale, and the structure distance's
/// parts. Every panel titled, every axis labelled with its unit, every curve in a legend.
CompareFigure compare_figure(const stochtex::Image& photo, const stochtex::Image& synthesis,
                             const stochtex::ComparisonReport& report, const std::string& photo_name,
                             const std::string& synthesis_name);

}  // namespace stex_cli
