// What POV-Ray's noise is, as measured — never assumed. Procedural includes build every octave
// from f_noise_generator(x, y, z, 2) (POV-Ray's default "range-corrected" Perlin noise; named
// explicitly so a scene's global noise_generator cannot change it). Its mean, variance and
// spectrum come from POV-Ray's own renders, measured by the core's metrics
// (pov/calibration/calibrate.sh writes pov_noise_calibration.cpp; docs/pov.md).
#pragma once

#include <stochtex/octave_spectrum.h>

#include <string>

namespace stochtex::pov {

struct PovNoiseCalibration {
    int generator;            ///< the noise_generator argument the includes pass
    double mean;              ///< of the raw noise value (nominally 0.5)
    double variance;          ///< pointwise, on plane slices
    double minimum, maximum;  ///< observed range (inside [0, 1]: no clipping by POV-Ray)
    int renders;              ///< rotated slices averaged
    double samples_per_cell;  ///< pixels per lattice cell in the renders
    std::string povray_version;
    OctaveSpectrum spectrum;  ///< variance per octave, cycles per lattice cell
};

const PovNoiseCalibration& pov_noise_calibration();

}  // namespace stochtex::pov
