// stochtex — Random-phase Gabor noise octaves: the parameters block of a gabor .stex (models/gabor/).
// The declaration of these fields (keys, ranges, defaults, docs) is the model's parameter schema,
// in core/src/models/gabor/; docs/stex-format.md lists it.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace stochtex {

/// Which frequencies the kernels of a Gabor noise draw (paper 001, Fig. 4). F is an octave's
/// frequency; `direction` is GaborParameters::direction.
enum class GaborKind {
    isotropic,    ///< ω uniform on the sphere |ω| = F: every slice looks alike (granite, sand)
    anisotropic,  ///< ω = F·direction for every kernel: oriented (wood grain, brushed metal)
    hybrid,       ///< ω uniform on the circle |ω| = F in the plane normal to `direction`
    /// Per octave k, a fraction oriented_fractions[k] of the kernels has ω = F·(cos θ_k, sin θ_k, 0),
    /// θ_k = orientations[k], and the rest draw ω as isotropic ones: oriented coarse ripples over
    /// isotropic fine grain (sand dunes, bark). All fractions 0 is the isotropic noise exactly.
    oriented,
};
const char* to_string(GaborKind kind);
GaborKind gabor_kind_from_string(const std::string& name);  // throws Error

/// Random-phase Gabor noise octaves (paper 001, with paper 000's colour and histogram model).
/// Channel c is Σ_k weights[c][k] · n_k, n_k a solid random-phase Gabor noise of unit variance
/// whose kernels have frequency |ω| = frequencies[k] and bandwidth a = bandwidth · frequencies[k].
struct GaborParameters {
    GaborKind kind = GaborKind::isotropic;
    /// Unit vector in solid texture space (u, v, w): the frequency direction (anisotropic) or the
    /// normal of the frequency plane (hybrid); unused by isotropic noise.
    std::array<double, 3> direction{0, 0, 1};
    /// a / F, the same for every octave (so octaves are scaled copies of one another).
    double bandwidth = 1;
    /// Mean number of impulses whose kernel (5 % envelope radius) covers a point: quality vs cost.
    double impulses_per_kernel = 16;
    /// Octave frequencies F_k in cycles per exemplar pixel.
    std::vector<double> frequencies;
    /// weights[c][k]: standard deviation of octave k in channel c (as many as frequencies).
    std::array<std::vector<double>, 3> weights;
    /// Kind oriented only (empty otherwise), one per octave: the frequency direction θ_k of the
    /// oriented kernels in degrees, from u towards v, in [−90, 90] (ω and −ω are the same noise),
    /// and the fraction of the octave's kernels that are oriented, in [0, 1].
    std::vector<double> orientations, oriented_fractions;
};

}  // namespace stochtex
