#include "numerics/nonnegative_least_squares.h"

#include <stochtex/error.h>

#include <vector>

namespace stochtex {

Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b)
{
    const Eigen::Index n = a.cols();
    if (a.rows() != b.size()) throw Error("nonnegative_least_squares: A and b have different row counts");
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    std::vector<bool> passive(std::size_t(n), false);
    const double tolerance = 1e-12 * (a.norm() * b.norm() + 1e-300);

    // Solves the unconstrained problem on the passive columns; the others stay 0.
    auto solve_passive = [&]() {
        std::vector<Eigen::Index> columns;
        for (Eigen::Index j = 0; j < n; ++j)
            if (passive[std::size_t(j)]) columns.push_back(j);
        // The inner loop can free every column (each step to the boundary zeroes one); the
        // problem on no columns has the solution 0, and Eigen cannot factor a 0-column matrix.
        if (columns.empty()) return Eigen::VectorXd::Zero(n).eval();
        Eigen::MatrixXd sub(a.rows(), Eigen::Index(columns.size()));
        for (std::size_t k = 0; k < columns.size(); ++k) sub.col(Eigen::Index(k)) = a.col(columns[k]);
        const Eigen::VectorXd solution = sub.colPivHouseholderQr().solve(b);
        Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
        for (std::size_t k = 0; k < columns.size(); ++k) s[columns[k]] = solution[Eigen::Index(k)];
        return s;
    };

    for (int outer = 0; outer < 3 * n + 10; ++outer) {
        const Eigen::VectorXd gradient = a.transpose() * (b - a * x);
        Eigen::Index best = -1;
        for (Eigen::Index j = 0; j < n; ++j)
            if (!passive[std::size_t(j)] && gradient[j] > tolerance && (best < 0 || gradient[j] > gradient[best])) best = j;
        if (best < 0) return x;  // Kuhn–Tucker conditions hold
        passive[std::size_t(best)] = true;
        for (int inner = 0; inner < 3 * n + 10; ++inner) {
            const Eigen::VectorXd s = solve_passive();
            bool feasible = true;
            double step = 1;
            for (Eigen::Index j = 0; j < n; ++j)
                if (passive[std::size_t(j)] && s[j] <= 0) {
                    feasible = false;
                    step = std::min(step, x[j] / (x[j] - s[j]));
                }
            if (feasible) {
                x = s;
                break;
            }
            // Walk towards s until the first coordinate hits zero, and free it.
            x += step * (s - x);
            for (Eigen::Index j = 0; j < n; ++j)
                if (passive[std::size_t(j)] && x[j] <= 1e-15) {
                    passive[std::size_t(j)] = false;
                    x[j] = 0;
                }
        }
    }
    return x;  // the iteration bounds are generous; reaching them leaves a feasible x
}

}  // namespace stochtex
