#!/usr/bin/env bash
# The bpy lane of the test command (scripts/run-tests.sh; issue 34): the official Blender builds,
# 4.5 LTS and 5.2, as PyPI's `bpy` modules (scripts/bpy-install.sh: pinned, cached under
# /var/cache/stochtex), run the add-on's scene tests (tests/blender_scene_test.cpp: extension
# install, analyse, bake, material, Cycles render against the core; its OSL route) and the OSL
# shaders through Cycles' own OSL (tests/cycles_osl_test.cpp). CTest label "bpy"; docs/blender.md.
#
# Uses the main lane's build folder (build/): configures it with STOCHTEX_BPY_TESTS=ON (which
# stays on: a later plain `ctest` there runs these tests too) and builds only what the tests need.
# Fails when PyPI cannot be reached and the cache is empty. STOCHTEX_SKIP_BPY=1 skips the lane.
set -euo pipefail

if [ "${STOCHTEX_SKIP_BPY:-0}" = "1" ]; then
  echo "bpy-lane: skipped (STOCHTEX_SKIP_BPY=1)"
  exit 0
fi
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/bpy-install.sh
echo "bpy-lane: installed or reused after $((SECONDS - start)) s"
cmake -S . -B build -DSTOCHTEX_BPY_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target stex stochtex_addon blender_scene_test cycles_osl_test >/dev/null
status=0
ctest --test-dir build --output-on-failure -j"$(nproc)" -L bpy || status=$?
echo "bpy-lane: $([ $status -eq 0 ] && echo passed || echo FAILED) in $((SECONDS - start)) s"
exit $status
