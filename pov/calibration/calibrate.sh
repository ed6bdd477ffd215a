#!/usr/bin/env bash
# Regenerates pov/src/pov_noise_calibration.cpp: renders POV-Ray's noise on 8 randomly rotated
# plane slices (noise_plane.pov, 1024², 8 pixels per lattice cell, EXR) and measures its mean,
# variance and spectrum with the core's metrics (measure_noise.cpp). Needs povray and a build
# (default build dir: build/). About 10 s. Rerun after changing the noise the includes use.
#   usage: pov/calibration/calibrate.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build}"
cmake --build "$build" --target stex_pov_measure_noise >/dev/null
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# Fixed "random" angles and offsets: the calibration is reproducible.
angles=("17 41 73" "113 29 151" "61 167 11" "199 83 257" "239 131 307" "283 227 37" "331 263 97" "7 311 199")
renders=()
for i in "${!angles[@]}"; do
  read -r ax ay az <<<"${angles[$i]}"
  povray -D +W1024 +H1024 -A +FE "+I$root/pov/calibration/noise_plane.pov" "+O$work/noise-$i.exr" \
    "Declare=AngleX=$ax" "Declare=AngleY=$ay" "Declare=AngleZ=$az" "Declare=Offset=$((1000 + 37 * i)).37" \
    2>"$work/povray-$i.log" || { cat "$work/povray-$i.log" >&2; exit 1; }
  renders+=("$work/noise-$i.exr")
done
version="$(povray --version 2>&1 | grep -m1 '^POV-Ray' || echo 'POV-Ray')"
"$build/pov/stex_pov_measure_noise" "$root/pov/src/pov_noise_calibration.cpp" 8 "$version" "${renders[@]}"
