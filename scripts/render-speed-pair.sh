#!/usr/bin/env bash
# Raster speed of two textures measured alternately (a loaded machine drifts; alternating keeps
# the drift out of the comparison): `stex render T -o r.exr --size 1024x1024 --threads 1`, its
# printed Mpixel/s, RUNS rounds of A then B; prints each one's median and the load average.
# Usage: scripts/render-speed-pair.sh BUILD A.stex B.stex [RUNS]   (RUNS: 9)
set -euo pipefail
stex="$1/cli/stex"
a="$2" b="$3" runs="${4:-9}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
speed() { "$stex" render "$1" -o "$work/r.exr" --size 1024x1024 --threads 1 | sed -n 's/.*, \([0-9.]*\) Mpixel\/s.*/\1/p'; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
load_before="$(cut -d' ' -f1 /proc/loadavg)"
for _ in $(seq "$runs"); do
    speed "$a" >>"$work/a"
    speed "$b" >>"$work/b"
done
echo "$(basename "$a"): median $(median <"$work/a") Mpixel/s ($(sort -g "$work/a" | tr '\n' ' '))"
echo "$(basename "$b"): median $(median <"$work/b") Mpixel/s ($(sort -g "$work/b" | tr '\n' ' '))"
echo "load average $load_before before, $(cut -d' ' -f1 /proc/loadavg) after; $runs rounds alternating"
