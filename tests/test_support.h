// Shared helpers for the tests: where the exemplars are, temporary files.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace stochtex {
class Texture;
struct RasterRegion;
}

namespace stochtex::test {

/// ../shared/exemplars/<name> if that folder exists, else "" (the caller GTEST_SKIPs).
std::string shared_exemplar(const std::string& name);
/// The small exemplar committed to the repository (data/exemplars/<name>).
std::string repo_exemplar(const std::string& name);
/// A fresh, empty directory for this test's files, private to this process.
std::string temp_dir(const std::string& test_name);

/// The message of the stochtex::Error `action` throws, "" if it throws none (another exception
/// propagates: the test fails with it).
std::string error_of(const std::function<void()>& action);

/// The first value where texture.eval_region(region) differs from eval() at that pixel's centre
/// and the region's footprint ("pixel I, J channel C: raster R, point P"); "" when all are equal.
std::string raster_point_difference(const Texture& texture, const RasterRegion& region);

/// How a program run ended and what it printed.
struct ProgramResult {
    bool exited = false;  ///< false: killed by a signal (a crash)
    int code = -1;        ///< exit code when `exited`
    int signal = 0;       ///< the signal otherwise
    std::string out, err;
    std::string output() const { return out + err; }
    bool succeeded() const { return exited && code == 0; }
};
std::ostream& operator<<(std::ostream& os, const ProgramResult& r);

/// Runs argv[0] (a path, or a name looked up on PATH) directly — no shell, so no quoting —
/// with stdout and stderr captured through files in `dir`.
ProgramResult run_program(const std::vector<std::string>& argv, const std::string& dir);
/// A program started by start_program(), still running (or finished but not yet waited for).
struct RunningProgram {
    int pid = -1;
    int spawn_error = 0;
    std::string name, dir;
};
/// Starts a program as run_program() does, without waiting (to signal it while it runs).
RunningProgram start_program(const std::vector<std::string>& argv, const std::string& dir);
/// Waits for a started program and collects what it printed.
ProgramResult finish_program(const RunningProgram& program);
/// Whether an executable called `name` is on PATH (tests of optional tools skip without it).
bool on_path(const std::string& name);
bool contains(const std::string& text, const std::string& part);

/// Runs a shell command line (for pipelines and `cd`); returns its exit status and its stdout
/// and stderr together. Prefer run_program() where no shell is needed.
struct CommandResult {
    int status = -1;
    std::string output;
};
CommandResult run_command(const std::string& command_line);
/// The command line quoting of one argument for /bin/sh.
std::string shell_quote(const std::string& argument);

}  // namespace stochtex::test
