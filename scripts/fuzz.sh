#!/usr/bin/env bash
# Runs the libFuzzer harnesses of fuzz/ (docs/limits.md, "Fuzzing and sanitizers") and prints,
# for each, the executions, executions per second, corpus size and findings.
#   usage: scripts/fuzz.sh [--build DIR] [--time SECONDS | --runs N] [--seed S] [--seeds-only] [HARNESS...]
#   HARNESS: stex light_set image ptm_coefficients plugin_open (default: all, one after another)
# --build DIR: a build configured with -DSTOCHTEX_FUZZERS=ON (and built); without it the
#   script configures and builds build-fuzz with clang-14 (ASan + UBSan on, as the sanitizer lane).
# --time: seconds per harness (default 60); --runs: executions per harness instead. With --time
#   the corpus grows in DIR/fuzz/corpus/<harness> and later runs continue from it; with --runs
#   (CI) it is a fresh temporary folder, so that a run depends only on the seeds and --seed.
# Seeds are made at run time from the project's own files (DIR/fuzz/seeds; nothing is stored in
# the repository): the committed exemplar's crops as PNG/JPEG/EXR, a .stex of every model
# analysed from it, a ptm fitted to a relief's lights with its .lp, JSON light list and
# coefficient EXR, and the .stex files behind plugin open hints. The dictionary (DIR/fuzz/stex.dict)
# is every JSON key of those files plus the plugin's hint names.
# A finding is a file in DIR/fuzz/findings/<harness>/ (crash-*, leak-*, timeout-*, oom-*; with
# --runs DIR/fuzz/ci/findings/<harness>/), emptied when the harness starts;
# reproduce it with DIR/fuzz/<harness>_fuzzer FILE. Exit status 1 if any harness found one.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="" seconds=60 runs="" seed=0 seeds_only=0 harnesses=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --time) seconds="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --seeds-only) seeds_only=1; shift ;;
    -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) harnesses+=("$1"); shift ;;
  esac
done
[ ${#harnesses[@]} -gt 0 ] || harnesses=(stex light_set image ptm_coefficients plugin_open)
if [ -z "$build" ]; then
  build="$root/build-fuzz"
  CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSTOCHTEX_ASAN=ON \
    -DSTOCHTEX_FUZZERS=ON -DSTOCHTEX_BUILD_TESTS=OFF -DSTOCHTEX_BUILD_BENCH=OFF >/dev/null
  cmake --build "$build" --target stex stochtex_fuzzers -j"$(nproc)"
fi
build="$(cd "$build" && pwd)"
stex="$build/cli/stex"
seeds="$build/fuzz/seeds"
# Seeds are the project's files, not fuzzing targets: leaks in the tools that make them are not
# this script's findings (the asan label checks them).
export ASAN_OPTIONS="detect_leaks=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"

make_seeds() {
  local work="$seeds/work"
  rm -rf "$seeds"; mkdir -p "$work" "$seeds"/{stex,light_set,image,ptm_coefficients,plugin_open}
  local photo="$root/data/exemplars/concrete_512.png"
  oiiotool "$photo" --cut 64x64+100+100 -o "$work/crop64.png"
  oiiotool "$photo" --cut 16x16+40+40 -o "$work/crop16.png"
  oiiotool "$work/crop16.png" -o "$work/crop16.jpg"
  oiiotool "$work/crop16.png" -d half -o "$work/crop16.exr"
  { printf '\0'; cat "$work/crop16.png"; } >"$seeds/image/png"
  { printf '\1'; cat "$work/crop16.jpg"; } >"$seeds/image/jpg"
  { printf '\2'; cat "$work/crop16.exr"; } >"$seeds/image/exr"
  # Every model's .stex (small options: seeds should be fast to read and render).
  "$stex" analyze "$work/crop64.png" -o "$seeds/stex/wavelet.stex" --model wavelet --bands 4 >/dev/null
  "$stex" analyze "$work/crop64.png" -o "$seeds/stex/joint.stex" --model wavelet --bands 4 --joint-colour on >/dev/null
  "$stex" analyze "$work/crop64.png" -o "$seeds/stex/gabor.stex" --model gabor --bands 2 --impulses 4 >/dev/null
  "$stex" analyze "$work/crop64.png" -o "$seeds/stex/lrp.stex" --model lrp --J 8 --L 2 >/dev/null
  "$stex" analyze "$work/crop64.png" -o "$seeds/stex/tiling.stex" --model tiling >/dev/null
  "$stex" tiling phasor -o "$seeds/stex/phasor.stex" --exemplar-size 16 >/dev/null
  oiiotool --pattern noise:type=uniform:min=0:max=1:seed=3 24x24 1 --blur 5x5 -d uint16 -o "$work/height.png"
  "$stex" ptm relief "$work/height.png" -o "$work/relief" --lights 8 >/dev/null
  "$stex" ptm fit "$work/relief/lights.lp" -o "$seeds/stex/ptm.stex" >/dev/null
  { printf '\0'; cat "$seeds/stex/ptm.ptm.exr"; } >"$seeds/ptm_coefficients/lrgb"
  mv "$seeds/stex/ptm.ptm.exr" "$seeds/ptm.ptm.exr"  # beside fuzz.stex, which the harnesses "read"
  { printf '\0'; cat "$work/relief/lights.lp"; } >"$seeds/light_set/lights.lp"
  { printf '\1'; awk 'NR > 1 { printf "%s{\"image\": \"%s\", \"direction\": [%s, %s, %s]}", (NR > 2 ? ", " : "{\"lights\": ["), $1, $2, $3, $4 }
                      END { print "]}" }' "$work/relief/lights.lp"; } >"$seeds/light_set/lights.json"
  local hints=("" "stex:width=64\nstex:height=48\nstex:tile_width=16\nstex:tile_height=16\n"
               "stex:channels=Y\nstex:scale=2.5\n" "stex:channels=RGBA\nstex:seed=7\nstex:light=0.3,0.2,0.93\n")
  local t i
  # The plugin's seeds: the models without an embedded exemplar (tiling's takes seconds to
  # prepare under ASan; its file is the stex harness's).
  for t in "$seeds"/stex/{wavelet,gabor,lrp,ptm}.stex; do
    for i in "${!hints[@]}"; do
      { printf '%b' "${hints[$i]}"; printf -- '---\n'; cat "$t"; } >"$seeds/plugin_open/$(basename "$t" .stex)-$i"
    done
  done
  # The dictionary: every key of the seed files, the light lists' keys, the hint names.
  { cat "$seeds"/stex/*.stex | grep -o '"[A-Za-z_][A-Za-z0-9_]*":' | tr -d ':'
    printf '"%s"\n' lights image direction
    printf '"stex:%s="\n' width height tile_width tile_height scale channels seed light
  } | sort -u | awk '{ gsub(/"/, "\\\""); printf "\"%s\"\n", $0 }' >"$build/fuzz/stex.dict"
  rm -rf "$work"
  echo "fuzz.sh: seeds in $seeds ($(find "$seeds" -type f | wc -l) files), dictionary $build/fuzz/stex.dict ($(wc -l <"$build/fuzz/stex.dict") keys)"
}

[ -f "$build/fuzz/stex.dict" ] && [ -d "$seeds/stex" ] && [ $seeds_only -eq 0 ] || make_seeds
[ $seeds_only -eq 1 ] && exit 0

export STOCHTEX_FUZZ_DATA="$seeds"
status=0
summary="$build/fuzz/summary${runs:+-ci}.txt"
printf '%-18s %12s %10s %8s %9s  %s\n' harness execs "exec/s" corpus findings "time (s)" >"$summary"
for h in "${harnesses[@]}"; do
  program="$build/fuzz/${h}_fuzzer"
  [ -x "$program" ] || { echo "fuzz.sh: $program is not built" >&2; exit 2; }
  # CI runs (--runs) keep their logs and findings apart from long runs of the same build.
  out="$build/fuzz"; [ -n "$runs" ] && out="$build/fuzz/ci"
  findings="$out/findings/$h"; rm -rf "$findings"; mkdir -p "$findings"
  dict=()
  case "$h" in stex|light_set|plugin_open) dict=(-dict="$build/fuzz/stex.dict") ;; esac
  if [ -n "$runs" ]; then
    # A fixed count, and a time cap so that a slow machine bounds the test command's time.
    corpus="$(mktemp -d)"; limit=(-runs="$runs" -max_total_time=30)
  else
    corpus="$build/fuzz/corpus/$h"; mkdir -p "$corpus"; limit=(-max_total_time="$seconds")
  fi
  log="$out/$h.log"
  # Leaks inside the libraries we call are suppressed by name (fuzz/lsan.supp says why). OIIO's
  # PNG reader's leak is matched by its OIIO frame with full stacks and by its string allocation
  # with fast ones (libstdc++ has no frame pointers, so the fast unwinder stops there): the image
  # harness unwinds slowly (full stacks in its reports), the others fast.
  sanitizer_env=(LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp")
  [ "$h" = image ] && sanitizer_env+=(ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0")
  start=$(date +%s)
  set +e
  (cd "$findings" && env "${sanitizer_env[@]}" "$program" "${limit[@]}" -seed="$seed" "${dict[@]}" -max_len=65536 -timeout=120 -rss_limit_mb=3072 \
     -print_final_stats=1 -artifact_prefix="$findings/" "$corpus" "$seeds/$h") >"$log" 2>&1
  rc=$?
  set -e
  elapsed=$(( $(date +%s) - start ))
  execs=$(awk '/stat::number_of_executed_units/ {print $NF}' "$log" | tail -1)
  rate=$(awk '/stat::average_exec_per_sec/ {print $NF}' "$log" | tail -1)
  # Findings: crashes, leaks, timeouts, out-of-memory (slow-unit-* files are only reports).
  found=$(find "$findings" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  size=$(find "$corpus" -type f | wc -l)
  printf '%-18s %12s %10s %8s %9s  %s\n' "$h" "${execs:-?}" "${rate:-?}" "$size" "$found" "$elapsed" | tee -a "$summary"
  [ -n "$runs" ] && rm -rf "$corpus"
  if [ $rc -ne 0 ] || [ "$found" -gt 0 ]; then
    status=1
    echo "fuzz.sh: $h: exit $rc, findings in $findings (log $log):" >&2
    grep -E "ERROR|SUMMARY|runtime error|==[0-9]+==|Test unit written" "$log" | head -20 >&2 || true
  fi
done
exit $status
