#!/usr/bin/env bash
# The sanitizer lane of the test command (scripts/run-tests.sh; docs/limits.md, "Fuzzing and
# sanitizers"): one clang build, -DSTOCHTEX_ASAN=ON -DSTOCHTEX_FUZZERS=ON, of only what its tests
# need (the core, stex, the plugin, the asan label's test programs and the fuzz harnesses), then
# `ctest -L 'asan|fuzz'`: the parser, CLI-robustness and plugin tests under AddressSanitizer +
# UndefinedBehaviorSanitizer, and each libFuzzer harness for a fixed count from fresh seeds.
#   usage: scripts/sanitizer-lane.sh [BUILD_DIR]    (default build-asan; needs clang-14)
# Running `ctest -L asan` by hand: export the three *SAN_OPTIONS below first.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-asan}"
jobs="$(nproc)"
start=$(date +%s)
# Another clang (Debian 13 has clang-19): STOCHTEX_SANITIZER_CXX=clang++-19 (its C compiler is
# the same name without "++").
cxx="${STOCHTEX_SANITIZER_CXX:-clang++-14}"
CC="${cxx/++/}" CXX="$cxx" cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSTOCHTEX_ASAN=ON -DSTOCHTEX_FUZZERS=ON \
  -DSTOCHTEX_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j"$jobs" --target stex stex_imageio stochtex_fuzzers \
  stex_file_test hardening_test cli_test plugin_test
built=$(date +%s)
# Errors are fatal; leaks inside the uninstrumented programs the tests start (oiiotool, python3,
# which preload the runtime) are theirs (lsan.supp). OIIO 2.4's TextureSystem::destroy() deletes
# its implementation through the 1-byte interface type, which ASan reports as
# new-delete-type-mismatch inside libOpenImageIO: that check is off.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:new_delete_type_mismatch=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp"
ctest --test-dir "$build" -L 'asan|fuzz' --output-on-failure -j"$jobs"
echo "sanitizer-lane: build $((built - start)) s, tests $(( $(date +%s) - built )) s"
