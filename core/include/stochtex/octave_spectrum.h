// stochtex — spectra as "variance per octave", and re-expressing a model's channel spectrum with
// another noise (a renderer's built-in noise: POV-Ray's, later OSL's or Blender's).
//
// Why variance per octave. A radially averaged PSD S(f) (metrics.h, a density per cycle²) of a
// noise stretched by a factor a becomes S(f·a)·a²: shape and amplitude both change. The variance
// per octave, g(ℓ) = dσ²/dlog2 f = 2π f² ln2 · S(f) at f = 2^ℓ, only shifts along ℓ, and
// Σ g·(octaves per bin) is the variance. So one measured curve describes a noise at every scale,
// and a sum of independent noises at octave frequencies is a sum of shifted copies of it.
#pragma once

#include <stochtex/metrics.h>

#include <vector>

namespace stochtex {

/// g(ℓ) sampled at increasing log2 frequencies ℓ (cycles per unit: lattice unit, texture unit
/// or pixel, as the producer says). Between samples g is linear in ℓ; outside it is zero.
struct OctaveSpectrum {
    std::vector<double> log2_frequency;
    std::vector<double> variance_per_octave;

    /// g at ℓ (linear interpolation, 0 outside the samples).
    double at(double log2_f) const;
    /// ∫ g dℓ (trapezoid): the variance the samples account for.
    double variance() const;
};

/// Converts a radially averaged PSD measured on a raster with `samples_per_unit` pixels per unit
/// to variance per octave in cycles per unit.
OctaveSpectrum octave_spectrum(const RadialPsd& psd, double samples_per_unit);

/// Copies of one basis noise at octave-spaced frequencies whose summed spectrum approximates a
/// target: octave k is the basis scaled to lattice frequency 2^log2_frequency[k] (cycles of the
/// basis's unit per target unit) with weight[k] (a standard-deviation factor, ≥ 0).
struct OctaveFit {
    std::vector<double> log2_frequency;
    std::vector<double> weight;
    /// RMS of 10·log10(fit/target) over the samples where the target holds ≥ 1 % of its peak.
    double rms_error_db = 0;
};

/// Fits Σ_k weight_k² · basis(ℓ − log2_frequency_k) to target(ℓ) by non-negative least squares
/// in relative error (each sample weighted by 1/(target + 1 % of its peak), so the octaves where
/// the texture has little power count as much as the strong ones, without dividing by ~0).
/// The octaves are `octave_count` frequencies one octave apart, the finest at
/// finest_log2_frequency + shift, where the shift (same for all octaves) is searched in
/// [shift_min, shift_max] in steps of 1/16 octave (equal bounds fix it: channels that must share
/// their noises). Then all weights are scaled together so that
/// Σ weight_k² · basis_variance equals target_variance exactly: the variance, which a histogram
/// map depends on, is matched whatever the spectral fit's residual. `basis_variance` is the
/// basis noise's measured pointwise variance. Throws Error if the target has no power.
OctaveFit fit_octaves(const OctaveSpectrum& target, double target_variance, const OctaveSpectrum& basis,
                      double basis_variance, double finest_log2_frequency, int octave_count,
                      double shift_min = -1.5, double shift_max = 1.5);

}  // namespace stochtex
