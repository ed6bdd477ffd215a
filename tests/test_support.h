// Shared helpers for the tests: where the exemplars are, temporary files.
#pragma once

#include <string>

namespace stochtex::test {

/// ../shared/exemplars/<name> if that folder exists, else "" (the caller GTEST_SKIPs).
std::string shared_exemplar(const std::string& name);
/// The small exemplar committed to the repository (data/exemplars/<name>).
std::string repo_exemplar(const std::string& name);
/// A fresh, empty directory for this test's files, private to this process.
std::string temp_dir(const std::string& test_name);

/// Runs a shell command line; returns its exit status and its stdout and stderr together.
struct CommandResult {
    int status = -1;
    std::string output;
};
CommandResult run_command(const std::string& command_line);
/// The command line quoting of one argument for /bin/sh.
std::string shell_quote(const std::string& argument);

}  // namespace stochtex::test
