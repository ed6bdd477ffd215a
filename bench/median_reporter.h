// stochtex benchmarks — the console table, then a comparison line per benchmark against the
// references measured in the same run. Google Benchmark prints each repetition and the
// aggregates; this reporter keeps the median rate of every benchmark (the single run when
// there are no repetitions) so that a benchmark's Finalize can print the comparisons.
#pragma once

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <map>
#include <string>

namespace stochtex::bench {

class MedianReporter : public benchmark::ConsoleReporter {
public:
    struct Entry {
        double rate = 0;    ///< the counter's median value (e.g. Mpix/s)
        std::string label;  ///< the benchmark's label (its model and parameters)
    };

    /// `units`: the rate counters to keep, in order of preference (the first one a run has).
    explicit MedianReporter(std::initializer_list<const char*> units, OutputOptions options = OO_Defaults)
        : ConsoleReporter(options), units_(units)
    {
    }

    void ReportRuns(const std::vector<Run>& reports) override
    {
        ConsoleReporter::ReportRuns(reports);
        for (const Run& run : reports) {
            if (run.error_occurred) continue;
            if (run.run_type == Run::RT_Aggregate && run.aggregate_name != "median") continue;
            for (const char* unit : units_) {
                const auto counter = run.counters.find(unit);
                if (counter == run.counters.end()) continue;
                medians_[run.run_name.str()] = {counter->second.value, run.report_label};
                break;
            }
        }
    }

protected:
    /// Medians by benchmark name (without the aggregate suffix), sorted by name.
    const std::map<std::string, Entry>& medians() const { return medians_; }
    /// The first benchmark whose name starts with `prefix`, or nullptr.
    const Entry* find(const std::string& prefix) const
    {
        for (const auto& [name, entry] : medians_)
            if (name.rfind(prefix, 0) == 0) return &entry;
        return nullptr;
    }

private:
    std::initializer_list<const char*> units_;
    std::map<std::string, Entry> medians_;
};

/// Whether the run prints Google Benchmark's console format (then a MedianReporter reports it):
/// no --benchmark_format=… other than console, nor a BENCHMARK_FORMAT environment variable.
inline bool console_format(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i)
        if (std::strncmp(argv[i], "--benchmark_format=", 19) == 0) return std::strcmp(argv[i] + 19, "console") == 0;
    const char* env = std::getenv("BENCHMARK_FORMAT");
    return !env || std::strcmp(env, "console") == 0;
}

}  // namespace stochtex::bench
