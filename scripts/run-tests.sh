#!/usr/bin/env bash
# Installs the dependencies (Debian 12, as root; idempotent), builds everything and runs the
# test suite. This is the README's test command and what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
# --with-blender: the Blender scene tests (ctest -L scene) run, not skip (about 11 s to install).
bash scripts/install-deps.sh --with-blender
# The lanes' downloads — the Debian 13 and sid folders (debootstrap, apt) and the bpy wheels (PyPI,
# whose 5.2 needs the Debian 13 folder's Python) — run in the background while the main build
# compiles: ≈ 9 min of network-bound work off the critical path. Each lane waits for its part; a
# part that failed is redone by its lane, which then fails with the reason. Logs: build/prepare-*.log.
mkdir -p build
trap 'wait' EXIT  # never leave a folder half-made, or mounted, behind a failed build
(bash scripts/debian13-lane.sh --prepare
 if [ "${STOCHTEX_SKIP_BPY:-0}" != 1 ]; then bash scripts/bpy-install.sh; fi) >build/prepare-debian13-bpy.log 2>&1 &
prepare_debian13_bpy=$!
bash scripts/sid-lane.sh --prepare >build/prepare-sid.log 2>&1 &
prepare_sid=$!
prepared() {  # prepared PID NAME: waits for a background preparation, says where a failure's log is
  wait "$1" || echo "run-tests: preparing $2 in the background failed (build/prepare-$2.log); its lane tries again"
}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
# The sanitizer lane (ASan + UBSan, libFuzzer; docs/limits.md): STOCHTEX_SANITIZER_LANE=OFF skips it.
if [ "${STOCHTEX_SANITIZER_LANE:-ON}" != OFF ]; then bash scripts/sanitizer-lane.sh build-asan; fi
# Debian 13 lane (issue 15): the plugin against OIIO 2.5 and the Blender scene tests with Blender
# 4.3 installing the add-on as an extension, in a debootstrap folder (scripts/debian13-lane.sh;
# its folder made above; ≈ 5 min: docs/testing.md). STOCHTEX_SKIP_DEBIAN13=1 skips it.
prepared "$prepare_debian13_bpy" debian13-bpy
bash scripts/debian13-lane.sh
# Debian sid lane (issue 31): g++ 16, OIIO 3.1, Blender 5.2 (scripts/sid-lane.sh). STOCHTEX_SKIP_SID=1 skips it.
prepared "$prepare_sid" sid
bash scripts/sid-lane.sh
# bpy lane (issue 34): the official Blender 4.5 LTS and 5.2 (PyPI's bpy, cached in /var/cache/stochtex/bpy) run the add-on's scene tests and Cycles' own OSL (scripts/bpy-lane.sh; docs/blender.md). STOCHTEX_SKIP_BPY=1 skips it.
bash scripts/bpy-lane.sh
