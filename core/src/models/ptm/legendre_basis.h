// The two bases of a PTM's reflectance functions (paper 004, §V–VI).
//
// A polynomial texture map describes each texel's brightness as a biquadratic function of the
// light direction's projection (l_u, l_v) on the surface:
//   monomial basis  A = {l_u², l_v², l_u l_v, l_u, l_v, 1}            (paper eq. 8: a0 … a5)
//   Legendre basis  B = {½, √3/2 l_u, √3/2 l_v, 3/2 l_u l_v,
//                        √45/4 l_u² − √45/12, √45/4 l_v² − √45/12}     (b0 … b5)
// B is orthonormal on the square [−1, 1]², so for two functions g1 = Σ b1_k B_k, g2 = Σ b2_k B_k
//   ∫∫ (g1 − g2)² dl_u dl_v = ‖b1 − b2‖²,
// which is why synthesis compares, blends and cuts coefficient vectors in B (ψ-space) and never
// in A, whose coefficient distances do not measure function distances (paper §VI).
// The matrices are the exact closed forms (the paper defers them to HPL-2003-16R1).
#pragma once

#include <array>

namespace stochtex::legendre {

constexpr int term_count = 6;
using Terms = std::array<double, term_count>;
using Matrix = std::array<Terms, term_count>;

/// A(l_u, l_v), in the order a0 … a5 of paper eq. 8.
Terms monomials(double lu, double lv);
/// B(l_u, l_v), in the order b0 … b5 above.
Terms legendre(double lu, double lv);

/// M with b = M a: the same function's coefficients in the orthonormal basis.
const Matrix& monomial_to_legendre();
/// M⁻¹ with a = M⁻¹ b.
const Matrix& legendre_to_monomial();

Terms apply(const Matrix& matrix, const Terms& coefficients);
inline Terms to_legendre(const Terms& a) { return apply(monomial_to_legendre(), a); }
inline Terms to_monomial(const Terms& b) { return apply(legendre_to_monomial(), b); }

/// Σ_k coefficients[k] · basis[k].
double dot(const Terms& coefficients, const Terms& basis);

}  // namespace stochtex::legendre
