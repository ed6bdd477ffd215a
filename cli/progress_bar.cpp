#include "progress_bar.h"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace stex_cli {

stochtex::ProgressCallback terminal_progress_bar()
{
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
