#!/usr/bin/env bash
# The photos the batch tests convert: COUNT (at most 12) small variants of one exemplar — crops at
# different places, flips, a rotation, colour shifts — so that each is a different photo and a
# different analysis, cheaply (SIZE² pixels).
#   make_photos.sh EXEMPLAR FOLDER [COUNT] [SIZE]
set -euo pipefail
exemplar=${1:?usage: make_photos.sh EXEMPLAR FOLDER [COUNT] [SIZE]}
folder=${2:?usage: make_photos.sh EXEMPLAR FOLDER [COUNT] [SIZE]}
count=${3:-12}
size=${4:-96}
command -v oiiotool >/dev/null || { echo "make_photos.sh: oiiotool not found (openimageio-tools)" >&2; exit 1; }
mkdir -p "$folder"
variants=(
  "crop_a|--cut ${size}x${size}+0+0"
  "crop_b|--cut ${size}x${size}+200+40"
  "crop_c|--cut ${size}x${size}+330+300"
  "flip|--cut ${size}x${size}+100+200 --flip"
  "flop|--cut ${size}x${size}+260+120 --flop"
  "rotate|--cut ${size}x${size}+40+380 --rotate90"
  "warm|--cut ${size}x${size}+150+150 --mulc 1.15,0.95,0.75"
  "cool|--cut ${size}x${size}+380+20 --mulc 0.8,0.95,1.2"
  "dark|--cut ${size}x${size}+60+260 --mulc 0.55,0.55,0.55"
  "green|--cut ${size}x${size}+300+380 --mulc 0.85,1.1,0.8"
  "wide|--cut $((size + 32))x${size}+10+100"
  "tall|--cut ${size}x$((size + 32))+400+60 --flip --mulc 1.05,1.0,0.9"
)
for ((i = 0; i < count && i < ${#variants[@]}; ++i)); do
  name=${variants[i]%%|*}
  # shellcheck disable=SC2086  # the operations are words
  oiiotool "$exemplar" ${variants[i]#*|} --origin +0+0 --fullpixels -d uint8 -o "$folder/$(printf '%02d' "$i")_$name.png"
done
