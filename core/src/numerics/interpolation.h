// Interpolation between two values, as morph() and the models' morphs use it.
#pragma once

namespace stochtex {

/// a at t = 0, b at t = 1.
inline double lerp(double a, double b, double t) { return a + (b - a) * t; }

}  // namespace stochtex
