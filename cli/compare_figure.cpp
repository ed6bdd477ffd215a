#include "compare_figure.h"

#include "bitmap_font.h"
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

/// The `stex compare` figure, two 512-pixel columns (photo left, synthesis right): the images
/// (the top-left crop of at most 512², small ones enlarged), their radial luma power spectra and
/// luma histograms, their 2D luma power spectra on one dB scale, and the structure distance's
/// parts. Every panel titled, every axis labelled with its unit, every curve in a legend.
CompareFigure compare_figure(const Image& photo_image, const Image& synthesis, const ComparisonReport& report,
                             const std::string& photo_name, const std::string& synthesis_name)
{
    constexpr int column = 512, caption = 28, chart_height = 320, bars_height = 260;
    const std::array<float, 3> ink{0, 0, 0}, photo_colour{0.02f, 0.1f, 0.75f}, synthesis_colour{0.8f, 0.1f, 0.02f};
    const int tile = std::min({column, photo_image.width, photo_image.height});
    const int factor = std::max(1, column / tile);
    auto crop = [&](const Image& source) {
        Image out(tile, tile, 3);
        for (int y = 0; y < tile; ++y)
            for (int x = 0; x < tile; ++x)
                for (int c = 0; c < 3; ++c) out.at(x, y, c) = source.at(x, y, c);
        return enlarged(out, factor);
    };
    // Radial spectra in dB; histograms as densities on shared bins from 0 to twice the photo's mean luma.
    const auto db_of = [](const std::vector<double>& power) {
        std::vector<double> db(power.size());
        for (std::size_t i = 0; i < db.size(); ++i) db[i] = 10.0 * std::log10(std::max(power[i], 1e-30));
        return db;
    };
    const Image psd_panel = chart_panel(
        column, chart_height, "radial power spectrum, luma", {"frequency (cycles/px)", true}, {"power (dB)", false},
        {{report.psd_reference_luma.frequency, db_of(report.psd_reference_luma.power), photo_colour, "photo"},
         {report.psd_test_luma.frequency, db_of(report.psd_test_luma.power), synthesis_colour, "synthesis"}});
    const double lo = 0, hi = std::max(1e-6, 2.0 * (0.2126 * report.mean_reference[0] + 0.7152 * report.mean_reference[1] +
                                                    0.0722 * report.mean_reference[2]));
    constexpr int bins = 64;
    std::vector<double> centres(bins);
    for (int b = 0; b < bins; ++b) centres[b] = lo + (b + 0.5) * (hi - lo) / bins;
    std::vector<double> photo_density = luma_histogram(photo_image, lo, hi, bins),
                        synthesis_density = luma_histogram(synthesis, lo, hi, bins);
    for (double& d : photo_density) d *= bins / (hi - lo);  // fraction per bin → density per unit value
    for (double& d : synthesis_density) d *= bins / (hi - lo);
    const Image histogram_panel = chart_panel(column, chart_height, "luma histogram", {"luma value (linear)", false},
                                              {"density", false},
                                              {{centres, photo_density, photo_colour, "photo"},
                                               {centres, synthesis_density, synthesis_colour, "synthesis"}});
    // The two 2D spectra on one colour scale: from the strongest cell of either down 60 dB
    // (polar_log_psd_distance_db's floor), so equal colours mean equal power.
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
    const int grid = report.spectrum_reference_luma.size, map = 360;
    const StructureDistance& structure = report.structure;
    std::vector<Bar> bars{{"total", structure.total, {0.15f, 0.15f, 0.15f}}};
    for (int part = 0; part < StructureDistance::kParts; ++part)
        bars.push_back({StructureDistance::part_name(part), structure.parts[part], synthesis_colour});

    const int images_y = caption, charts_y = images_y + column + 8, maps_y = charts_y + chart_height + 8,
              bars_y = maps_y + caption + map + 2 * caption;
    Image figure(2 * column, bars_y + bars_height, 3);
    std::fill(figure.pixels.begin(), figure.pixels.end(), 1.0f);
    const auto label = [&](int x, int y, const std::string& text) { draw_text(figure, x, y, text, ink, 2); };
    label(4, 6, "photo: " + photo_name);
    label(column + 4, 6, "synthesis: " + synthesis_name);
    paste(figure, crop(photo_image), 0, images_y);
    paste(figure, crop(synthesis), column + 4, images_y);  // a white gap between the two
    paste(figure, psd_panel, 0, charts_y);
    paste(figure, histogram_panel, column, charts_y);
    const int map_x = 52;  // room for the fy labels on the left, the dB scale on the right
    label(map_x, maps_y + 6, "photo: 2D luma power spectrum");
    label(column + map_x, maps_y + 6, "synthesis: 2D luma power spectrum");
    for (int side = 0; side < 2; ++side) {
        const int x0 = side * column + map_x, y0 = maps_y + caption;
        paste(figure, heat_map_panel(side == 0 ? photo_db : synthesis_db, grid, map, db_lo, db_hi), x0, y0);
        label(x0 - 42, y0, "+.5");
        label(x0 - 42, y0 + map - 14, "-.5");
        label(x0 - 30, y0 + map / 2 - 7, "fy");
        label(x0 - 12, y0 + map + 4, "-.5");
        label(x0 + map - 24, y0 + map + 4, "+.5");
        label(x0 + map / 2 - 100, y0 + map + 4, "fx (cycles/px)");
        paste(figure, heat_map_scale(80, map, db_lo, db_hi), x0 + map + 8, y0);
    }
    paste(figure,
          bar_panel(2 * column, bars_height,
                    "structure distance to the photo (Portilla-Simoncelli statistics)", bars, 1.0,
                    "1 = the photo's random-phase noise"),
          0, bars_y);
    return {figure, db_lo, db_hi};
}

}  // namespace stex_cli
