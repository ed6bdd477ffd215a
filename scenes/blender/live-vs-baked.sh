#!/usr/bin/env bash
# The live-against-baked table of docs/blender.md ("Live against baked"): Cycles renders the same
# texture (a) live from its .stex through the OIIO plugin, (b) from a 4096² and (c) a 16384²
# tiled, MIP-mapped half EXR baked by `stex bake`, each with scenes/blender/live_plane.py (the
# straight-on view and the receding one). Prints a Markdown table: bytes on disk, bake seconds,
# render seconds (straight on + receding), Blender's peak resident memory.
#
# Usage: scenes/blender/live-vs-baked.sh BUILD OUT [PHOTO]
#   BUILD: a build folder holding cli/stex, plugins/stex.imageio.so (built against the OIIO the
#          `blender` on PATH loads) and addon/stochtex-*.zip; OUT: a scratch folder (≈ 1.5 GB:
#          the 16384² EXR); PHOTO: default data/exemplars/concrete_512.png.
# Blender 5.2+ streams all three files tile by tile (its texture cache); older Blenders read
# level 0 whole, so (a) and (c) cost them seconds and gigabytes — the script runs there too,
# the table then shows that. In the Debian sid folder of scripts/sid-lane.sh (Blender 5.2.2):
#   chroot /var/cache/stochtex/sid bash /stochtex/src/scenes/blender/live-vs-baked.sh /stochtex/build /tmp/lvb
# (with /proc mounted and the source bind-mounted, as the lane does).
set -euo pipefail
if [ $# -lt 2 ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
  exit 2
fi
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "$1" && pwd)
out=$2
photo=${3:-$src/data/exemplars/concrete_512.png}
stex=$build/cli/stex
addon=$(ls "$build"/addon/stochtex-*.zip 2>/dev/null | head -1)
plugins=$build/plugins
for needed in "$stex" "$addon" "$plugins/stex.imageio.so" "$photo"; do
  [ -e "$needed" ] || { echo "live-vs-baked: missing $needed (build the stex, stex_imageio and stochtex_addon targets)" >&2; exit 1; }
done
command -v blender >/dev/null || { echo "live-vs-baked: no blender on PATH" >&2; exit 1; }
mkdir -p "$out"

texels=16384  # the .stex's default level 0 (docs/stex-format.md, image)
"$stex" analyze "$photo" -o "$out/texture.stex" --model wavelet >/dev/null
bake() {  # bake SIZE: prints the seconds
  local start=$EPOCHREALTIME
  "$stex" bake "$out/texture.stex" -o "$out/baked-$1.exr" --size "$1" --half >/dev/null
  python3 -c "print(f'{$EPOCHREALTIME - $start:.1f}')"
}
render() {  # render FILE LABEL: live_plane.py on FILE, its report in OUT/LABEL/live.json
  OPENIMAGEIO_PLUGIN_PATH=$plugins OIIO_LIBRARY_PATH=$plugins \
    blender -b --factory-startup --python "$src/scenes/blender/live_plane.py" -- --addon "$addon" \
    --photo "$photo" --out "$out/$2" --stex "$1" --texels "$3" --size 256 --samples 8 --receding >"$out/$2.log" 2>&1 ||
    { echo "live-vs-baked: Blender failed on $1 (log: $out/$2.log)" >&2; exit 1; }
}
bake_4096=$(bake 4096)
bake_16384=$(bake 16384)
render "$out/texture.stex" live $texels
render "$out/baked-4096.exr" baked-4096 4096
render "$out/baked-16384.exr" baked-16384 16384

echo "Blender: $(blender --version 2>/dev/null | head -1); $(nproc) cores; $(date -u +%Y-%m-%d)"
echo
echo "| texture file | bytes on disk | bake | render (straight on + receding) | peak memory |"
echo "|---|---|---|---|---|"
row() {  # row LABEL FILE BAKE-SECONDS REPORT-FOLDER
  python3 - "$@" <<'EOF'
import json, os, sys
label, path, bake, folder = sys.argv[1:5]
report = json.load(open(os.path.join(folder, "live.json")))
print("| %s | %s | %s | %.2f + %.2f s | %.0f MB |" % (label, format(os.path.getsize(path), ","), bake,
      report["live_seconds"], report["receding_seconds"], report["peak_rss_mb"]))
EOF
}
row "(a) \`.stex\`, live" "$out/texture.stex" none "$out/live"
row "(b) 4096² half EXR, tiled, MIP-mapped" "$out/baked-4096.exr" "$bake_4096 s" "$out/baked-4096"
row "(c) 16384² half EXR, tiled, MIP-mapped" "$out/baked-16384.exr" "$bake_16384 s" "$out/baked-16384"
