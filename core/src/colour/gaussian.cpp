#include "colour/gaussian.h"

#include "numerics/constants.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <limits>

namespace stochtex {

double inverse_normal_cdf(double p)
{
    constexpr double tiny = std::numeric_limits<double>::min();
    p = std::clamp(p, tiny, 1.0 - 1e-16);
    // Acklam (2003): rational approximations on the central region and the tails.
    static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                   1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
    static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                   6.680131188771972e+01,  -1.328068155288572e+01};
    static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                   -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
    static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                   3.754408661907416e+00};
    constexpr double p_low = 0.02425;
    double x;
    if (p < p_low) {
        const double q = std::sqrt(-2 * std::log(p));
        x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    } else if (p <= 1 - p_low) {
        const double q = p - 0.5, r = q * q;
        x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
            (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
    } else {
        const double q = std::sqrt(-2 * std::log(1 - p));
        x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    }
    // One Halley step takes the 1e-9 approximation to full double precision.
    const double e = normal_cdf(x) - p;
    const double u = e * std::sqrt(2 * kPi) * std::exp(0.5 * x * x);
    return x - u / (1 + 0.5 * x * u);
}

const GaussHermite& GaussHermite::standard_normal()
{
    static const GaussHermite rule = [] {
        // Golub–Welsch for the probabilists' Hermite weight exp(−z²/2): the Jacobi matrix has
        // zero diagonal and off-diagonal sqrt(k); nodes are its eigenvalues, weights the squared
        // first components of its unit eigenvectors.
        Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(count, count);
        for (int k = 1; k < count; ++k) jacobi(k, k - 1) = jacobi(k - 1, k) = std::sqrt(double(k));
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(jacobi);
        GaussHermite result;
        for (int i = 0; i < count; ++i) {
            result.node[i] = solver.eigenvalues()(i);
            const double first = solver.eigenvectors()(0, i);
            result.weight[i] = first * first;
        }
        return result;
    }();
    return rule;
}

const SmallGaussHermite& SmallGaussHermite::standard_normal(int count)
{
    static const std::array<SmallGaussHermite, 3> rules = [] {
        // The positive nodes and, first, the centre's weight; the rule mirrors them.
        const std::vector<double> nodes[3] = {
            {1.7320508075688772},
            {1.3556261799742659, 2.8569700138728056},
            {1.1544053947399682, 2.366759410734541, 3.7504397177257425}};
        const std::vector<double> weights[3] = {
            {2.0 / 3, 1.0 / 6},
            {8.0 / 15, 0.2220759220056126, 0.011257411327720691},
            {16.0 / 35, 0.2401231786050127, 0.030757123967586498, 0.0005482688559722184}};
        std::array<SmallGaussHermite, 3> result;
        for (std::size_t r = 0; r < 3; ++r) {
            SmallGaussHermite& rule = result[r];
            const std::size_t half = nodes[r].size();
            for (std::size_t k = half; k > 0; --k) rule.node.push_back(-nodes[r][k - 1]), rule.weight.push_back(weights[r][k]);
            rule.node.push_back(0), rule.weight.push_back(weights[r][0]);
            for (std::size_t k = 0; k < half; ++k) rule.node.push_back(nodes[r][k]), rule.weight.push_back(weights[r][k + 1]);
        }
        return result;
    }();
    return rules[std::size_t(std::clamp(count, 3, 7) - 3) / 2];
}

}  // namespace stochtex
