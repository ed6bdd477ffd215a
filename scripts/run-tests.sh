#!/usr/bin/env bash
# Installs the dependencies (Debian 12, as root; idempotent), builds everything and runs the
# test suite. This is the README's test command and what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
# --with-blender: the Blender scene tests (ctest -L scene) run, not skip (about 11 s to install).
bash scripts/install-deps.sh --with-blender
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
# The sanitizer lane (ASan + UBSan, libFuzzer; docs/limits.md): STOCHTEX_SANITIZER_LANE=OFF skips it.
if [ "${STOCHTEX_SANITIZER_LANE:-ON}" != OFF ]; then bash scripts/sanitizer-lane.sh build-asan; fi
