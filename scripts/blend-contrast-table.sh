#!/usr/bin/env bash
# The blend-contrast table of docs/models/tiling.md ("Blend contrast"): each shared photo analysed
# once with `stex analyze PHOTO --model tiling` (the model's defaults), then the same file with
# parameters.blend_contrast set to each γ, so only the blend changes; `stex compare` at the
# photo's size (structure distance and its parts, spectra, W1, gradients, false colour), and the
# raster speed of `stex render --size 1024x1024 --threads 1` (Mpixel/s as it prints it, the
# median of three runs).
# Usage: scripts/blend-contrast-table.sh [build-dir] [contrasts…]   (default: build; 1 2 4 8)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
shift || true
contrasts=("${@:-1 2 4 8}")
read -r -a contrasts <<<"${contrasts[*]}"
stex="$build/cli/stex"
source "$root/scripts/compare-report.sh"  # $exemplars, $work, after, part
# The mean and the largest of a per-channel row ("log-PSD dB", "W1/sigma").
row_mean() { awk -v l="$1" 'index($0, l) == 1 { printf "%.2f", ($(NF - 2) + $(NF - 1) + $NF) / 3 }'; }
row_max() { awk -v l="$1" 'index($0, l) == 1 { m = $(NF - 2); if ($(NF - 1) > m) m = $(NF - 1); if ($NF > m) m = $NF; printf "%.3f", m }'; }
speed() {  # texture: median Mpixel/s of three 1024² single-thread renders
    for _ in 1 2 3; do
        "$stex" render "$1" -o "$work/r.exr" --size 1024x1024 --threads 1 | sed -n 's/.*, \([0-9.]*\) Mpixel\/s.*/\1/p'
    done | sort -g | sed -n 2p
}

echo "| photo | γ | structure distance | cross-scale | phase | radial log-PSD dB | 2D log-PSD dB | worst W1/σ | gradient magnitude W1 | gradient orientation W1 ° | false colour % | render Mpixel/s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for name in palm_bark karst_rock gravel sandy_rock rusted_metal concrete; do
    photo="$exemplars/$name.png"
    "$stex" analyze "$photo" -o "$work/t.stex" --model tiling >/dev/null
    for gamma in "${contrasts[@]}"; do
        python3 - "$work/t.stex" "$work/g.stex" "$gamma" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
if float(sys.argv[3]) != 1:
    d["parameters"]["blend_contrast"] = float(sys.argv[3])
json.dump(d, open(sys.argv[2], "w"), indent=2)
EOF
        "$stex" compare "$photo" "$work/g.stex" >"$work/compare.log" 2>/dev/null
        r="$work/compare.log"
        printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$gamma" \
            "$(after 'structure distance' <"$r")" "$(part cross-scale <"$r")" "$(part phase <"$r")" \
            "$(row_mean 'log-PSD dB' <"$r")" "$(after '2D log-PSD' <"$r")" "$(row_max 'W1/sigma' <"$r")" \
            "$(after 'gradient magnitude' <"$r")" "$(after 'gradient orientation' <"$r")" \
            "$(after 'false-colour rate' <"$r")" "$(speed "$work/g.stex")"
    done
done
