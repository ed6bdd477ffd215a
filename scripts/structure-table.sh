#!/usr/bin/env bash
# The structure table of docs/metrics.md: the shared photos with the most structure analysed with
# `--model auto` (the CLI's default: today's automatic choice) and with each model's defaults,
# then `stex compare` at the photo's size; one Markdown row per photo × model with the structure
# distance and its five parts, and the 2D log-PSD distance and gradient magnitude W1 beside them.
# Usage: scripts/structure-table.sh [build-dir] [models…] (default: build; auto, then the registry's
# models with analysis).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
shift || true
stex="$build/cli/stex"
source "$root/scripts/registry-models.sh"
models=("$@")
[ ${#models[@]} -gt 0 ] || models=(auto $(registry_models "$stex" analysis))
source "$root/scripts/compare-report.sh"  # $exemplars, $work, after, part

echo "| photo | model | structure distance | marginals | auto-correlation | cross-orientation | cross-scale | phase | 2D log-PSD dB | gradient magnitude W1 |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for name in palm_bark karst_rock gravel sandy_rock; do
    photo="$exemplars/$name.png"
    for model in "${models[@]}"; do
        if ! "$stex" analyze "$photo" -o "$work/t.stex" --model "$model" >"$work/analyze.log" 2>&1; then
            echo "| $name | $model | analyse failed: $(tail -1 "$work/analyze.log") |"
            continue
        fi
        label="$model"
        # auto: name the model it chose ("wrote t.stex (tiling, 208312 bytes) from …").
        [ "$model" = auto ] && label="auto ($(sed -n 's/^wrote .* (\([a-z]*\), .*/\1/p' "$work/analyze.log" | tail -1))"
        "$stex" compare "$photo" "$work/t.stex" >"$work/compare.log" 2>/dev/null
        r="$work/compare.log"
        printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$label" "$(after 'structure distance' <"$r")" \
            "$(part marginals <"$r")" "$(part auto-correlation <"$r")" "$(part cross-orientation <"$r")" \
            "$(part cross-scale <"$r")" "$(part phase <"$r")" "$(after '2D log-PSD' <"$r")" "$(after 'gradient magnitude' <"$r")"
    done
done
