#!/usr/bin/env bash
# The exemplar table of docs/metrics.md: every shared photo (but the height map) analysed by each
# model with its defaults, then `stex compare` at the photo's size; one Markdown row per photo ×
# model with the radial and 2D log-PSD distances (and the 2D one's angular part), the gradient distances, the false-colour rate,
# W1/σ and the seconds analyse and compare took.
# Usage: scripts/metrics-table.sh [build-dir] [models…] (default: build; the registry's models with analysis).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
shift || true
stex="$build/cli/stex"
source "$root/scripts/registry-models.sh"
models=("$@")
[ ${#models[@]} -gt 0 ] || models=($(registry_models "$stex" analysis))
exemplars="$root/../shared/exemplars"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

mean3() { awk -v l="$1" 'index($0, l) == 1 { n = split(substr($0, length(l) + 1), v, " "); printf "%.2f", (v[1] + v[2] + v[3]) / 3 }'; }
after() { awk -v l="$1" 'index($0, l) == 1 { sub(/.*: /, ""); print $1 }'; }
angular() { awk '/^2D log-PSD/ { sub(/.*\(orientation\) /, ""); print $1 }'; }

echo "| photo | model | radial log-PSD dB (mean RGB) | 2D log-PSD dB | of which angular dB | gradient orientation W1 ° | gradient magnitude W1 | false colour % | W1/σ (mean RGB) | analyse s | compare s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for photo in "$exemplars"/*.png; do
    name="$(basename "$photo" .png)"
    [ "$name" = rock_height ] && continue  # a height map, not a photo
    for model in "${models[@]}"; do
        t0=$(date +%s.%N)
        if ! "$stex" analyze "$photo" -o "$work/t.stex" --model "$model" >"$work/analyze.log" 2>&1; then
            echo "| $name | $model | analyse failed: $(tail -1 "$work/analyze.log") |"
            continue
        fi
        t1=$(date +%s.%N)
        "$stex" compare "$photo" "$work/t.stex" >"$work/compare.log" 2>/dev/null
        t2=$(date +%s.%N)
        r="$work/compare.log"
        printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %.1f | %.1f |\n' "$name" "$model" \
            "$(mean3 'log-PSD dB' <"$r")" "$(after '2D log-PSD' <"$r")" "$(angular <"$r")" "$(after 'gradient orientation' <"$r")" \
            "$(after 'gradient magnitude' <"$r")" "$(after 'false-colour' <"$r")" "$(mean3 'W1/sigma' <"$r")" \
            "$(echo "$t1 - $t0" | bc)" "$(echo "$t2 - $t1" | bc)"
    done
done
