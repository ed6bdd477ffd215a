#include <stochtex/models/channel_spectrum.h>

#include <stochtex/error.h>
#include <stochtex/render.h>
#include <stochtex/models/wavelet_parameters.h>

#include <cmath>
#include <mutex>
#include <string>

namespace stochtex {

namespace {

/// The spectrum of one 2D wavelet band at 1 lattice cell per unit, measured once from the core's
/// own point-sampled render (4 samples per cell over 256² cells): what the texture really
/// synthesises, with the B-spline's tails and the tile's finite randomness, not an idealised
/// octave.
const OctaveSpectrum& wavelet_band_spectrum()
{
    static std::once_flag once;
    static OctaveSpectrum spectrum;
    std::call_once(once, [] {
        TextureDescription band;
        band.model = "wavelet";
        band.pixels_per_unit = 1;  // band 0: one lattice cell per texture unit
        band.parameters = WaveletParameters{{std::vector<double>{1.0}, std::vector<double>{0.0}, std::vector<double>{0.0}}};
        constexpr int size = 1024, samples_per_cell = 4;
        RenderSettings settings;
        settings.width = settings.height = size;
        settings.units_per_pixel = 1.0 / samples_per_cell;
        settings.filter = false;
        const Image image = render(*make_texture(band), settings);
        spectrum = octave_spectrum(radial_psd(image.channel(0), size, size, 8), samples_per_cell);
    });
    return spectrum;
}

}  // namespace

OctaveSpectrum channel_spectrum(const TextureDescription& description, int channel)
{
    if (channel < 0 || channel > 2)
        throw Error("channel_spectrum: channel " + std::to_string(channel) + " is not 0, 1 or 2");
    if (description.model != "wavelet" || !description.parameters.holds<WaveletParameters>())
        throw Error("channel_spectrum: model '" + description.model + "' has no band spectrum");
    const OctaveSpectrum& band = wavelet_band_spectrum();
    const std::vector<double>& weights = description.parameters.get<WaveletParameters>().band_weights[channel];
    const int bands = int(weights.size());
    // Band j: ppu·2^-j lattice cells per texture unit, i.e. a shift of log2(ppu) − j octaves.
    const double finest = std::log2(description.pixels_per_unit);
    // The range the analysis measured: from the coarsest band's lower edge (2^-(J+1) cycles per
    // exemplar pixel; the photo's lower frequencies were folded into that band, so the bands' own
    // tails below it are artefacts of the basis, not data) up to one cycle per exemplar pixel
    // (above Nyquist the B-spline's tails only alias back when sampled).
    OctaveSpectrum target;
    const double step = 1.0 / 8;
    const double lo = finest - (bands + 1), hi = finest;
    for (double l = lo; l <= hi + 1e-9; l += step) {
        double g = 0;
        for (int j = 0; j < bands; ++j) g += weights[std::size_t(j)] * weights[std::size_t(j)] * band.at(l - finest + j);
        target.log2_frequency.push_back(l);
        target.variance_per_octave.push_back(g);
    }
    return target;
}

}  // namespace stochtex
