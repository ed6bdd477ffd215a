#include "compare_figure.h"

#include "plot.h"

#include <stochtex/render.h>
#include <stochtex/texture.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace stex_cli {

using namespace stochtex;

Image render_at_photo_scale(const TextureDescription& description, int width, int height, int threads,
                            const ProgressCallback& progress)
{
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.units_per_pixel = 1.0 / description.pixels_per_unit;
    settings.threads = threads;
    return render(*make_texture(description), settings, progress);
}

namespace {

/// Luma histogram (counts normalised to a density) on shared bin edges, for the plot.
std::vector<double> luma_histogram(const Image& image, double lo, double hi, int bins)
{
    std::vector<double> counts(bins, 0.0);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const double luma = 0.2126 * image.pixels[3 * i] + 0.7152 * image.pixels[3 * i + 1] + 0.0722 * image.pixels[3 * i + 2];
        const int bin = int((luma - lo) / (hi - lo) * bins);
        if (bin >= 0 && bin < bins) counts[bin] += 1.0 / image.pixel_count();
    }
    return counts;
}

}  // namespace

CompareFigure compare_figure(const Image& photo_image, const Image& synthesis, const ComparisonReport& report)
{
    // Figure: photo | synthesis on top (at most 512 px each), PSD and histogram plots below.
    const int tile = std::min(512, std::min(photo_image.width, photo_image.height));
    auto crop = [&](const Image& source) {
        Image out(tile, tile, 3);
        for (int y = 0; y < tile; ++y)
            for (int x = 0; x < tile; ++x)
                for (int c = 0; c < 3; ++c) out.at(x, y, c) = source.at(x, y, c);
        return out;
    };
    const std::array<float, 3> photo_colour{0.05f, 0.05f, 0.6f}, synthesis_colour{0.7f, 0.08f, 0.02f};
    const Image psd_panel = plot_panel(tile, tile / 2,
                                       {{report.psd_reference_luma.frequency, report.psd_reference_luma.power, photo_colour},
                                        {report.psd_test_luma.frequency, report.psd_test_luma.power, synthesis_colour}},
                                       true, true);
    const double lo = 0, hi = std::max(1e-6, 2.0 * (0.2126 * report.mean_reference[0] + 0.7152 * report.mean_reference[1] +
                                                    0.0722 * report.mean_reference[2]));
    constexpr int bins = 64;
    std::vector<double> centres(bins);
    for (int b = 0; b < bins; ++b) centres[b] = lo + (b + 0.5) * (hi - lo) / bins;
    const Image histogram_panel = plot_panel(
        tile, tile / 2,
        {{centres, luma_histogram(photo_image, lo, hi, bins), photo_colour},
         {centres, luma_histogram(synthesis, lo, hi, bins), synthesis_colour}},
        false, false);
    // The two luma spectra in dB on one colour scale: from the strongest cell of either down
    // 60 dB (polar_log_psd_distance_db's floor), so equal colours mean equal power.
    const auto to_db = [](const CentredSpectrum& spectrum) {
        std::vector<double> db(spectrum.power.size());
        for (std::size_t i = 0; i < db.size(); ++i)
            db[i] = spectrum.power[i] > 0 ? 10.0 * std::log10(spectrum.power[i]) : -1e300;
        return db;
    };
    const std::vector<double> photo_db = to_db(report.spectrum_reference_luma),
                              synthesis_db = to_db(report.spectrum_test_luma);
    const double db_hi = std::max(*std::max_element(photo_db.begin(), photo_db.end()),
                                  *std::max_element(synthesis_db.begin(), synthesis_db.end()));
    const double db_lo = db_hi - 60.0;
    const int grid = report.spectrum_reference_luma.size;
    Image figure(2 * tile, tile + tile / 2 + tile, 3);
    paste(figure, crop(photo_image), 0, 0);
    paste(figure, crop(synthesis), tile, 0);
    paste(figure, psd_panel, 0, tile);
    paste(figure, histogram_panel, tile, tile);
    paste(figure, heat_map_panel(photo_db, grid, tile, db_lo, db_hi), 0, tile + tile / 2);
    paste(figure, heat_map_panel(synthesis_db, grid, tile, db_lo, db_hi), tile, tile + tile / 2);
    return {figure, db_lo, db_hi};
}

}  // namespace stex_cli
