// Shared by the libFuzzer harnesses (fuzz/README.md): a private scratch folder for the readers
// that take a path, and the folder holding the files a .stex may refer to.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace stochtex::fuzz {

/// Where .stex inputs are "read from", so that a ptm's coefficient file reference resolves
/// against the seed corpus's own coefficient files: $STOCHTEX_FUZZ_DATA (scripts/fuzz.sh sets
/// it to the seed folder), else the current folder.
inline std::string data_dir()
{
    const char* dir = std::getenv("STOCHTEX_FUZZ_DATA");
    return dir && *dir ? dir : ".";
}

/// A folder private to this process (in /dev/shm where it exists: the readers that take a path
/// then cost no disk I/O), holding links to data_dir()'s files; removed at exit.
inline const std::string& scratch_dir()
{
    static const std::string dir = [] {
        std::string base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
        std::string templ = base + "/stochtex-fuzz-XXXXXX";
        if (!mkdtemp(templ.data())) std::abort();
        std::error_code ignored;
        for (const auto& entry : std::filesystem::directory_iterator(data_dir(), ignored))
            std::filesystem::create_symlink(std::filesystem::absolute(entry.path()), std::filesystem::path(templ) / entry.path().filename(),
                                            ignored);
        static const std::string removed_at_exit = templ;
        std::atexit([] {
            std::error_code ignored_too;
            std::filesystem::remove_all(removed_at_exit, ignored_too);
        });
        return templ;
    }();
    return dir;
}

/// Writes `size` bytes to scratch_dir()/name and returns the path.
inline std::string scratch_file(const std::string& name, const std::uint8_t* data, std::size_t size)
{
    const std::string path = scratch_dir() + "/" + name;
    unlink(path.c_str());  // never write through a link to a seed
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) std::abort();
    if (size && std::fwrite(data, 1, size, file) != size) std::abort();
    std::fclose(file);
    return path;
}

}  // namespace stochtex::fuzz
