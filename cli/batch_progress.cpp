#include "batch_progress.h"

#include "progress_bar.h"

#include <unistd.h>

#include <cstdio>

namespace stex_cli {

BatchProgress::BatchProgress(int total) : total_(total), terminal_(!progress_lines_enabled() && isatty(STDERR_FILENO)) {}

void BatchProgress::photo_finished(bool failed, const std::string& line)
{
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    failed_ += failed;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    // The photos left at the mean pace so far (photos differ: a rough figure, better as it goes).
    const double left = elapsed / done_ * (total_ - done_);
    if (terminal_) std::fputs("\r\033[K", stderr);  // the progress line gives way to the photo's
    std::fputs((line + "\n").c_str(), stdout);
    std::fflush(stdout);
    if (progress_lines_enabled()) {
        std::fprintf(stderr, "progress %.4f batch %d/%d eta %.0f\n", double(done_) / total_, done_, total_, left);
    } else if (terminal_) {
        const int seconds = int(left + 0.5);
        std::fprintf(stderr, "batch %d/%d photos%s, %d:%02d left", done_, total_,
                     failed_ ? (", " + std::to_string(failed_) + " failed").c_str() : "", seconds / 60, seconds % 60);
        if (done_ == total_) std::fputc('\n', stderr);
    }
    std::fflush(stderr);
}

}  // namespace stex_cli
