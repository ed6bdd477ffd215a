#include "test_support.h"

#include <stochtex/error.h>
#include <stochtex/texture.h>

#include <filesystem>

#include <cerrno>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace fs = std::filesystem;

namespace stochtex::test {

std::string raster_point_difference(const Texture& texture, const RasterRegion& region)
{
    std::vector<float> raster(std::size_t(region.width) * region.height * 3);
    texture.eval_region(region, raster.data());
    for (int j = 0; j < region.height; ++j)
        for (int i = 0; i < region.width; ++i) {
            const Rgb point = texture.eval({region.u(i), region.v(j)}, region.footprint);
            for (int c = 0; c < 3; ++c) {
                const float value = raster[(std::size_t(j) * region.width + i) * 3 + c];
                if (value != point[c])
                    return "pixel " + std::to_string(i) + ", " + std::to_string(j) + " channel " + std::to_string(c) +
                           ": raster " + std::to_string(value) + ", point " + std::to_string(point[c]);
            }
        }
    return "";
}

std::string error_of(const std::function<void()>& action)
{
    try {
        action();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

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

std::ostream& operator<<(std::ostream& os, const ProgramResult& r)
{
    if (r.exited)
        os << "exit code " << r.code;
    else
        os << "killed by signal " << r.signal;
    return os << "\n--- stdout ---\n" << r.out << "--- stderr ---\n" << r.err;
}

namespace {

std::string read_text(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

RunningProgram start_program(const std::vector<std::string>& args, const std::string& dir)
{
    RunningProgram program;
    program.dir = dir;
    program.name = args.empty() ? std::string() : args[0];
    const fs::path out_path = fs::path(dir) / "stdout.txt", err_path = fs::path(dir) / "stderr.txt";
    std::vector<std::string> strings = args;
    std::vector<char*> argv;
    for (std::string& arg : strings) argv.push_back(arg.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    program.spawn_error = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    program.pid = program.spawn_error == 0 ? pid : -1;
    return program;
}

ProgramResult finish_program(const RunningProgram& program)
{
    ProgramResult result;
    if (program.spawn_error != 0) {
        result.err = "cannot run " + program.name + ": " + std::strerror(program.spawn_error);
        return result;
    }
    int status = 0;
    while (waitpid(program.pid, &status, 0) < 0 && errno == EINTR) {
    }
    result.exited = WIFEXITED(status);
    result.code = result.exited ? WEXITSTATUS(status) : -1;
    result.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    result.out = read_text(fs::path(program.dir) / "stdout.txt");
    result.err = read_text(fs::path(program.dir) / "stderr.txt");
    return result;
}

ProgramResult run_program(const std::vector<std::string>& args, const std::string& dir)
{
    return finish_program(start_program(args, dir));
}

bool on_path(const std::string& name)
{
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "");
    for (std::string folder; std::getline(folders, folder, ':');)
        if (!folder.empty() && access((fs::path(folder) / name).c_str(), X_OK) == 0) return true;
    return false;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

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
