// `stex batch`: progress over photos — done/total and the time left.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace stex_cli {

/// Counts finished photos and shows it: on a terminal a line redrawn in place on stderr
/// ("batch 5/12 photos, 1 failed, 0:42 left"); with `stex --progress-lines` one line per photo
/// "progress FRACTION batch DONE/TOTAL eta SECONDS" for programs; else nothing. Each photo's own
/// line (what it became) goes to stdout either way. Thread-safe: the --jobs workers share one.
class BatchProgress {
public:
    explicit BatchProgress(int total);
    /// One photo finished; `line` says what became of it.
    void photo_finished(bool failed, const std::string& line);

private:
    std::mutex mutex_;
    int total_, done_ = 0, failed_ = 0;
    bool terminal_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace stex_cli
