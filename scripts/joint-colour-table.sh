#!/usr/bin/env bash
# docs/models/README.md's "Joint colour" table: for each shared colour photo (its top-left 512²)
# and each model with joint colour, `stex analyze --joint-colour off|on` then `stex compare`:
# false-colour rate, the worst channel's W1/σ and the channels' mean radial log-PSD distance.
# Prints Markdown rows.
#   usage: scripts/joint-colour-table.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
stex="$build/cli/stex"
source "$root/scripts/registry-models.sh"
models=($(registry_models "$stex" analysis joint_colour))
exemplars="$root/../shared/exemplars"
[ -d "$exemplars" ] || { echo "no $exemplars" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# One line of figures from `stex compare`: false colour %, worst W1/σ, mean log-PSD dB.
figures() {
    "$stex" compare "$1" "$2" | awk '
        /^W1\/sigma/ { w = $2; if ($3 > w) w = $3; if ($4 > w) w = $4 }
        /^log-PSD dB/ { psd = ($3 + $4 + $5) / 3 }
        /^false-colour rate/ { fc = $(NF - 1) }
        END { printf "%.2f %.3f %.2f\n", fc, w, psd }'
}
echo "| photo | model | false colour off → on | W1/σ off → on | log-PSD dB off → on |"
echo "|---|---|---|---|---|"
for name in gravel karst_rock palm_bark sandy_rock grass rusted_metal concrete dirt sand_dunes; do
    oiiotool "$exemplars/$name.png" --cut 512x512+0+0 -o "$work/$name.png"
    for model in "${models[@]}"; do
        for joint in off on; do
            "$stex" analyze "$work/$name.png" -o "$work/$name-$model-$joint.stex" --model "$model" \
                --joint-colour "$joint" >/dev/null
        done
        read -r fc0 w0 p0 < <(figures "$work/$name.png" "$work/$name-$model-off.stex")
        read -r fc1 w1 p1 < <(figures "$work/$name.png" "$work/$name-$model-on.stex")
        echo "| $name | $model | $fc0 % → $fc1 % | $w0 → $w1 | $p0 → $p1 |"
    done
done
