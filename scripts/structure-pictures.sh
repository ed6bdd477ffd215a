#!/usr/bin/env bash
# The structure pictures of docs/models/{wavelet,gabor,lrp}.md (issue 33): for each model, a strip
# with one row per structured photo (palm_bark, karst_rock, gravel, sandy_rock) and three columns:
# the photo's centred 192² crop | `stex render` of `stex analyze PHOTO --model MODEL` (the model's
# defaults) | the same with `--model tiling` (tiling's defaults), both 192² at the photo's pixel
# scale (--scale 1, the render's top-left corner). Writes OUT/structure-{wavelet,gabor,lrp}.jpg.
# Takes about 30 s on 2 shared cores (16 analyses and 16 renders of 192²).
# Usage: scripts/structure-pictures.sh [stex] [out-dir] (default: build/cli/stex, docs/images).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
stex="${1:-$root/build/cli/stex}"
out="${2:-$root/docs/images}"
exemplars="$root/../shared/exemplars"
[ -d "$exemplars" ] || { echo "$(basename "$0"): $exemplars is missing (the shared photos)" >&2; exit 1; }
mkdir -p "$out"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

photos=(palm_bark karst_rock gravel sandy_rock)
size=192 gap=4

for name in "${photos[@]}"; do
    photo="$exemplars/$name.png"
    # The photo's centred crop (palm bark is 512×2048).
    read -r w h < <(oiiotool --info -v "$photo" | sed -n 's/.* : *\([0-9]*\) x *\([0-9]*\),.*/\1 \2/p' | head -1)
    oiiotool "$photo" --cut "${size}x${size}+$(( (w - size) / 2 ))+$(( (h - size) / 2 ))" \
        --ch R,G,B -o "$work/$name-photo.png"
    for model in wavelet gabor lrp tiling; do
        "$stex" analyze "$photo" -o "$work/$name-$model.stex" --model "$model" >/dev/null
        "$stex" render "$work/$name-$model.stex" -o "$work/$name-$model.png" --size "${size}x${size}" >/dev/null
    done
done

cols=3 rows=${#photos[@]}
W=$(( cols * size + (cols - 1) * gap )) H=$(( rows * size + (rows - 1) * gap ))
for model in wavelet gabor lrp; do
    # (oiiotool's --paste takes the foreground first, then the background.)
    args=(--create "${W}x${H}" 3 --fill:color=1,1,1 "${W}x${H}")
    for i in "${!photos[@]}"; do
        y=$(( i * (size + gap) ))
        for j in 0 1 2; do
            case $j in 0) f=photo ;; 1) f=$model ;; 2) f=tiling ;; esac
            args+=("$work/${photos[$i]}-$f.png" --ch R,G,B --swap --paste "+$(( j * (size + gap) ))+$y")
        done
    done
    oiiotool "${args[@]}" --quality 85 -o "$out/structure-$model.jpg"
    echo "$out/structure-$model.jpg: $(stat -c %s "$out/structure-$model.jpg") bytes"
done
