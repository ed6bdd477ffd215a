// stochtex — writing an output file safely (every .stex, image, bake, include and shader).
//
// Each output is written to a temporary file in the target's folder (a rename is atomic only
// within one file system) and renamed over the target once it is complete. So a failed write
// (disk full, file-size limit, an error half-way) or an interrupted one leaves the previous
// file as it was, and readers never see a half-written file. A failed or abandoned write also
// removes its temporary, and remove_pending_outputs() lets a signal handler do the same for a
// process that is being interrupted (the `stex` tool does it on SIGINT and SIGTERM).
#pragma once

#include <string>

namespace stochtex {

/// A temporary file beside `path` that replaces `path` on commit(); without a commit (an
/// exception, an early return) the destructor removes it.
class AtomicOutput {
public:
    explicit AtomicOutput(std::string path);
    ~AtomicOutput();
    AtomicOutput(const AtomicOutput&) = delete;
    AtomicOutput& operator=(const AtomicOutput&) = delete;

    /// The final name (for messages and for choosing a format by extension).
    const std::string& path() const { return path_; }
    /// Where to write: "<path>.<pid>-<n>.tmp", unique to this process and this output.
    const std::string& temporary() const { return temporary_; }
    /// Renames the temporary over path(). Throws Error naming path() (the temporary is removed).
    void commit();

private:
    std::string path_, temporary_;
    int slot_ = -1;  // where remove_pending_outputs() finds the temporary; -1: not registered
    bool committed_ = false;
};

/// Checks, before any work, that an output can be created at `path`: its folder exists, is a
/// folder and is writable, and `path` is not a folder. Throws Error "<path>: cannot write
/// <what>: …". check_image_output() (image.h) adds the format.
void check_output_path(const std::string& path, const std::string& what);

/// Writes `text` to `path` through an AtomicOutput. Throws Error naming the file and the reason.
void write_file_atomically(const std::string& path, const std::string& text);

/// Removes the temporary of every AtomicOutput still open in this process. Async-signal-safe
/// (only unlink(2) on paths stored in advance): meant for a SIGINT/SIGTERM handler, after which
/// the process must exit without committing anything.
void remove_pending_outputs() noexcept;

}  // namespace stochtex
