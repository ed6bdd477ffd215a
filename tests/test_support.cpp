#include "test_support.h"

#include <filesystem>

#include <cstdio>

#include <sys/wait.h>
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

CommandResult run_command(const std::string& command_line)
{
    CommandResult result;
    FILE* pipe = popen((command_line + " 2>&1").c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.output.append(buffer, n);
    const int status = pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string shell_quote(const std::string& argument)
{
    std::string quoted = "'";
    for (char c : argument) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

}  // namespace stochtex::test
