// `stex batch --shard I/N`: which photos of a batch one task of an array job converts.
#pragma once

#include <functional>
#include <string>

namespace stex_cli {

/// Task `index` of `count`: the photos whose stable index mod count is index. Every scheduler's
/// array job hands its tasks an index (docs/cluster.md); the split depends on nothing else, so
/// the shards of one batch never overlap and together cover it, whatever order they run in.
struct BatchShard {
    int index = 0, count = 1;
    bool holds(int photo_index) const { return photo_index % count == index; }
    /// "shard-I-of-N": the name of this shard's report.
    std::string label() const;
};

/// Parses "I/N" (0 ≤ I < N), or "auto": SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT from
/// `environment` (a getenv; the task ids of `sbatch --array=0-(N-1)`). Throws stochtex::Error
/// naming --shard and what was wrong (the variables' values included).
BatchShard parse_batch_shard(const std::string& text,
                             const std::function<const char*(const char*)>& environment);

}  // namespace stex_cli
