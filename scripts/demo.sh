#!/usr/bin/env bash
# The main job, end to end: analyse a shipped photo into a .stex, render it through the core
# (2D at the photo's scale, zoomed out, and a solid slice), compare it with the photo, and print
# where the images are. Installs what it needs (Debian 12, as root; idempotent).
#   usage: scripts/demo.sh [PHOTO] [OUTPUT_DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
photo="${1:-$root/data/exemplars/concrete_512.png}"
out="${2:-$root/out/demo}"
bash "$root/scripts/install-deps.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j"$(nproc)" --target stex >/dev/null
stex="$root/build/cli/stex"
mkdir -p "$out"
name="$(basename "${photo%.*}")"
"$stex" analyze "$photo" -o "$out/$name.stex"
"$stex" info "$out/$name.stex"
"$stex" render "$out/$name.stex" -o "$out/$name-core.exr"
"$stex" render "$out/$name.stex" -o "$out/$name-core.png"
"$stex" render "$out/$name.stex" -o "$out/$name-core-wide.png" --size 1024x512 --scale 4
"$stex" render "$out/$name.stex" -o "$out/$name-core-solid.png" --solid --z 0.25
"$stex" compare "$photo" "$out/$name.stex" -o "$out/$name-compare.png"
echo
echo "Demo images in $out:"
echo "  $name.stex             the procedural texture ($(stat -c %s "$out/$name.stex") bytes)"
echo "  $name-core.exr/.png    core render at the photo's pixel scale (EXR scene-linear, PNG sRGB)"
echo "  $name-core-wide.png    1024x512, zoomed out 4x (band-clamped anti-aliasing)"
echo "  $name-core-solid.png   a slice of the solid (3D) texture"
echo "  $name-compare.png      photo | synthesis, radial PSDs and histograms"
echo "(The OIIO plugin and POV-Ray routes arrive with issues 3 and 4.)"
