#include "models/ptm/legendre_basis.h"

#include <cmath>

namespace stochtex::legendre {

namespace {

// Expanding A in B: 1 = 2 B0, l_u = (2/√3) B1, l_v = (2/√3) B2, l_u l_v = (2/3) B3,
// l_u² = (4/√45) B4 + (2/3) B0, l_v² = (4/√45) B5 + (2/3) B0. Column k of M is A_k in B.
const double sqrt3 = std::sqrt(3.0), sqrt45 = std::sqrt(45.0);

}  // namespace

Terms monomials(double lu, double lv) { return {lu * lu, lv * lv, lu * lv, lu, lv, 1.0}; }

Terms legendre(double lu, double lv)
{
    return {0.5,
            sqrt3 / 2 * lu,
            sqrt3 / 2 * lv,
            1.5 * lu * lv,
            sqrt45 / 4 * lu * lu - sqrt45 / 12,
            sqrt45 / 4 * lv * lv - sqrt45 / 12};
}

const Matrix& monomial_to_legendre()
{
    //                        a0 (l_u²)      a1 (l_v²)      a2 (l_u l_v)  a3 (l_u)   a4 (l_v)   a5 (1)
    static const Matrix m{{{2.0 / 3,        2.0 / 3,       0,            0,         0,         2},
                           {0,              0,             0,            2 / sqrt3, 0,         0},
                           {0,              0,             0,            0,         2 / sqrt3, 0},
                           {0,              0,             2.0 / 3,      0,         0,         0},
                           {4 / sqrt45,     0,             0,            0,         0,         0},
                           {0,              4 / sqrt45,    0,            0,         0,         0}}};
    return m;
}

const Matrix& legendre_to_monomial()
{
    // The inverse of the expansion above: a0 = √45/4 b4, a1 = √45/4 b5, a2 = 3/2 b3,
    // a3 = √3/2 b1, a4 = √3/2 b2, a5 = b0/2 − √45/12 (b4 + b5).
    //                        b0    b1         b2         b3     b4            b5
    static const Matrix m{{{0,     0,         0,         0,     sqrt45 / 4,   0},
                           {0,     0,         0,         0,     0,            sqrt45 / 4},
                           {0,     0,         0,         1.5,   0,            0},
                           {0,     sqrt3 / 2, 0,         0,     0,            0},
                           {0,     0,         sqrt3 / 2, 0,     0,            0},
                           {0.5,   0,         0,         0,     -sqrt45 / 12, -sqrt45 / 12}}};
    return m;
}

Terms apply(const Matrix& matrix, const Terms& coefficients)
{
    Terms result{};
    for (int row = 0; row < term_count; ++row) result[row] = dot(matrix[row], coefficients);
    return result;
}

double dot(const Terms& coefficients, const Terms& basis)
{
    double sum = 0;
    for (int k = 0; k < term_count; ++k) sum += coefficients[k] * basis[k];
    return sum;
}

}  // namespace stochtex::legendre
