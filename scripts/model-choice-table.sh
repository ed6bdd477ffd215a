#!/usr/bin/env bash
# What `stex analyze --model auto` chooses for each shared photo (../shared/exemplars, not the
# height map), with its score table, and a contact sheet: per photo a row of 128² crops —
# photo | each model with analysis, in the registry's order (each model's own fit, in pca colour but
# the chosen one in its chosen colour mode, rendered at the photo's pixel scale), the chosen one
# framed in white; then the choice with `--choice-structure`, framed in grey, and the photo and that
# texture zoomed out ×2. Prints Markdown (docs/models/README.md's table).
#   usage: scripts/model-choice-table.sh [BUILD_DIR] [SHEET.jpg]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
sheet="${2:-}"
stex="$build/cli/stex"
exemplars="$root/../shared/exemplars"
[ -d "$exemplars" ] || { echo "no $exemplars" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
source "$root/scripts/registry-models.sh"
models=($(registry_models "$stex" analysis))
rows=()
echo "| photo | chosen | penalty of each candidate | chosen: radial dB, 2D dB, W1/σ, false colour, orientation °, \|∇\| W1 | bytes | analyse s |"
echo "|---|---|---|---|---|---|"
for photo in "$exemplars"/*.png; do
    name="$(basename "$photo" .png)"
    [ "$name" = rock_height ] && continue  # a height map, not a photo
    t0=$(date +%s.%N)
    "$stex" analyze "$photo" -o "$work/$name-auto.stex" >"$work/$name-auto.log"
    t1=$(date +%s.%N)
    python3 - "$work/$name-auto.stex" "$name" "$(echo "$t1 - $t0" | bc)" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
def label(model, colour, joint):
    return model + ("" if colour == "pca" else "/" + colour) + ("+joint" if joint else "")
scores = {label(s["model"], s["colour"], s.get("joint_colour", False)): s for s in d["provenance"]["model_choice"]}
chosen = label(d["model"], d["colour"]["mode"], "chroma_given_brightness" in d["colour"])
c = scores[chosen]
f = lambda v, p: "n/a" if v is None else ("%." + str(p) + "f") % v
print("| %s | **%s** | %s | %s, %s, %s, %s %%, %s, %s | %d | %.1f |" % (
    sys.argv[2], chosen, ", ".join("%s %s" % (m, f(s["penalty"], 2)) for m, s in scores.items()),
    f(c["radial_log_psd_db"], 2), f(c["polar_log_psd_db"], 2), f(c["w1_sigma"], 3),
    f(None if c["false_colour_rate"] is None else 100 * c["false_colour_rate"], 2),
    f(c["gradient_orientation_degrees"], 2), f(c["gradient_magnitude_w1"], 3), c["bytes"], float(sys.argv[3])))
PY
    [ -n "$sheet" ] || continue
    chosen="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["model"])' "$work/$name-auto.stex")"
    chosen_colour="$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["colour"]["mode"])' "$work/$name-auto.stex")"
    chosen_joint="$(python3 -c 'import json,sys; print("on" if "chroma_given_brightness" in json.load(open(sys.argv[1]))["colour"] else "off")' "$work/$name-auto.stex")"
    # The photo's top-left 128² and each model's render of the same size, sRGB.
    oiiotool "$photo" --cut 128x128+0+0 -o "$work/$name-0.png"
    row=("$work/$name-0.png")
    for model in "${models[@]}"; do
        colour=pca joint=off
        [ "$model" = "$chosen" ] && colour="$chosen_colour" joint="$chosen_joint"  # the chosen candidate as it was chosen
        "$stex" analyze "$photo" -o "$work/$name-$model.stex" --model "$model" --colour "$colour" --joint-colour "$joint" >/dev/null
        "$stex" render "$work/$name-$model.stex" -o "$work/$name-$model.png" --size 128x128 >/dev/null
        if [ "$model" = "$chosen" ]; then
            oiiotool "$work/$name-$model.png" --cut 124x124+2+2 --fit:pad=1 128x128 --ch R,G,B \
                --box:color=1,1,1:fill=0 0,0,127,127 -o "$work/$name-$model.png"
        fi
        row+=("$work/$name-$model.png")
    done
    # Issue 33: the choice scoring structure (`--choice-structure`: tiling's sharper blends and
    # larger exemplar tried too), framed in grey; then the photo and that texture zoomed out ×2
    # (the photo's top-left 256² halved, `stex render --scale 2`), where ghosts and cut plates show.
    "$stex" analyze "$photo" -o "$work/$name-structure.stex" --choice-structure >/dev/null
    "$stex" render "$work/$name-structure.stex" -o "$work/$name-structure.png" --size 128x128 >/dev/null
    oiiotool "$work/$name-structure.png" --cut 124x124+2+2 --fit:pad=1 128x128 --ch R,G,B \
        --box:color=0.5,0.5,0.5:fill=0 0,0,127,127 -o "$work/$name-structure.png"
    oiiotool "$photo" --cut 256x256+0+0 --resize 128x128 -o "$work/$name-0-half.png"
    "$stex" render "$work/$name-structure.stex" -o "$work/$name-structure-half.png" --size 128x128 --scale 2 >/dev/null
    row+=("$work/$name-structure.png" "$work/$name-0-half.png" "$work/$name-structure-half.png")
    rows+=("${row[@]}")
done
if [ -n "$sheet" ]; then
    columns=$(( ${#models[@]} + 4 ))  # the photo, each model, the structure choice, both zoomed out
    oiiotool --nosoftwareattrib "${rows[@]}" --mosaic:pad=4 ${columns}x$(( ${#rows[@]} / columns )) --ch R,G,B --compression jpeg:85 -o "$sheet"
    echo
    echo "contact sheet: $sheet"
fi
