#include <stochtex/atomic_write.h>
#include <stochtex/error.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace stochtex {

namespace {

// The temporaries a signal handler may have to remove. A handler can neither lock nor allocate,
// so the paths live in fixed slots whose state is a lock-free atomic: a slot is claimed (busy),
// filled, then published (live); the handler only reads live slots.
constexpr int slot_count = 64;
constexpr std::size_t slot_path_size = 4096;
enum SlotState : int { free_slot = 0, busy_slot = 1, live_slot = 2 };
struct PendingSlot {
    std::atomic<int> state{free_slot};
    char path[slot_path_size];
};
PendingSlot pending[slot_count];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

std::atomic<unsigned> output_counter{0};

/// A slot holding `path`, or -1 when none is free or the path is too long: the temporary is then
/// still removed on failure, only not by a signal handler.
int register_pending(const std::string& path)
{
    if (path.size() >= slot_path_size) return -1;
    for (int i = 0; i < slot_count; ++i) {
        int expected = free_slot;
        if (!pending[i].state.compare_exchange_strong(expected, busy_slot)) continue;
        std::memcpy(pending[i].path, path.c_str(), path.size() + 1);
        pending[i].state.store(live_slot);
        return i;
    }
    return -1;
}

void unregister_pending(int slot)
{
    if (slot >= 0) pending[slot].state.store(free_slot);
}

}  // namespace

AtomicOutput::AtomicOutput(std::string path) : path_(std::move(path))
{
    // Beside the target (same file system, so the rename is atomic); the pid and a counter keep
    // two processes, or two outputs of one process, from sharing a temporary.
    temporary_ = path_ + "." + std::to_string(getpid()) + "-" + std::to_string(output_counter.fetch_add(1)) + ".tmp";
    slot_ = register_pending(temporary_);
}

AtomicOutput::~AtomicOutput()
{
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove(temporary_, ignored);
    }
    unregister_pending(slot_);
}

void AtomicOutput::commit()
{
    std::error_code error;
    std::filesystem::rename(temporary_, path_, error);
    if (error) throw Error(path_ + ": cannot move the finished file into place: " + error.message());
    committed_ = true;
}

void check_output_path(const std::string& path, const std::string& what)
{
    namespace fs = std::filesystem;
    const std::string failed = path + ": cannot write " + what + ": ";
    std::error_code error;
    if (path.empty()) throw Error("(empty output name): cannot write " + what);
    if (fs::is_directory(path, error)) throw Error(failed + "it is a folder");
    // The temporary is created in the output's folder (a rename is atomic only there).
    const fs::path parent = fs::path(path).parent_path();
    const fs::path folder = parent.empty() ? fs::path(".") : parent;
    if (!fs::exists(folder, error)) throw Error(failed + "the folder " + folder.string() + " does not exist");
    if (!fs::is_directory(folder, error)) throw Error(failed + folder.string() + " is not a folder");
    if (access(folder.c_str(), W_OK | X_OK) != 0)
        throw Error(failed + "the folder " + folder.string() + " is not writable (" + std::strerror(errno) + ")");
}

void write_file_atomically(const std::string& path, const std::string& text)
{
    AtomicOutput output(path);
    std::ofstream out(output.temporary(), std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path + ": cannot write: " + std::strerror(errno));
    out << text;
    out.close();  // flushes: a full disk or a file-size limit shows here
    if (!out) throw Error(path + ": cannot write: " + std::strerror(errno));
    output.commit();
}

void remove_pending_outputs() noexcept
{
    for (PendingSlot& slot : pending)
        if (slot.state.load() == live_slot) unlink(slot.path);
}

}  // namespace stochtex
