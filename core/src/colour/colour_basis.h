// Colour decorrelation (paper 000, §6.2): the principal axes of the photo's RGB covariance.
#pragma once

#include <stochtex/image.h>
#include <stochtex/texture_description.h>

#include <array>

namespace stochtex {

using Matrix3 = std::array<std::array<double, 3>, 3>;

struct ColourBasis {
    std::array<double, 3> mean{};
    /// Columns are the axes; rgb = mean + basis · y.
    Matrix3 basis{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
};

/// PCA mode: eigenvectors of the covariance sorted by decreasing variance, each signed so its
/// component sum is positive (the first axis is "brightness", as users expect), and the last
/// flipped if needed so that det = +1 (a rotation, which morphing slerps). RGB modes: identity.
ColourBasis fit_colour_basis(const Image& rgb, ColourMode mode);

/// y = basisᵀ (rgb − mean), as three planes.
std::array<std::vector<float>, 3> decorrelate(const Image& rgb, const ColourBasis& basis);

double determinant(const Matrix3& m);

}  // namespace stochtex
