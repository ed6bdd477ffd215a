// `stex batch`: the photos of a batch, from a folder or a manifest, each with a stable index.
#pragma once

#include <string>
#include <vector>

namespace stex_cli {

/// One photo of a batch and the options it was given (empty: the batch's own).
struct BatchPhoto {
    int index = 0;          ///< its place in the batch: what sharding uses (index mod N)
    std::string path;       ///< where to read it (relative paths are the manifest's folder's)
    std::string listed_as;  ///< as the folder or manifest names it (kept in the report)
    std::string name;       ///< its output subfolder and file stem: unique in the batch
    std::string model, colour;
    double unit_size_m = 0; ///< 0: the batch's; -1: the manifest's value is not a number > 0 (the photo fails)
};

/// The photos of `source`: a folder (its image files, sorted by name, not recursing) or a manifest
/// (.csv with a header row naming `photo` and optionally `name`, `model`, `colour`, `unit_size`; or
/// .json: an array of objects with those keys, or {"photos": [...]}). The order — sorted names, the
/// manifest's rows — is the stable index, so every shard of every run agrees on it. Throws
/// stochtex::Error naming the source for a source that does not exist, a manifest that cannot be
/// parsed, a row without a photo, and two photos with one name (the second row named). A photo
/// that is missing or unreadable is not checked here: it fails alone when the batch reaches it.
std::vector<BatchPhoto> list_batch_photos(const std::string& source);

/// `text` made safe as one file name: letters, digits, '.', '-' and '_' kept, others '_'.
std::string batch_safe_name(const std::string& text);

}  // namespace stex_cli
