#!/usr/bin/env bash
# The ptm model end to end (docs/models/ptm.md): test data with a known truth rendered from the
# rock height scan, the PTM fit, synthesis in ψ-space, relighting under lights no photo was
# taken with, normal and albedo maps, and the OIIO plugin's light hint. Prints every number the
# document quotes; the figures go to OUTPUT_DIR (default out/ptm).
#   usage: scripts/ptm-demo.sh [OUTPUT_DIR] [BUILD_DIR]
# Takes ~5 minutes on 2 cores, most of it the exhaustive search run for the speed-up (step 6).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-$root/out/ptm}"
build="${2:-$root/build}"
scan="$root/../shared/exemplars/rock_height.png"
[ -f "$scan" ] || { echo "needs $scan (the shared exemplars)" >&2; exit 1; }
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)" --target stex stex_imageio >/dev/null
stex="$build/cli/stex"
mkdir -p "$out"
relief=(--downsample 2 --depth 24)  # the 1024² scan as 512² texels, heights 0 … 24 texels

echo "== 1. photos under 40 known lights, and the truth under 8 other lights"
"$stex" ptm relief "$scan" -o "$out/photos" --lights 40 --min-elevation 15 "${relief[@]}"
"$stex" ptm relief "$scan" -o "$out/unseen" --lights 8 --min-elevation 20 --azimuth-offset 17 "${relief[@]}"

echo "== 2. fit (lrgb and rgb), leave-one-light-out"
"$stex" ptm fit "$out/photos/lights.lp" -o "$out/rock.stex" --per-light
"$stex" ptm fit "$out/photos/lights.lp" -o "$out/rock-rgb.stex" --colour rgb

echo "== 3. the fitted PTM under the unseen lights, texel by texel"
"$stex" ptm relight "$out/rock.stex" --lights-from "$out/unseen/lights.lp" --compare --pixelwise -o "$out/fit-unseen.png"

echo "== 4. normal and albedo maps against the true ones"
for estimator in lambertian ptm-maximum; do
  "$stex" ptm export-maps "$out/rock.stex" --estimator "$estimator" --normal "$out/normal-$estimator.png" \
    --albedo "$out/albedo-$estimator.png" --reference-normals "$out/photos/normal.exr" \
    --reference-albedo "$out/photos/albedo.exr"
done

echo "== 5. synthesis: 1024² tileable from the 512² PTM, relit under the unseen lights"
"$stex" ptm synthesize "$out/rock.stex" -o "$out/rock-1024.stex" --size 1024x1024 --block 80 --overlap 16 --tileable
"$stex" ptm relight "$out/rock-1024.stex" --lights-from "$out/unseen/lights.lp" --compare -o "$out/synthesis-unseen.png"

echo "== 6. search: the projection-kernel rejection against the exhaustive search (same output?)"
"$stex" ptm synthesize "$out/rock.stex" -o "$out/rock-512.stex" --size 512x512 --block 80 --overlap 16 --verify

echo "== 7. figures"
# A relighting strip: the synthesis under five lights around the compass at 30° elevation.
"$stex" ptm relight "$out/rock-1024.stex" -o "$out/strip.png" --size 384x384 \
  --light-angles 0,30 --light-angles 72,30 --light-angles 144,30 --light-angles 216,30 --light-angles 288,30
# Truth, fitted PTM and synthesis under one unseen light (the first), 384² crops.
first=$(sed -n 2p "$out/unseen/lights.lp" | awk '{print $2","$3","$4}')
oiiotool "$out/unseen/light_000.exr" --cut 384x384+0+0 --colorconvert linear sRGB -o "$out/truth-0.png"
"$stex" ptm relight "$out/rock.stex" --light "$first" --size 384x384 -o "$out/fit-0.png"
"$stex" ptm relight "$out/rock-1024.stex" --light "$first" --size 384x384 -o "$out/synthesis-0.png"
# The plugin: the synthesis as a MIP-mapped image lit from the west, through OIIO's own tool.
export OIIO_LIBRARY_PATH="$build/plugins"
oiiotool --iconfig stex:width 1024 --iconfig stex:height 1024 --iconfig stex:light "-1,0,0.6" "$out/rock-1024.stex" \
  --selectmip 1 --colorconvert linear sRGB -o "$out/plugin-west-mip1.png"
echo "figures in $out"
