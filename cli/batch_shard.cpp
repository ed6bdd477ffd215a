#include "batch_shard.h"

#include <stochtex/error.h>

#include <cstdio>

namespace stex_cli {

using stochtex::Error;

std::string BatchShard::label() const
{
    return "shard-" + std::to_string(index) + "-of-" + std::to_string(count);
}

namespace {

bool parse_count(const char* text, int& value)
{
    char extra = 0;
    return text && std::sscanf(text, "%d%c", &value, &extra) == 1;
}

BatchShard checked(int index, int count, const std::string& what)
{
    if (count < 1 || count > 1000000 || index < 0 || index >= count)
        throw Error("--shard: " + what + ": expected 0 <= I < N, N >= 1");
    return {index, count};
}

}  // namespace

BatchShard parse_batch_shard(const std::string& text, const std::function<const char*(const char*)>& environment)
{
    if (text == "auto") {
        const char* id = environment("SLURM_ARRAY_TASK_ID");
        const char* count = environment("SLURM_ARRAY_TASK_COUNT");
        int i = 0, n = 0;
        if (!parse_count(id, i) || !parse_count(count, n))
            throw Error(std::string("--shard auto: needs SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT (an sbatch --array "
                                    "task); got SLURM_ARRAY_TASK_ID=") +
                        (id ? "'" + std::string(id) + "'" : "unset") + ", SLURM_ARRAY_TASK_COUNT=" +
                        (count ? "'" + std::string(count) + "'" : "unset") +
                        " (other schedulers: pass --shard I/N, docs/cluster.md)");
        // `--array=0-(N-1)` numbers the tasks 0..N-1; another numbering would leave photos out.
        return checked(i, n, "SLURM_ARRAY_TASK_ID=" + std::string(id) + ", SLURM_ARRAY_TASK_COUNT=" + count +
                                 " (submit with --array=0-(N-1))");
    }
    int i = 0, n = 0;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &i, &slash, &n, &extra) != 3 || slash != '/')
        throw Error("--shard: expected I/N (e.g. 0/4) or auto, got '" + text + "'");
    return checked(i, n, "'" + text + "'");
}

}  // namespace stex_cli
