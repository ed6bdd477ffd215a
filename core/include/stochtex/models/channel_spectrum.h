// stochtex — a model's channel spectrum as variance per octave (octave_spectrum.h): what a
// front-end re-expresses with a renderer's own noise (POV-Ray's procedural include). Only the
// wavelet model has one (its band weights are a spectrum), so this is the wavelet's API; the
// variance-per-octave maths it returns is generic and lives in spectra/.
#pragma once

#include <stochtex/octave_spectrum.h>
#include <stochtex/texture_description.h>

namespace stochtex {

/// The expected spectrum of decorrelated channel `channel` before its histogram map (the
/// Gaussian noise m_c of the model), in cycles per texture unit, for the 2D texture (the
/// photo's statistics). wavelet: Σ_j w_cj² · (the band's own spectrum, measured once from a
/// point-sampled render of one band) shifted to band j's lattice frequency ppu·2^-j. Sampled
/// (8 per octave) only where the analysis measured the photo: from the coarsest band's lower
/// edge, 2^-(J+1) cycles per exemplar pixel, to 1 cycle per exemplar pixel.
/// Throws Error for a model that has no such spectrum.
OctaveSpectrum channel_spectrum(const TextureDescription& description, int channel);

}  // namespace stochtex
