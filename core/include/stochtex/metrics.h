// stochtex — texture statistics and distances: the one place where "how close is this
// synthesis to that photo" is defined. Used by tests, `stex compare` and the benchmarks.
// Declared here: what front-ends and the models' fits call, and the types of the report.
// Defined below the models where the fits call them (radial_psd and log_psd_distance_db in
// core/src/spectra/, W1 in core/src/numerics/), so no model calls up into analysis/. The
// measures that only the core's own code and the tests call (the polar spectrum, the spectral
// orientation, the 2D spectral distances, gradient and colour statistics) are internal,
// declared beside their code in core/src/spectra/ and core/src/analysis/.
#pragma once

#include <stochtex/image.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace stochtex {

/// Radially averaged power spectrum of one channel (mean removed, Hann window with power
/// compensation, so non-periodic photos do not leak a "+" into high frequencies).
/// Bins are log-spaced (bins_per_octave per octave) from 1/min(w,h) to 0.5 cycles per pixel;
/// power is the mean |F|² per bin, normalised so that Σ over all bins of the periodogram equals
/// the channel variance (Parseval). Empty bins are dropped.
struct RadialPsd {
    std::vector<double> frequency;  ///< bin centre, cycles per pixel
    std::vector<double> power;      ///< mean periodogram power in the bin
    /// FFT samples averaged in each bin (conjugate pairs counted twice, as in PolarPsd). Empty
    /// for a spectrum that is exact rather than estimated (an analytic model's): every bin counts.
    std::vector<double> samples;
};
RadialPsd radial_psd(const std::vector<float>& plane, int width, int height, int bins_per_octave = 4);

/// The fewest FFT samples a radius bin of an estimated spectrum must hold to count in a
/// distance (≥ 64 independent ones: the periodogram's own noise ≲ 0.5 dB per bin). Below it, two
/// realisations of one texture differ by dBs (3.3 dB at 256² with every bin counted), so the
/// distance would measure the sample, not the texture. The 2D distance uses the same floor.
constexpr int resolved_bin_samples = 128;

/// RMS over the frequency bins both spectra have (matched by frequency) and both resolve (hold
/// at least min_samples samples, or are exact) of 10·log10(Pa/Pb), in dB.
double log_psd_distance_db(const RadialPsd& a, const RadialPsd& b, int min_samples = resolved_bin_samples);

/// The orientation of one channel's power spectrum (spectra/spectral_orientation.h; mean
/// removed; Moisan's periodic component, so image edges add no "+"): the power-weighted mean of
/// e^{2iθ} over all frequencies, θ a frequency's angle from the x axis towards y up. strength in [0, 1] (0: no preferred
/// direction); angle in (−90°, 90°], the dominant frequency direction. A rough surface lit from
/// azimuth φ gains power along φ: relit textures must match their truth in this too.
struct SpectralOrientation {
    double strength = 0, angle_degrees = 0;
};

/// One channel's periodogram density (radial_psd's estimator) on a centred size×size grid for
/// display: cell (i, j) holds the mean over the FFT samples with frequency
/// (fx, fy), i = ⌊(fx + ½)·size⌋, j = ⌊(½ − fy)·size⌋ (fy towards y up, so the picture turns
/// as the image does), clamped to the grid; 0 where no sample falls (size > width or height).
/// The DC sample is left out.
struct CentredSpectrum {
    int size = 0;
    std::vector<double> power;  ///< size·size, rows top to bottom
};

/// 1-Wasserstein distance between the empirical distributions of two samples (any sizes).
double wasserstein1(const std::vector<float>& a, const std::vector<float>& b);
/// The same of two samples already sorted ascending (to compare many samples with one reference).
double wasserstein1_of_sorted(const std::vector<double>& sorted_a, const std::vector<double>& sorted_b);

/// How far a synthesis's structure is from its photo's: Portilla–Simoncelli statistics of a
/// complex steerable pyramid (4 scales × 4 orientations) of luma, plus the colour channels'
/// marginals, in five groups (docs/metrics.md, "Structure"). Each part is the RMS difference of
/// its group's statistics divided by the same for the photo against its own random-phase
/// version (same spectrum, no structure): 0 is the photo's structure, 1 is as structureless as
/// the photo's noise. total is the mean of the parts. NaN where the images are too small
/// (either side under 64 pixels) or flat.
struct StructureDistance {
    static constexpr int kParts = 5;
    /// Short names of the parts, in order: "marginals" (skewness and kurtosis of luma, of its
    /// low-pass levels and of R, G, B; the bands' amplitude sparsity), "auto-correlation" (of the
    /// low-pass levels and of the band amplitudes, 7×7 lags), "cross-orientation" (amplitude
    /// correlations between the orientations of a scale), "cross-scale" (amplitude correlations
    /// between a band and the next coarser scale's), "phase" (a band against the next coarser
    /// scale's phase-doubled band: edges and lines align across scales, noise does not).
    static const char* part_name(int part);
    double total = 0;
    std::array<double, kParts> parts{};
};

/// Everything `stex compare` prints, per RGB channel where it applies. A comment naming a
/// function not declared here names an internal one in core/src/analysis/ (spectral_distances.h,
/// gradient_statistics.h, colour_statistics.h) or core/src/spectra/ (power_spectrum.h);
/// docs/metrics.md describes each measure.
struct ComparisonReport {
    std::array<double, 3> mean_reference{}, mean_test{};
    std::array<double, 3> stddev_reference{}, stddev_test{};
    double covariance_error = 0;            ///< relative Frobenius
    std::array<double, 3> w1{};             ///< per channel
    std::array<double, 3> w1_relative{};    ///< w1 / stddev_reference
    std::array<double, 3> log_psd_db{};     ///< per channel
    RadialPsd psd_reference_luma, psd_test_luma;  ///< for plots
    // What the radial and per-value metrics cannot see, on luma (0.2126 R + 0.7152 G + 0.0722 B):
    double polar_log_psd_db = 0;             ///< polar_log_psd_distance_db: the 2D spectrum, orientation included
    double polar_log_psd_angular_db = 0;     ///< polar_log_psd_angular_db: its orientation part
    double gradient_orientation_degrees = 0; ///< circular W1 of the |∇|-weighted orientation histograms
    double gradient_magnitude_w1 = 0;        ///< W1 of |∇|/σ, relative to the reference's mean |∇|/σ
    double false_colour_rate = 0;            ///< false_colour_rate(reference, test), a fraction
    StructureDistance structure;             ///< Portilla–Simoncelli statistics, luma and colour marginals
    /// centred_spectrum of luma for plots, side ≤ 256 (min of it and the images' sides).
    CentredSpectrum spectrum_reference_luma, spectrum_test_luma;
};
ComparisonReport compare_images(const Image& reference, const Image& test);

/// The reference's side of compare_images made once, to compare many tests with one photo (the
/// model choice scores every candidate against the same photo): its sorted samples, spectra,
/// gradients and chroma region. compare_images(ComparisonReference(a), b) is compare_images(a, b),
/// bit for bit. Cheap to copy; immutable, so it may be shared between threads.
class ComparisonReference {
public:
    /// Throws Error unless `reference` is a non-empty RGB image. Without `with_structure` the
    /// reports' structure distance is NaN: the model choice, whose penalty does not use it, skips
    /// its cost (two steerable pyramids of the photo, one per candidate: ~60 % of the choice's).
    explicit ComparisonReference(const Image& reference, bool with_structure = true);
    int width() const;
    int height() const;

private:
    struct Prepared;
    friend ComparisonReport compare_images(const ComparisonReference& reference, const Image& test);
    std::shared_ptr<const Prepared> prepared_;
};
ComparisonReport compare_images(const ComparisonReference& reference, const Image& test);

/// What a synthesis is held to against its photo (docs/metrics.md, "Fidelity"): at or under
/// each target a person comparing the two side by side sees no difference of that kind.
struct FidelityTargets {
    double radial_log_psd_db = 1.5;            ///< mean over RGB of log_psd_db
    double polar_log_psd_db = 1.5;             ///< polar_log_psd_db (luma)
    double w1_sigma = 0.10;                    ///< the worst RGB channel's w1_relative
    double false_colour_rate = 0.01;           ///< a fraction
    double gradient_orientation_degrees = 5;   ///< gradient_orientation_degrees
    double gradient_magnitude_w1 = 0.10;       ///< gradient_magnitude_w1
    /// structure.total, the seventh term: 0 (the default) leaves it out. 0.25 where it is used
    /// (`stex analyze --choice-structure`): between two crops of one photo (≤ 0.19 at 256²,
    /// ≈ 0.04 at 512²) and a Σw² = 1 blend of two crops, tiling's ghosts (0.31–0.37).
    double structure_distance = 0;
};

/// One number for "how far is this synthesis from its photo": the mean over the six metrics of
/// FidelityTargets (seven with a structure_distance target) of metric / target (1: every metric on its target; lower is closer). A mean,
/// not a maximum, so a model that fails one target by a little and meets the rest well beats one
/// that fails several; each term is capped at 10 so one unmeasurable or extreme metric cannot
/// hide the others. A metric that could not be measured (NaN: images too small) counts 10.
double fidelity_penalty(const ComparisonReport& report, const FidelityTargets& targets = {});
std::string format_report(const ComparisonReport& report);

}  // namespace stochtex
