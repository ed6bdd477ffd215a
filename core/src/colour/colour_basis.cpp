#include "colour/colour_basis.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <numeric>

namespace stochtex {

double determinant(const Matrix3& m)
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

ColourBasis fit_colour_basis(const Image& rgb, ColourMode mode)
{
    ColourBasis result;
    const std::size_t n = rgb.pixel_count();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d x(rgb.pixels[3 * i], rgb.pixels[3 * i + 1], rgb.pixels[3 * i + 2]);
        sum += x;
        second += x * x.transpose();
    }
    const Eigen::Vector3d mean = sum / double(n);
    for (int c = 0; c < 3; ++c) result.mean[c] = mean[c];
    if (mode != ColourMode::pca) return result;

    const Eigen::Matrix3d covariance = second / double(n) - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return solver.eigenvalues()[a] > solver.eigenvalues()[b]; });
    Eigen::Matrix3d axes;
    for (int c = 0; c < 3; ++c) {
        Eigen::Vector3d axis = solver.eigenvectors().col(order[c]);
        const double component_sum = axis.sum();
        // Sign rule: positive component sum; for axes orthogonal to grey (sum ≈ 0), make the
        // largest-magnitude component positive so the choice is still deterministic.
        int largest = 0;
        axis.cwiseAbs().maxCoeff(&largest);
        const bool flip = std::abs(component_sum) > 1e-6 ? component_sum < 0 : axis[largest] < 0;
        axes.col(c) = flip ? Eigen::Vector3d(-axis) : axis;
    }
    if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) result.basis[r][c] = axes(r, c);
    return result;
}

std::array<std::vector<float>, 3> decorrelate(const Image& rgb, const ColourBasis& basis)
{
    const std::size_t n = rgb.pixel_count();
    std::array<std::vector<float>, 3> planes;
    for (auto& plane : planes) plane.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double d[3] = {rgb.pixels[3 * i] - basis.mean[0], rgb.pixels[3 * i + 1] - basis.mean[1],
                             rgb.pixels[3 * i + 2] - basis.mean[2]};
        for (int c = 0; c < 3; ++c)
            planes[c][i] = float(basis.basis[0][c] * d[0] + basis.basis[1][c] * d[1] + basis.basis[2][c] * d[2]);
    }
    return planes;
}

}  // namespace stochtex
