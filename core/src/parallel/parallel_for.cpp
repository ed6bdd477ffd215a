#include "parallel/parallel_for.h"

#include <stochtex/error.h>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>

namespace stochtex {

int thread_count(int requested)
{
    return requested > 0 ? requested : int(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_for(int count, int threads, const std::function<void(int index)>& body, const ParallelReport& report)
{
    if (count <= 0) return;
    using Clock = std::chrono::steady_clock;
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<int> done{0};
    Clock::time_point last_report = Clock::now();  // touched by the calling thread only
    const auto run_item = [&](int index) {
        if (report.cancel && report.cancel->load(std::memory_order_relaxed))
            throw Error(std::string(report.stage) + ": cancelled");
        body(index);
        const int finished = done.fetch_add(1, std::memory_order_relaxed) + 1;
        // The calling thread works too (TBB's arena keeps it a slot), so it reports between
        // its own items: no extra thread, and callbacks need no locking.
        if (report.progress && std::this_thread::get_id() == caller &&
            Clock::now() - last_report >= std::chrono::milliseconds(50)) {
            last_report = Clock::now();
            report.progress(double(finished) / count, report.stage);
        }
    };
    // No more than TBB will run (its worker limit, the cores by default): asking for more only
    // gets a warning on stderr.
    const int allowed = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    const int workers = std::min({thread_count(threads), count, std::max(1, allowed)});
    if (workers == 1) {
        for (int index = 0; index < count; ++index) run_item(index);
    } else {
        // One item per task (grain 1, simple partitioner): items are as large as the callers
        // chose (row bands, tiles), and counter-like balancing is what the pools before did.
        // An exception cancels the loop's task group; TBB rethrows it here after the running
        // items end.
        tbb::task_arena arena(workers);
        arena.execute([&] {
            tbb::parallel_for(
                tbb::blocked_range<int>(0, count, 1),
                [&](const tbb::blocked_range<int>& range) {
                    for (int index = range.begin(); index != range.end(); ++index) run_item(index);
                },
                tbb::simple_partitioner());
        });
    }
    if (report.progress) report.progress(1.0, report.stage);
}

}  // namespace stochtex
