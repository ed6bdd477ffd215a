#!/usr/bin/env bash
# Converts a texture library on a Slurm cluster: an array job of TASKS tasks, each running
# `stex batch --shard auto` (its share: the photos whose stable index mod TASKS is its task id),
# then a merge job, dependent on the whole array, running `stex batch-report` (report.json,
# report.csv, index.html). docs/cluster.md.
#
#   scripts/cluster/submit-batch.sh [options] SOURCE OUTPUT [-- stex batch options...]
#     --tasks N            array tasks (default 8)
#     --cpus-per-task C    cores per task, given to stex batch as --threads (default 1)
#     --resume             skip the photos already done in OUTPUT (a resubmission after a crash
#                          or a cancel: each finished photo has a record, so nothing is done twice)
#     --sbatch ARG         an extra sbatch argument for both jobs (repeatable: --sbatch --partition=cpu)
#   STEX: the stex program the tasks run (default: stex on PATH, as the submitting shell sees it).
# Prints "ARRAY_JOB_ID MERGE_JOB_ID". The tasks' logs go to OUTPUT/slurm/.
set -euo pipefail
tasks=8 cpus=1 resume=() extra=()
usage() { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --tasks) tasks=${2:?}; shift 2 ;;
    --cpus-per-task) cpus=${2:?}; shift 2 ;;
    --resume) resume=(--resume); shift ;;
    --sbatch) extra+=("${2:?}"); shift 2 ;;
    -h|--help) usage ;;
    --) break ;;
    -*) echo "submit-batch.sh: unknown option $1" >&2; usage ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || usage
source=$(realpath -- "$1") output=$(realpath -m -- "$2")
shift 2
[ "${1:-}" = -- ] && shift
case "$tasks" in ''|*[!0-9]*|0) echo "submit-batch.sh: --tasks: expected a whole number >= 1, got '$tasks'" >&2; exit 2 ;; esac
stex=$(command -v "${STEX:-stex}") || { echo "submit-batch.sh: ${STEX:-stex} not found (set STEX)" >&2; exit 2; }
[ -e "$source" ] || { echo "submit-batch.sh: $source: no such folder or manifest" >&2; exit 2; }
mkdir -p "$output/slurm"

# The job scripts, with every argument quoted for the shell that runs them.
quoted() { printf ' %q' "$@"; }
task_command="exec$(quoted "$stex" batch "$source" -o "$output" --shard auto "${resume[@]}") --threads \"\${SLURM_CPUS_PER_TASK:-1}\"$(quoted "$@")"
merge_command="exec$(quoted "$stex" batch-report "$output")"

array=$(sbatch --parsable --job-name=stex-batch --array="0-$((tasks - 1))" --cpus-per-task="$cpus" \
  --output="$output/slurm/task-%A_%a.log" "${extra[@]}" <<JOB
#!/bin/sh
$task_command
JOB
)
array=${array%%;*}
# afterany: the merge runs however the tasks ended — a task whose photos failed exits non-zero,
# and the report is where those failures are read. A cancelled array is cancelled with the merge
# (scancel both), and a resubmission with --resume submits a new merge.
merge=$(sbatch --parsable --job-name=stex-batch-merge --dependency="afterany:$array" --kill-on-invalid-dep=yes \
  --output="$output/slurm/merge-%j.log" "${extra[@]}" <<JOB
#!/bin/sh
$merge_command
JOB
)
echo "${array} ${merge%%;*}"
