// PTM fitting (paper 004 §V, after Malzbender et al. 2001): per texel, least squares of a
// biquadratic in (l_u, l_v) through the photos' values, with one pseudo-inverse shared by all
// texels. The fit is done directly in the Legendre basis: same span, same least-squares
// function, and the maps come out in ψ-space.
//
// Leave-one-light-out needs no refit. With design matrix X (one row x_i = B(l_i) per light),
// G = XᵀX, P = G⁻¹Xᵀ and leverages h_i = x_i · P[:, i], deleting light i changes the
// coefficients by −P[:, i]·e_i/(1 − h_i) (e_i the residual), exactly; lrgb's chroma then follows
// from per-texel sums that are updated by removing light i's term.
#include <stochtex/error.h>
#include <stochtex/models/ptm.h>
#include <stochtex/models/ptm_parameters.h>

#include "models/ptm/ptm_functions.h"

#include "models/ptm/legendre_basis.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace stochtex {

namespace {

using legendre::term_count;
using legendre::Terms;
using Vector6 = Eigen::Matrix<double, term_count, 1>;
using Matrix6 = Eigen::Matrix<double, term_count, term_count>;

/// G's condition number beyond this means the lights do not determine a biquadratic.
constexpr double max_condition = 1e8;
/// A leverage this close to 1: the light alone fixes part of the fit; leaving it out is undefined.
constexpr double max_leverage = 1 - 1e-9;

struct Design {
    std::vector<Vector6> rows;     // x_i
    std::vector<Vector6> columns;  // P[:, i] = G⁻¹ x_i
    std::vector<double> leverage;  // h_i
    Matrix6 gram;                  // G
};

Design make_design(const std::vector<Vec3>& directions)
{
    Design design;
    design.gram.setZero();
    for (const Vec3& l : directions) {
        const Terms b = legendre::legendre(l[0], l[1]);
        const Vector6 row = Eigen::Map<const Vector6>(b.data());
        design.rows.push_back(row);
        design.gram += row * row.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(design.gram);
    const double smallest = eigen.eigenvalues()(0), largest = eigen.eigenvalues()(term_count - 1);
    if (!(smallest > largest / max_condition))
        throw Error("PTM fit: the light directions do not determine a biquadratic (condition number " +
                    std::to_string(largest / std::max(smallest, 1e-300)) +
                    "); spread the lights over the hemisphere");
    const Matrix6 inverse = design.gram.inverse();
    for (const Vector6& row : design.rows) {
        design.columns.push_back(inverse * row);
        design.leverage.push_back(row.dot(design.columns.back()));
    }
    return design;
}

/// Predictions are clamped as relighting clamps them (radiance is not negative).
double clamp_positive(double value) { return std::max(0.0, value); }

/// lrgb chroma: the least-squares factor c with value ≈ luminance · c, given Σ value·luminance
/// and Σ luminance²; neutral (1) where the texel is black under every light.
double chroma_factor(double value_times_luminance, double luminance_squared)
{
    return luminance_squared > 1e-30 ? value_times_luminance / luminance_squared : 1.0;
}

/// Sums of squared errors, over everything and per light.
struct ErrorSums {
    double fit = 0, loo = 0, data = 0;
    std::vector<double> loo_per_light;
};

}  // namespace

PtmFit fit_ptm(const std::vector<Image>& photos, const std::vector<Vec3>& directions, PtmColour colour,
               const ProgressCallback& progress)
{
    const std::size_t n = photos.size();
    if (n != directions.size())
        throw Error("PTM fit: " + std::to_string(n) + " photos but " + std::to_string(directions.size()) + " directions");
    if (n < std::size_t(term_count))
        throw Error("PTM fit: needs at least 6 photos (a biquadratic has 6 coefficients), got " + std::to_string(n));
    for (std::size_t i = 0; i < n; ++i) {
        if (photos[i].channels != 3) throw Error("PTM fit: photo " + std::to_string(i) + " is not RGB");
        if (photos[i].width != photos[0].width || photos[i].height != photos[0].height)
            throw Error("PTM fit: photo " + std::to_string(i) + " is " + std::to_string(photos[i].width) + "x" +
                        std::to_string(photos[i].height) + ", photo 0 is " + std::to_string(photos[0].width) + "x" +
                        std::to_string(photos[0].height) + " (one camera, one size)");
    }
    std::vector<Vec3> unit;
    for (std::size_t i = 0; i < n; ++i)
        unit.push_back(checked_light_direction(directions[i], "light " + std::to_string(i)));
    const Design design = make_design(unit);
    const bool loo_defined =
        *std::max_element(design.leverage.begin(), design.leverage.end()) < max_leverage;

    const int width = photos[0].width, height = photos[0].height;
    const int channels = ptm_channel_count(colour);
    PtmFit fit;
    fit.maps.colour = colour;
    fit.maps.coefficients = Image(width, height, channels);
    ErrorSums sums;
    sums.loo_per_light.assign(n, 0.0);

    std::vector<double> values(n * 3), luminance(n);
    for (int y = 0; y < height; ++y) {
        if (progress && y % 16 == 0) progress(double(y) / height, "fit");
        for (int x = 0; x < width; ++x) {
            const std::size_t texel = std::size_t(y) * width + x;
            for (std::size_t i = 0; i < n; ++i) {
                const float* rgb = &photos[i].pixels[texel * 3];
                luminance[i] = 0;
                for (int c = 0; c < 3; ++c) {
                    values[i * 3 + c] = rgb[c];
                    luminance[i] += luma_weights[c] * rgb[c];
                    sums.data += double(rgb[c]) * rgb[c];
                }
            }
            float* out = &fit.maps.coefficients.pixels[texel * channels];
            // The fitted functions: luminance (lrgb) or R, G, B (rgb); b = P · values.
            const int functions = colour == PtmColour::lrgb ? 1 : 3;
            std::array<Vector6, 3> b;
            for (int f = 0; f < functions; ++f) {
                b[f].setZero();
                for (std::size_t i = 0; i < n; ++i)
                    b[f] += design.columns[i] * (colour == PtmColour::lrgb ? luminance[i] : values[i * 3 + f]);
                for (int k = 0; k < term_count; ++k) out[f * term_count + k] = float(b[f](k));
            }
            if (colour == PtmColour::rgb) {
                for (std::size_t i = 0; i < n; ++i)
                    for (int c = 0; c < 3; ++c) {
                        const double value = values[i * 3 + c];
                        const double residual = value - design.rows[i].dot(b[c]);
                        sums.fit += std::pow(value - clamp_positive(value - residual), 2);
                        if (!loo_defined) continue;
                        const double predicted = clamp_positive(value - residual / (1 - design.leverage[i]));
                        sums.loo += std::pow(value - predicted, 2);
                        sums.loo_per_light[i] += std::pow(value - predicted, 2);
                    }
                continue;
            }
            // lrgb chroma from Σ_i value_ci · L_i and Σ_i L_i², L_i the fitted luminance.
            // Kept as 6-vectors (Σ_i value_ci x_i, and G) so that one light can be removed.
            std::array<Vector6, 3> value_moments;
            for (auto& m : value_moments) m.setZero();
            for (std::size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) value_moments[c] += design.rows[i] * values[i * 3 + c];
            const double luminance_squared = b[0].dot(design.gram * b[0]);
            double chroma[3];
            for (int c = 0; c < 3; ++c) {
                chroma[c] = chroma_factor(value_moments[c].dot(b[0]), luminance_squared);
                out[term_count + c] = float(chroma[c]);
            }
            for (std::size_t i = 0; i < n; ++i) {
                const double fitted = design.rows[i].dot(b[0]);
                for (int c = 0; c < 3; ++c)
                    sums.fit += std::pow(values[i * 3 + c] - clamp_positive(fitted * chroma[c]), 2);
                if (!loo_defined) continue;
                const double residual = luminance[i] - fitted;
                const Vector6 without = b[0] - design.columns[i] * (residual / (1 - design.leverage[i]));
                const double at_i = design.rows[i].dot(without);
                const double without_squared = without.dot(design.gram * without) - at_i * at_i;
                for (int c = 0; c < 3; ++c) {
                    const double value = values[i * 3 + c];
                    const double moment = (value_moments[c] - design.rows[i] * value).dot(without);
                    const double predicted = clamp_positive(at_i * chroma_factor(moment, without_squared));
                    sums.loo += std::pow(value - predicted, 2);
                    sums.loo_per_light[i] += std::pow(value - predicted, 2);
                }
            }
        }
    }
    const double count = double(n) * width * height * 3;
    fit.data_rms = std::sqrt(sums.data / count);
    fit.rmse = std::sqrt(sums.fit / count);
    const double undefined = std::numeric_limits<double>::quiet_NaN();
    fit.loo_rmse = loo_defined ? std::sqrt(sums.loo / count) : undefined;
    for (double sum : sums.loo_per_light)
        fit.loo_rmse_per_light.push_back(loo_defined ? std::sqrt(sum / (double(width) * height * 3)) : undefined);
    if (progress) progress(1.0, "fit");
    return fit;
}

}  // namespace stochtex
