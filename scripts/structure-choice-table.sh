#!/usr/bin/env bash
# Issue 33's table: per shared photo, the automatic choice (`stex analyze PHOTO -o t.stex`, the
# CLI's default `--model auto`) of two builds or two sets of flags — "before" and "after" — and
# `stex compare PHOTO t.stex` of each at the photo's size: the chosen model, colour mode, blend
# contrast γ and exemplar size, the structure distance and its five parts, radial (mean RGB) and
# 2D log-PSD dB, the worst W1/σ, false colour, analysis seconds, and the structure distance's
# change in %. `stex compare` is the after build's for both.
# Usage: scripts/structure-choice-table.sh BEFORE_BUILD AFTER_BUILD [photo…] [-- after's analyze flags…]
#   photos default to the four with the most structure (palm_bark karst_rock gravel sandy_rock);
#   e.g. scripts/structure-choice-table.sh build-main build -- --choice-structure
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
before="$1/cli/stex"
after_stex="$2/cli/stex"
shift 2
photos=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do photos+=("$1"); shift; done
[ $# -gt 0 ] && shift
flags=("$@")
[ ${#photos[@]} -gt 0 ] || photos=(palm_bark karst_rock gravel sandy_rock)
source "$root/scripts/compare-report.sh"  # $exemplars, $work, after, part
row_mean() { awk -v l="$1" 'index($0, l) == 1 { printf "%.2f", ($(NF - 2) + $(NF - 1) + $NF) / 3 }'; }
row_max() { awk -v l="$1" 'index($0, l) == 1 { m = $(NF - 2); if ($(NF - 1) > m) m = $(NF - 1); if ($NF > m) m = $NF; printf "%.3f", m }'; }
# model | colour | γ | exemplar of a .stex
chosen() {
    python3 - "$1" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
p = d["parameters"]
colour = d["colour"]["mode"] + ("+joint" if "chroma_given_brightness" in d["colour"] else "")
# γ and the exemplar's size where the model has an exemplar to blend (its parameters say so).
blended = isinstance(p.get("exemplar"), dict)
gamma = p.get("blend_contrast", 1) if blended else None
exemplar = "%d×%d" % (p["exemplar"]["width"], p["exemplar"]["height"]) if blended else "–"
print("%s | %s | %s | %s" % (d["model"], colour, "–" if gamma is None else "%g" % gamma, exemplar))
EOF
}

echo "| photo | build | model | colour | γ | exemplar | structure distance | marginals | auto-correlation | cross-orientation | cross-scale | phase | radial log-PSD dB | 2D log-PSD dB | worst W1/σ | false colour % | analyse s | structure change |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for name in "${photos[@]}"; do
    photo="$exemplars/$name.png"
    base=""
    for side in before after; do
        if [ "$side" = before ]; then stex="$before" args=(); else stex="$after_stex" args=("${flags[@]}"); fi
        t0=$(date +%s.%N)
        "$stex" analyze "$photo" -o "$work/$side.stex" ${args[@]+"${args[@]}"} >"$work/analyze.log"
        t1=$(date +%s.%N)
        "$after_stex" compare "$photo" "$work/$side.stex" >"$work/compare.log" 2>/dev/null
        r="$work/compare.log"
        s="$(after 'structure distance' <"$r")"
        change=""
        if [ "$side" = before ]; then base="$s"; else change="$(python3 -c "print('%+.0f %%' % (100 * ($s / $base - 1)))")"; fi
        printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.1f | %s |\n' "$name" "$side" \
            "$(chosen "$work/$side.stex")" "$s" "$(part marginals <"$r")" "$(part auto-correlation <"$r")" \
            "$(part cross-orientation <"$r")" "$(part cross-scale <"$r")" "$(part phase <"$r")" \
            "$(row_mean 'log-PSD dB' <"$r")" "$(after '2D log-PSD' <"$r")" "$(row_max 'W1/sigma' <"$r")" \
            "$(after 'false-colour rate' <"$r")" "$(echo "$t1 - $t0" | bc)" "$change"
        cp "$work/$side.stex" "${KEEP_DIR:-$work}/$name-$side.stex" 2>/dev/null || true
    done
done
