#!/usr/bin/env bash
# `oiiotool T.stex --resize 512x512` (the plugin's tiles through OIIO's resize) against the same
# resize of the same image read from a baked, tiled, uncompressed float OpenEXR: the reference a
# .stex competes with here is a file on disk holding the pixels already made.
# Usage: bench/oiiotool_resize.sh [build-dir] [size] [rounds]   (defaults: build, 4096, 3)
# size 16384 is the plugin's default image (stex:width/height unset); it needs ~4.3 GB of disk
# for the EXR and ~3.3 GB of memory per oiiotool, and a round takes ~2 minutes on 2 cores.
# Prints each run's wall and CPU (user + system) seconds and the medians; the two resized images
# are checked to be the same (oiiotool --diff).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
size="${2:-4096}"
rounds="${3:-3}"
for tool in oiiotool python3; do
  command -v "$tool" >/dev/null || { echo "oiiotool_resize.sh: $tool is not installed" >&2; exit 1; }
done
[ -x "$build/cli/stex" ] || { echo "oiiotool_resize.sh: $build/cli/stex not found (build the stex target)" >&2; exit 1; }
[ -f "$build/plugins/stex.imageio.so" ] || { echo "oiiotool_resize.sh: $build/plugins/stex.imageio.so not found (build the plugin)" >&2; exit 1; }
export OIIO_LIBRARY_PATH="$build/plugins"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
lscpu | grep 'Model name' || true
echo "cores: $(nproc); image ${size}x${size}; load average: $(cut -d' ' -f1-3 /proc/loadavg)"

"$build/cli/stex" analyze "$root/data/exemplars/concrete_512.png" --model wavelet -o "$work/t.stex" >/dev/null
image=()
[ "$size" = 16384 ] || image=(--iconfig stex:width "$size" --iconfig stex:height "$size")
oiiotool "${image[@]}" "$work/t.stex" -d float --tile 64 64 --compression none -o "$work/baked.exr"

# One timed command: appends "wall cpu" to $work/times.<name>.
timed() {
  local name="$1"
  shift
  /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" >/dev/null
  read -r wall user system <"$work/time"
  local cpu
  cpu="$(python3 -c "print(f'{$user + $system:.2f}')")"
  echo "$name: ${wall} s wall, ${cpu} s CPU"
  echo "$wall $cpu" >>"$work/times.$name"
}
for ((round = 1; round <= rounds; round++)); do
  timed stex oiiotool "${image[@]}" "$work/t.stex" --resize 512x512 -o "$work/from_stex.exr"
  timed baked oiiotool "$work/baked.exr" --resize 512x512 -o "$work/from_baked.exr"
done
oiiotool --diff "$work/from_stex.exr" "$work/from_baked.exr" | tail -1

python3 - "$work" <<'EOF'
import statistics, sys
work = sys.argv[1]
median = {}
for name in ("stex", "baked"):
    rows = [tuple(map(float, line.split())) for line in open(f"{work}/times.{name}")]
    median[name] = (statistics.median(r[0] for r in rows), statistics.median(r[1] for r in rows))
    print(f"median {name:5}: {median[name][0]:.2f} s wall, {median[name][1]:.2f} s CPU")
print(f"the .stex against the baked EXR: {median['baked'][0] / median['stex'][0]:.2f}x wall, "
      f"{median['baked'][1] / median['stex'][1]:.2f}x CPU (above 1: the .stex is faster)")
EOF
