#include "test_support.h"

#include <filesystem>

#include <unistd.h>

namespace fs = std::filesystem;

namespace stochtex::test {

std::string shared_exemplar(const std::string& name)
{
    fs::path path = fs::path(STOCHTEX_SHARED_DIR) / "exemplars" / name;
    return fs::exists(path) ? path.string() : std::string();
}

std::string repo_exemplar(const std::string& name)
{
    return (fs::path(STOCHTEX_SOURCE_DIR) / "data" / "exemplars" / name).string();
}

std::string temp_dir(const std::string& test_name)
{
    // CTest runs tests in parallel processes: the pid keeps their directories apart.
    fs::path dir = fs::temp_directory_path() / ("stochtex-test-" + test_name + "-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

}  // namespace stochtex::test
