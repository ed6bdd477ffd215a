// `stex batch`: what became of each photo, logged per shard and merged into one report.
//
// Layout of a batch's output folder:
//   <name>/<name>.stex, <name>/photo.png, synthesis.png, compare.png, <name>.exr   (per photo)
//   batch-plan.json               every photo of the batch, in stable-index order (each shard writes it)
//   reports/shard-I-of-N.jsonl    one JSON line per photo a shard finished, appended as it goes
//   report.json, report.csv       the merge: one record per photo, in index order (no timings:
//                                 the same bytes whatever the shards or --jobs)
//   timings.csv                   the merge's seconds per photo, which vary from run to run
//   index.html                    the gallery (batch_gallery.h)
#pragma once

#include "batch_inputs.h"

#include <stochtex/texture_description.h>

#include <string>
#include <vector>

namespace stex_cli {

/// One photo's outcome.
struct PhotoRecord {
    int index = 0;
    std::string name, photo;   ///< the output name; the photo as the source listed it
    std::string status;        ///< "done", "failed", or (merge only) "missing": no shard reported it
    std::string error;         ///< failed: the message
    std::string model, colour; ///< the texture's model and colour mode ("pca+joint": joint colour)
    int width = 0, height = 0; ///< the photo's
    long long bytes = 0;       ///< the .stex file's
    /// `--model auto`: every candidate's score, as the .stex provenance keeps it
    /// (Provenance::model_choice); the chosen one's metrics are the record's. Empty for a named model.
    std::vector<stochtex::ModelScore> candidates;
    int chosen = -1;           ///< index into candidates; -1: none (a named model)
    std::vector<std::string> outputs;  ///< files written, relative to the output folder
    double seconds = 0;        ///< wall time of the photo (in the shard logs and timings.csv only)
};

/// The record of a finished analysis: model, colour and the score table from `description`
/// (its provenance), the chosen candidate marked as format_model_choice marks it.
void fill_from_description(PhotoRecord& record, const stochtex::TextureDescription& description);

/// Writes batch-plan.json (atomically); if one is there already it must list the same photos
/// (a resumed or sharded run of one batch), else throws Error naming the folder.
void write_batch_plan(const std::string& output_folder, const std::vector<BatchPhoto>& photos);

/// The shard log's path, and appending one record to it as one write(2) of one line (O_APPEND),
/// flushed to disk: a task killed at any moment leaves whole lines, and a record only follows
/// every output of its photo.
std::string shard_log_path(const std::string& output_folder, const std::string& shard_label);
void append_record(const std::string& log_path, const PhotoRecord& record);

/// Every record of every shard log under `output_folder` (an unterminated last line, if any,
/// left out), in file-name then line order.
std::vector<PhotoRecord> read_shard_logs(const std::string& output_folder);

/// The names of photos some shard log reports done: what --resume skips.
std::vector<std::string> finished_names(const std::string& output_folder);

struct MergeSummary {
    int total = 0, done = 0, failed = 0, missing = 0;
};

/// Merges the shard logs of `output_folder` over its batch plan into report.json, report.csv,
/// timings.csv and index.html (all atomically). Per photo: its "done" record if any shard has
/// one, else its last failure, else "missing". Throws Error if the folder has no batch plan.
MergeSummary merge_batch_reports(const std::string& output_folder);

}  // namespace stex_cli
