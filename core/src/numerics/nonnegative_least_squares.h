// Non-negative least squares: min ‖A x − b‖ subject to x ≥ 0 (Lawson & Hanson 1974, ch. 23).
// For small dense problems (tens of unknowns): fitting non-negative powers, where an
// unconstrained solve of strongly overlapping columns would give negative "variances".
#pragma once

#include <Eigen/Dense>

namespace stochtex {

/// The active-set algorithm: exact (up to round-off) in finitely many steps, unlike projected
/// descent, which crawls when columns are nearly collinear (adjacent octaves of a broad noise).
Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

}  // namespace stochtex
