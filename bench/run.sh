#!/usr/bin/env bash
# Builds wavelet_bench (Release) and runs it with 5 repetitions, printing medians only.
# Usage: bench/run.sh [build-dir] [extra benchmark flags...]   (default build dir: build-bench)
# STOCHTEX_BENCH=lrp_bench bench/run.sh runs another benchmark program the same way.
# Takes well under a minute on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build-bench}"
if [ $# -gt 0 ]; then shift; fi
lscpu | grep 'Model name' || true
echo "cores: $(nproc)"
cmake -S "$root" -B "$build" >/dev/null
program="${STOCHTEX_BENCH:-wavelet_bench}"
cmake --build "$build" --target "$program" -j"$(nproc)" >/dev/null
"$build/bench/$program" \
  --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_min_time=0.25 "$@"
