#!/usr/bin/env bash
# Fingerprints of what the CLI makes for every model: the .stex files analysis writes and the
# images `stex render`, `stex bake` and the plugin make of them (2D filtered, point-sampled,
# zoomed out, tileable, solid, offset). A refactor that keeps behaviour keeps every line.
#   usage: scripts/render-fingerprints.sh BUILD_DIR OUT_FILE [WORK_DIR]
#   then:  diff before.txt after.txt      (empty: bit-identical)
# Uses only the committed exemplar (data/exemplars/concrete_512.png), so it runs anywhere.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:?usage: $0 BUILD_DIR OUT_FILE [WORK_DIR]}" && pwd)"
out_file="${2:?usage: $0 BUILD_DIR OUT_FILE [WORK_DIR]}"
work="${3:-$(mktemp -d)}"
stex="$build/cli/stex"
photo="$root/data/exemplars/concrete_512.png"
source "$root/scripts/registry-models.sh"
# The models come from the registry, by capability (each from the analysed ones, whose .stex
# files the later steps reuse); the first model with a front-end's form stands for that
# front-end (one line each, as it was when one model had them).
analysed=($(registry_models "$stex" analysis))
solid=($(registry_models "$stex" analysis solid))
first() { local names; names=($(registry_models "$stex" "$@")); echo "${names[0]}"; }
morph=$(first analysis morph)
pov=$(first analysis pov_procedural)
osl=$(first analysis osl)
mkdir -p "$work"
: >"$out_file"
fingerprint() {  # label file
  # Images through oiiotool's pixel hash (the EXR header holds nothing variable, but PNG
  # writers may): the pixels are what must not change.
  local hash
  case "$2" in
    *.stex|*.inc|*.osl) hash=$(sed 's/"tool": "[^"]*"/"tool": ""/' "$2" | sha256sum | cut -c1-16) ;;
    *) hash=$(oiiotool --hash "$2" 2>/dev/null | awk '/SHA-1/ {print substr($2, 1, 16); exit}') ;;
  esac
  printf '%-34s %s\n' "$1" "$hash" >>"$out_file"
}
render() {  # label stex output args...
  local label="$1" texture="$2" image="$3"; shift 3
  "$stex" render "$texture" -o "$work/$image" "$@" >/dev/null
  fingerprint "$label" "$work/$image"
}

small=(--size 96x80)
for model in "${analysed[@]}"; do
  t="$work/$model.stex"
  extra=()
  case "$model" in  # smaller than the defaults, for speed; other models analyse with theirs
    gabor) extra=(--bands 4 --impulses 8) ;;
    lrp) extra=(--J 24 --L 4) ;;
  esac
  "$stex" analyze "$photo" -o "$t" --model "$model" "${extra[@]}" >/dev/null
  fingerprint "$model analyze" "$t"
  render "$model 2D" "$t" "$model-2d.exr" "${small[@]}"
  render "$model 2D point" "$t" "$model-point.exr" "${small[@]}" --no-filter
  render "$model 2D scale 3.5 offset" "$t" "$model-zoom.exr" "${small[@]}" --scale 3.5 --u 0.3 --v -1.7
  render "$model 2D tileable" "$t" "$model-tile.exr" --size 256x128 --tileable
  render "$model 2D png" "$t" "$model-2d.png" "${small[@]}" --seed 7
  "$stex" bake "$t" -o "$work/$model-bake.exr" --size 256 --tile 64 >/dev/null
  fingerprint "$model bake" "$work/$model-bake.exr"
  OIIO_LIBRARY_PATH="$build/plugins" oiiotool --iconfig stex:width 256 --iconfig stex:height 256 \
    --iconfig stex:tile_width 32 --iconfig stex:tile_height 32 "$t" --selectmip 1 -o "$work/$model-oiio.exr"
  fingerprint "$model plugin mip1" "$work/$model-oiio.exr"
done
# Solid renders for the models that have a solid form.
for model in "${solid[@]}"; do
  render "$model solid" "$work/$model.stex" "$model-solid.exr" "${small[@]}" --solid --z 0.37
  render "$model solid zoom" "$work/$model.stex" "$model-solid-zoom.exr" "${small[@]}" --solid --z -2 --scale 5
done
# The solid bake at the texels of a position map (a sheared ramp, every texel covered).
oiiotool --pattern fill:topleft=0,0,0,1:topright=2,0,0.5,1:bottomleft=0,1.5,1,1:bottomright=2,1.5,1.5,1 48x40 4 \
  -d float -o "$work/positions.exr"
# Tiling too: not a solid noise, but its triplanar blend is what a solid bake of it evaluates.
for model in "${solid[@]}" tiling; do
  "$stex" bake "$work/$model.stex" -o "$work/$model-solid-map.exr" --positions "$work/positions.exr" --position-scale 0.5 >/dev/null
  fingerprint "$model bake positions" "$work/$model-solid-map.exr"
done
"$stex" morph "$work/$morph.stex" "$work/$morph.stex" --t 0.5 -o "$work/morph.stex" >/dev/null
fingerprint "$morph morph" "$work/morph.stex"
"$stex" pov "$work/$pov.stex" -o "$work/$pov.inc" --name T >/dev/null
fingerprint "$pov pov include" "$work/$pov.inc"
"$stex" osl "$work/$osl.stex" -o "$work/$osl.osl" --tile-dir /tiles >/dev/null
fingerprint "$osl osl shader" "$work/$osl.osl"

# ptm: relightable test data from a synthetic height map, fitted, rendered, relit.
oiiotool --pattern noise:type=uniform:min=0:max=1:seed=3 48x48 1 --blur 5x5 -d uint16 -o "$work/height.png"
"$stex" ptm relief "$work/height.png" -o "$work/relief" --lights 12 >/dev/null
"$stex" ptm fit "$work/relief/lights.lp" -o "$work/ptm.stex" >/dev/null
fingerprint "ptm fit" "$work/ptm.stex"
render "ptm 2D" "$work/ptm.stex" "ptm-2d.exr" --size 64x64
render "ptm 2D zoom" "$work/ptm.stex" "ptm-zoom.exr" --size 64x64 --scale 2.5 --u 0.1
"$stex" ptm relight "$work/ptm.stex" -o "$work/ptm-lit.exr" --light-angles 40,35 >/dev/null
fingerprint "ptm relight" "$work/ptm-lit.exr"
# tiling variants made by their own commands
"$stex" tiling phasor -o "$work/phasor.stex" >/dev/null
fingerprint "tiling phasor" "$work/phasor.stex"
render "tiling phasor 2D" "$work/phasor.stex" "phasor.exr" --size 64x64 --scale 2
echo "fingerprints of $(wc -l <"$out_file") outputs in $out_file (work files in $work)"
