// Formatting `stex info` lines: one printf-style helper for the shared lines (analysis/describe.cpp)
// and each model's own (Model::describe), so the columns line up the same way everywhere. Beside
// model.h, below every model's folder, so that models format their lines without including
// analysis/.
#pragma once

#include <cstdio>
#include <string>

namespace stochtex {

/// `pattern` (printf, up to three doubles) as a string; longer results are cut at 255 characters.
inline std::string info_text(const char* pattern, double a, double b = 0, double c = 0)
{
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
    return buffer;
}

}  // namespace stochtex
