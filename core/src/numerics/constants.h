// Mathematical constants, one definition each. π is spelled out rather than taken from kPi:
// kPi is POSIX, not C++17 (<cmath> need not define it), and the literal is the one glibc's
// kPi expands to, so results are the same bit for bit.
#pragma once

namespace stochtex {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace stochtex
