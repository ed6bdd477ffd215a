#!/usr/bin/env bash
# The batch on a real Slurm cluster (the one-node cluster of scripts/slurm-fixture.sh, which the
# CTest fixture starts): scripts/cluster/submit-batch.sh over a dozen photos made from the
# committed exemplar.
#   slurm_batch_test.sh matches-local CLUSTER_DIR WORK_DIR
#     the array job's merged report and every output are byte-identical to `stex batch --jobs 2`
#   slurm_batch_test.sh cancel-resume CLUSTER_DIR WORK_DIR
#     scancel mid-run, resubmit with --resume: everything completes, no partial (.tmp) file is
#     left, and no photo is done twice (each has exactly one "done" record in the shard logs)
# Environment: STEX (the stex program), STOCHTEX_SOURCE_DIR (the repository).
# A cluster the fixture could not start fails the test; STOCHTEX_SKIP_SLURM=1 skips it (exit 77).
set -euo pipefail
mode=${1:?usage: slurm_batch_test.sh matches-local|cancel-resume CLUSTER_DIR WORK_DIR}
cluster=${2:?} work=${3:?}
here=$(cd "$(dirname "$0")" && pwd)
repo=${STOCHTEX_SOURCE_DIR:-$(cd "$here/../.." && pwd)}
stex=${STEX:?STEX: the stex program}

if [ -e "$cluster/skipped" ]; then echo "SKIPPED: STOCHTEX_SKIP_SLURM=1"; exit 77; fi
[ -f "$cluster/slurm.conf" ] || { echo "FAIL: no cluster at $cluster (the SlurmClusterStart fixture failed: see its output)"; exit 1; }
export SLURM_CONF=$cluster/slurm.conf
rm -rf "$work"; mkdir -p "$work"
bash "$here/make_photos.sh" "$repo/data/exemplars/concrete_512.png" "$work/photos" 12
# Cheap per-photo work with every kind of output: --model auto's choice (wavelet, gabor, lrp,
# tiling fitted and scored), the gallery's crops, a compare figure.
options=(--preview 64 --compare)

fail() { echo "FAIL: $*"; for log in "$work"/*/slurm/*.log; do [ -f "$log" ] && { echo "--- $log"; tail -n 5 "$log"; }; done; exit 1; }

# Waits until none of the given jobs is pending or running (at most $2 s).
wait_for_jobs() {
  local jobs=$1 limit=$2 start=$SECONDS
  while [ -n "$(squeue -h -j "$jobs" -o %i 2>/dev/null)" ]; do
    [ $((SECONDS - start)) -lt "$limit" ] || fail "jobs $jobs still queued after $limit s: $(squeue -j "$jobs")"
    sleep 0.5
  done
}

# The records of one photo-name that say done, over every shard log.
done_records() { cat "$1"/reports/*.jsonl 2>/dev/null | grep -c '"status":"done"' || true; }

no_partial_files() {
  local partial
  partial=$(find "$1" -name '*.tmp')
  [ -z "$partial" ] || fail "partial files left in $1: $partial"
}

every_photo_done_once() {
  local folder=$1 name count
  for photo in "$work"/photos/*.png; do
    name=$(basename "$photo" .png)
    count=$(cat "$folder"/reports/*.jsonl | grep -c "\"name\":\"$name\",.*\"status\":\"done\"" || true)
    [ "$count" = 1 ] || fail "$name has $count done records in $folder/reports (expected exactly 1)"
    [ -s "$folder/$name/$name.stex" ] || fail "$folder/$name/$name.stex missing"
  done
  grep -q '"done": 12' "$folder/report.json" || fail "$folder/report.json does not say 12 done: $(head -n 8 "$folder/report.json")"
}

case "$mode" in
matches-local)
  start=$SECONDS
  "$stex" batch "$work/photos" -o "$work/local" --jobs 2 "${options[@]}" > "$work/local.txt" || fail "local batch: $(cat "$work/local.txt")"
  local_seconds=$((SECONDS - start))
  start=$SECONDS
  read -r array merge < <(STEX=$stex bash "$repo/scripts/cluster/submit-batch.sh" --tasks 4 "$work/photos" "$work/slurm" -- "${options[@]}")
  echo "submitted array job $array (4 tasks) and merge job $merge"
  wait_for_jobs "$array,$merge" 600
  echo "local --jobs 2: ${local_seconds} s; Slurm, 4 tasks + merge: $((SECONDS - start)) s"
  grep -q '^merged' "$work"/slurm/slurm/merge-*.log || fail "the merge job did not merge: $(cat "$work"/slurm/slurm/merge-*.log)"
  every_photo_done_once "$work/slurm"
  no_partial_files "$work/slurm"
  # Every output of the two runs, byte for byte: the .stex files, images, report.json,
  # report.csv, index.html and batch-plan.json. Not compared: the shard logs and timings.csv
  # (seconds, and the shard a photo ran in) and the Slurm logs.
  compared=0
  while IFS= read -r file; do
    cmp -s "$work/local/$file" "$work/slurm/$file" || fail "$file differs between the local and the Slurm run"
    compared=$((compared + 1))
  done < <(cd "$work/local" && find . -type f ! -path './reports/*' ! -name timings.csv | sort)
  slurm_files=$(cd "$work/slurm" && find . -type f ! -path './reports/*' ! -path './slurm/*' ! -name timings.csv | wc -l)
  [ "$slurm_files" = "$compared" ] || fail "the Slurm run has $slurm_files outputs, the local one $compared"
  echo "PASS: $compared files byte-identical between stex batch --jobs 2 and the 4-task Slurm array job"
  ;;
cancel-resume)
  # Bigger photos' worth of work per task (a bake each), so that the cancel lands mid-run.
  options+=(--bake 256)
  read -r array merge < <(STEX=$stex bash "$repo/scripts/cluster/submit-batch.sh" --tasks 3 "$work/photos" "$work/out" -- "${options[@]}")
  echo "submitted array job $array (3 tasks) and merge job $merge"
  start=$SECONDS
  until [ "$(done_records "$work/out")" -ge 2 ]; do
    [ $((SECONDS - start)) -lt 300 ] || fail "no two photos done within 300 s"
    sleep 0.2
  done
  scancel "$array" "$merge"
  wait_for_jobs "$array,$merge" 120
  done_at_cancel=$(done_records "$work/out")
  echo "cancelled after $done_at_cancel of 12 photos done"
  [ "$done_at_cancel" -lt 12 ] || fail "the array finished before the cancel: nothing was interrupted"
  no_partial_files "$work/out"
  [ ! -e "$work/out/report.json" ] || fail "the cancelled merge job ran"
  read -r array merge < <(STEX=$stex bash "$repo/scripts/cluster/submit-batch.sh" --resume --tasks 3 "$work/photos" "$work/out" -- "${options[@]}")
  echo "resubmitted with --resume: array job $array, merge job $merge"
  wait_for_jobs "$array,$merge" 600
  grep -h '^batch\|skipped' "$work"/out/slurm/task-"$array"_*.log || true
  every_photo_done_once "$work/out"
  no_partial_files "$work/out"
  cat "$work"/out/slurm/merge-"$merge".log
  echo "PASS: cancelled at $done_at_cancel/12, resumed: 12 done, each once, no partial file"
  ;;
*) echo "unknown mode $mode"; exit 2 ;;
esac
