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
# Debian 13 lane (issue 15): the plugin against OIIO 2.5 and the Blender scene tests with Blender
# 4.3 installing the add-on as an extension, in a debootstrap folder (scripts/debian13-lane.sh;
# ≈ 8–9 min from nothing on 2 idle cores, ≈ 2 min when the folder is reused; README). STOCHTEX_SKIP_DEBIAN13=1 skips it.
bash scripts/debian13-lane.sh
# Debian sid lane (issue 31): g++ 16, OIIO 3.1, Blender 5.2 (scripts/sid-lane.sh). STOCHTEX_SKIP_SID=1 skips it.
bash scripts/sid-lane.sh
# bpy lane (issue 34): the official Blender 4.5 LTS and 5.2 (PyPI's bpy, cached in /var/cache/stochtex/bpy) run the add-on's scene tests and Cycles' own OSL (scripts/bpy-lane.sh; docs/blender.md). STOCHTEX_SKIP_BPY=1 skips it.
bash scripts/bpy-lane.sh
