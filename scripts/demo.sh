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
cmake --build "$root/build" -j"$(nproc)" --target stex stex_imageio >/dev/null
stex="$root/build/cli/stex"
mkdir -p "$out"
name="$(basename "${photo%.*}")"
# The model is chosen for the photo (--model auto, the default): the score table is printed.
"$stex" analyze "$photo" -o "$out/$name.stex"
"$stex" info "$out/$name.stex"
# What the chosen model can do (the registry's capabilities) decides the solid and POV steps.
can() {  # capability
  "$stex" models --json | python3 -c 'import json, sys
model = json.load(open(sys.argv[1]))["model"]
sys.exit(0 if next(m for m in json.load(sys.stdin)["models"] if m["name"] == model)["capabilities"][sys.argv[2]] else 1)' \
    "$out/$name.stex" "$1"
}
"$stex" render "$out/$name.stex" -o "$out/$name-core.exr"
"$stex" render "$out/$name.stex" -o "$out/$name-core.png"
"$stex" render "$out/$name.stex" -o "$out/$name-core-wide.png" --size 1024x512 --scale 4
if can solid; then "$stex" render "$out/$name.stex" -o "$out/$name-core-solid.png" --solid --z 0.25; fi
"$stex" compare "$photo" "$out/$name.stex" -o "$out/$name-compare.png"
# The OIIO plugin (docs/oiio-plugin.md): OIIO's own oiiotool reads the .stex as a MIP-mapped
# image; write its level 0 at 1024² and its level 3 (128², each texel filtered by the model).
export OIIO_LIBRARY_PATH="$root/build/plugins"
oiiotool --iconfig stex:width 1024 --iconfig stex:height 1024 "$out/$name.stex" -o "$out/$name-oiio.exr"
oiiotool "$out/$name-oiio.exr" --colorconvert linear sRGB -o "$out/$name-oiio.png"
oiiotool --iconfig stex:width 1024 --iconfig stex:height 1024 "$out/$name.stex" --selectmip 3 \
  --colorconvert linear sRGB -o "$out/$name-oiio-mip3.png"
# POV-Ray (docs/pov.md): the texture as a procedural include and as a baked one, each on the
# measurement plane (one texture unit, 512², linear EXR and sRGB PNG), then both in the showcase.
pov_render() {  # scene output.png|.exr include-dir [extra povray arguments...]
  local scene="$1" image="$2" dir="$3"; shift 3
  povray -D "+L$dir" "+I$root/scenes/pov/$scene" "+O$image" "$@" >"${image%.*}.log" 2>&1 ||
    { cat "${image%.*}.log" >&2; exit 1; }
}
pov_modes="baked"
# Procedural where the model has a POV-Ray form and the texture uses no joint colour (POV-Ray
# cannot multiply two patterns: such a texture is baked, docs/pov.md).
joint_colour() { python3 -c 'import json, sys; sys.exit(0 if "chroma_given_brightness" in json.load(open(sys.argv[1]))["colour"] else 1)' "$out/$name.stex"; }
if can pov_procedural && ! joint_colour; then pov_modes="procedural baked"; fi
for mode in $pov_modes; do
  mkdir -p "$out/pov-$mode"
  "$stex" pov "$out/$name.stex" -o "$out/pov-$mode/plane_texture.inc" --name Plane_Texture --mode "$mode"
  for format in exr png; do
    flag=$([ "$format" = exr ] && echo +FE || echo +FN)
    pov_render test_plane.pov "$out/$name-pov-$mode.$format" "$out/pov-$mode" -A "$flag" +W512 +H512 \
      Declare=Extent_U=1 Declare=Depth=0.25
  done
done
"$stex" pov "$out/$name.stex" -o "$out/showcase_procedural.inc" --name Showcase_Procedural
"$stex" pov "$out/$name.stex" -o "$out/showcase_baked.inc" --name Showcase_Baked --mode baked --bake-size 2048
pov_render showcase.pov "$out/$name-pov-showcase.png" "$out" +W800 +H450 +A0.1 +AM2 +R2
echo
echo "Demo images in $out:"
echo "  $name.stex             the procedural texture ($(stat -c %s "$out/$name.stex") bytes)"
echo "  $name-core.exr/.png    core render at the photo's pixel scale (EXR scene-linear, PNG sRGB)"
echo "  $name-core-wide.png    1024x512, zoomed out 4x (band-clamped anti-aliasing)"
[ -e "$out/$name-core-solid.png" ] && echo "  $name-core-solid.png   a slice of the solid (3D) texture"
echo "  $name-compare.png      photo | synthesis, radial PSDs and histograms"
echo "  $name-oiio.exr/.png     through the OIIO plugin (oiiotool): level 0 of a 1024² virtual image, tileable"
echo "  $name-oiio-mip3.png    its MIP level 3 (128²), computed by the model with that level's footprint"
[ -e "$out/$name-pov-procedural.png" ] && echo "  $name-pov-procedural.exr/.png  POV-Ray, procedural include (solid, POV-Ray's own noise), same plane"
echo "  $name-pov-baked.exr/.png       POV-Ray, baked include (a tileable EXR image map)"
echo "  $name-pov-showcase.png         POV-Ray showcase: cube, columns, sphere (${pov_modes%% *}); baked floor"
echo "  pov-${pov_modes// /\/, pov-}/, showcase_*.inc   the generated includes (and baked EXRs)"
echo "  (model: $(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["model"])' "$out/$name.stex"), chosen by stex analyze --model auto; see its score table above)"
