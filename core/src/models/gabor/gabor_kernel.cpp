#include "models/gabor/gabor_kernel.h"

#include "numerics/constants.h"

namespace stochtex {

GaborFilter::GaborFilter(double a, const Symmetric2& sigma_f)
{
    identity = sigma_f.xx == 0 && sigma_f.xy == 0 && sigma_f.yy == 0;
    if (identity) return;
    const double k = 2 * kPi * a * a;
    matrix = {1 + k * sigma_f.xx, k * sigma_f.xy, 1 + k * sigma_f.yy};
    const double det = matrix.determinant();  // ≥ 1: A = I + (positive semi-definite)
    inverse_a = {matrix.yy / det, -matrix.xy / det, matrix.xx / det};
    // A⁻¹ and Σ_f commute (A is a polynomial in Σ_f), so their product is symmetric.
    const double c = 2 * kPi * kPi;
    damping = {c * (inverse_a.xx * sigma_f.xx + inverse_a.xy * sigma_f.xy),
               c * (inverse_a.xx * sigma_f.xy + inverse_a.xy * sigma_f.yy),
               c * (inverse_a.xy * sigma_f.xy + inverse_a.yy * sigma_f.yy)};
    amplitude = 1 / std::sqrt(det);
}

}  // namespace stochtex
