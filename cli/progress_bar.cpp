#include "progress_bar.h"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace stex_cli {

namespace {
bool progress_lines = false;
}

void set_progress_lines(bool enabled) { progress_lines = enabled; }
bool progress_lines_enabled() { return progress_lines; }

stochtex::ProgressCallback terminal_progress_bar()
{
    if (progress_lines) {
        return [last = -1](double fraction, const char* stage) mutable {
            const int percent = int(fraction * 100 + 0.5);
            if (percent == last) return;
            last = percent;
            std::fprintf(stderr, "progress %.2f %s\n", percent / 100.0, stage);
            std::fflush(stderr);
        };
    }
    if (!isatty(STDERR_FILENO)) return {};
    return [last = -1](double fraction, const char* stage) mutable {
        const int percent = int(fraction * 100 + 0.5);
        if (percent == last) return;
        last = percent;
        constexpr int width = 30;
        const int filled = percent * width / 100;
        std::fprintf(stderr, "\r%-10s [%s%s] %3d%%", stage, std::string(filled, '#').c_str(),
                     std::string(width - filled, ' ').c_str(), percent);
        if (percent >= 100) std::fputc('\n', stderr);
        std::fflush(stderr);
    };
}

}  // namespace stex_cli
