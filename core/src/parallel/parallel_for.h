// stochtex — the one worker pool: independent items on all cores (TBB), with progress,
// cancellation and errors that reach the caller.
#pragma once

#include <stochtex/progress.h>

#include <atomic>
#include <functional>

namespace stochtex {

/// What parallel_for reports while it runs, and how to stop it.
struct ParallelReport {
    /// Called with the fraction of items done, from the calling thread only (progress.h), at
    /// most every 50 ms while items run and once with 1.0 at the end.
    ProgressCallback progress;
    /// The stage name given to progress and to the cancellation error.
    const char* stage = "";
    /// Set (from any thread) to stop: items not yet started are skipped and parallel_for
    /// throws Error("<stage>: cancelled").
    const std::atomic<bool>* cancel = nullptr;
};

/// The thread count a `threads` option means: itself if positive, else the machine's cores.
int thread_count(int requested);

/// Runs body(index) once for every index in [0, count), items spread over at most `threads`
/// threads, the caller's included (thread_count(): 0 is all cores; TBB never runs more threads
/// than the machine has cores, whatever is asked).
/// Callers give each item its own output (a row band, a tile, a row), so results do not depend
/// on which thread runs an item nor in what order: renders stay bit-identical for any thread
/// count. The first exception an item throws stops the items not yet started, and is rethrown
/// here — on the calling thread, as thrown (an Error keeps its message) — once every running
/// item has ended, so nothing outlives the caller's buffers and no worker ends the process.
void parallel_for(int count, int threads, const std::function<void(int index)>& body, const ParallelReport& report = {});

}  // namespace stochtex
