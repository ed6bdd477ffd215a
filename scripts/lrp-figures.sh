#!/usr/bin/env bash
# The pictures of docs/models/lrp.md: for each photo, a 384² crop of the photo, then `stex render`
# of lrp textures analysed from the whole photo with r = 0 (noise by example) and r > 0 (fixed-phase
# structure with random placement and turbulence), each 384² at the photo's scale, shown at 256².
# Usage: scripts/lrp-figures.sh [build-dir] (default: build); writes docs/images/lrp-*.jpg and
# prints the .stex sizes.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
stex="$build/cli/stex"
exemplars="$root/../shared/exemplars"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

figure() {  # figure NAME R
    local name="$1" r="$2"
    "$stex" analyze "$exemplars/$name.png" -o "$work/$name-0.stex" --model lrp --r 0 >/dev/null
    "$stex" analyze "$exemplars/$name.png" -o "$work/$name-r.stex" --model lrp --r "$r" >/dev/null
    echo "$name: r = 0 $(stat -c %s "$work/$name-0.stex") bytes, r = $r $(stat -c %s "$work/$name-r.stex") bytes"
    for variant in 0 r; do
        "$stex" render "$work/$name-$variant.stex" -o "$work/$name-$variant.png" --size 384x384 >/dev/null
    done
    oiiotool "$exemplars/$name.png" --cut 384x384+320+320 --resize 256x256 -o "$work/$name-photo.png"
    # (oiiotool's --paste takes the foreground first, then the background.)
    oiiotool "$work/$name-photo.png" --create 776x256 3 --fill:color=1,1,1 776x256 --paste +0+0 \
        "$work/$name-0.png" --resize 256x256 --swap --paste +260+0 \
        "$work/$name-r.png" --resize 256x256 --swap --paste +520+0 \
        --quality 88 -o "$root/docs/images/lrp-$name.jpg"
}

figure concrete 0.2
figure sand_dunes 0.2
figure gravel 0.3
figure karst_rock 0.3
