// The one worker pool (core/src/parallel/parallel_for.h): every item once, errors and
// cancellation reach the caller, progress comes from the calling thread.
#include "parallel/parallel_for.h"

#include <stochtex/error.h>

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace stochtex;

namespace {

TEST(ParallelFor, RunsEveryItemOnce)
{
    for (int threads : {0, 1, 3}) {
        std::vector<std::atomic<int>> runs(1000);
        parallel_for(int(runs.size()), threads, [&](int i) { runs[i].fetch_add(1); });
        for (std::size_t i = 0; i < runs.size(); ++i) ASSERT_EQ(runs[i].load(), 1) << "item " << i << ", " << threads << " threads";
    }
    parallel_for(0, 4, [](int) { FAIL() << "no items, no calls"; });
}

TEST(ParallelFor, TheFirstErrorReachesTheCallerAndStopsTheRest)
{
    std::atomic<int> started{0};
    try {
        parallel_for(10000, 4, [&](int i) {
            started.fetch_add(1);
            if (i == 10) throw Error("item 10 failed");
            std::this_thread::sleep_for(std::chrono::microseconds(100));
        });
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "item 10 failed");
    }
    EXPECT_LT(started.load(), 10000);  // the items not yet started were skipped
    // Any exception type arrives as thrown.
    EXPECT_THROW(parallel_for(8, 2, [](int i) { if (i == 7) throw std::bad_alloc(); }), std::bad_alloc);
}

TEST(ParallelFor, CancellationStopsTheItemsNotYetStarted)
{
    std::atomic<bool> cancel{false};
    std::vector<int> ran;
    try {
        // One thread: items run in order, so exactly items 0..3 run.
        parallel_for(100, 1, [&](int i) {
            ran.push_back(i);
            if (i == 3) cancel = true;
        }, {nullptr, "test stage", &cancel});
        FAIL() << "not cancelled";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "test stage: cancelled");
    }
    EXPECT_EQ(ran, (std::vector<int>{0, 1, 2, 3}));
}

TEST(ParallelFor, ProgressComesFromTheCallingThreadAndEndsAtOne)
{
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<double> fractions;
    std::set<std::thread::id> workers;
    std::mutex mutex;
    parallel_for(200, 3, [&](int) {
        {
            const std::lock_guard<std::mutex> lock(mutex);
            workers.insert(std::this_thread::get_id());
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }, {[&](double fraction, const char* stage) {
        EXPECT_EQ(std::this_thread::get_id(), caller);
        EXPECT_STREQ(stage, "stage");
        fractions.push_back(fraction);
    }, "stage"});
    ASSERT_GE(fractions.size(), 2u);  // 200 × 2 ms on ≤ 3 threads: ≥ 130 ms, reports every 50 ms
    for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_LE(fractions[i - 1], fractions[i]);
    EXPECT_EQ(fractions.back(), 1.0);
    EXPECT_TRUE(workers.count(caller)) << "the calling thread works too";
}

}  // namespace
