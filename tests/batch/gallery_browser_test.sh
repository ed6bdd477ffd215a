#!/usr/bin/env bash
# The batch's index.html in a real browser: headless Chromium (Debian's `chromium`) opens it from
# disk; the page must log nothing to the console (no script error, no failed load) and every
# image must load (the page marks one that does not: class "missing-image"). Two broken copies
# check that the test sees each kind of failure. Writes a screenshot, WORK_DIR/gallery.png.
#   gallery_browser_test.sh WORK_DIR
# Environment: STEX, STOCHTEX_SOURCE_DIR. No chromium fails; STOCHTEX_SKIP_BROWSER=1 skips (exit 77).
set -euo pipefail
work=${1:?usage: gallery_browser_test.sh WORK_DIR}
here=$(cd "$(dirname "$0")" && pwd)
repo=${STOCHTEX_SOURCE_DIR:-$(cd "$here/../.." && pwd)}
stex=${STEX:?STEX: the stex program}
if [ "${STOCHTEX_SKIP_BROWSER:-0}" = 1 ]; then echo "SKIPPED: STOCHTEX_SKIP_BROWSER=1"; exit 77; fi
browser=$(command -v chromium || true)
[ -n "$browser" ] || { echo "FAIL: chromium not found: install it (scripts/install-deps.sh) or set STOCHTEX_SKIP_BROWSER=1"; exit 1; }
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$work"; mkdir -p "$work"
bash "$here/make_photos.sh" "$repo/data/exemplars/concrete_512.png" "$work/photos" 5
# A manifest: per-photo options, and one photo that does not exist (a failed row on the page).
{
  echo "photo,name,model,colour"
  for photo in "$work"/photos/*.png; do echo "$(basename "$photo"),,,"; done | sed '2s/,,,$/,,wavelet,rgb/'
  echo "no_such_photo.png,lost,,"
} > "$work/photos/manifest.csv"
status=0
"$stex" batch "$work/photos/manifest.csv" -o "$work/out" --compare > "$work/batch.txt" || status=$?
[ "$status" = 1 ] || fail "exit status $status, expected 1 (one photo failed): $(cat "$work/batch.txt")"
images=$(grep -o '<img ' "$work/out/index.html" | wc -l)
[ "$images" = 10 ] || fail "index.html has $images images, expected 10 (5 photos, 2 each)"

# Loads a page, lets its script run, prints its DOM; the browser's own log (console messages
# included) goes to $2.
load() {
  timeout 120 "$browser" --headless --no-sandbox --disable-gpu --no-first-run --disable-extensions \
    --user-data-dir="$work/profile" --enable-logging=stderr --v=0 --allow-file-access-from-files \
    --virtual-time-budget=5000 --dump-dom "file://$1" 2> "$2"
}
console_messages() { grep -E 'CONSOLE|Uncaught|Failed to load|ERR_FILE_NOT_FOUND' "$1" || true; }

dom=$(load "$work/out/index.html" "$work/chromium.log") || fail "chromium could not load the page: $(tail -n 20 "$work/chromium.log")"
[ -z "$(console_messages "$work/chromium.log")" ] || fail "console messages: $(console_messages "$work/chromium.log")"
grep -q 'id="summary">6 photos: 5 done, 1 failed' <<< "$dom" || fail "the page's script did not run (no summary line)"
! grep -q 'alt="missing:' <<< "$dom" || fail "an image did not load: $(grep -o 'alt="missing:[^"]*"' <<< "$dom")"
# Sorted worst first: the failed photo, then the highest penalty.
first_row=$(grep -o '<tr class="[a-z]*" data-status="[a-z]*" data-index="[0-9]*"' <<< "$dom" | head -n 1)
[[ "$first_row" == *failed* ]] || fail "the failed photo is not first: $first_row"

# The checks can fail: a page with a script error, and one with an image gone.
mkdir -p "$work/broken"
cp -r "$work/out/." "$work/broken/"
sed 's|"use strict";|"use strict"; undefined_function();|' "$work/out/index.html" > "$work/broken/script-error.html"
load "$work/broken/script-error.html" "$work/broken-script.log" > /dev/null || true
[ -n "$(console_messages "$work/broken-script.log")" ] || fail "a script error was not seen in the console log"
rm "$work/broken/$(ls "$work/broken" | grep -v -e '\.' -e reports | head -n 1)/synthesis.png"
broken_dom=$(load "$work/broken/index.html" "$work/broken-image.log") || true
grep -q 'alt="missing:' <<< "$broken_dom" || fail "a missing image was not marked"

timeout 120 "$browser" --headless --no-sandbox --disable-gpu --no-first-run --user-data-dir="$work/profile" \
  --hide-scrollbars --window-size=1400,1100 --virtual-time-budget=5000 --screenshot="$work/gallery.png" \
  "file://$work/out/index.html" 2> "$work/screenshot.log" || fail "no screenshot: $(tail -n 5 "$work/screenshot.log")"
[ -s "$work/gallery.png" ] || fail "no screenshot written"
echo "PASS: the gallery loads in $("$browser" --version 2>/dev/null | head -n 1) with no console message, all $images images, worst first; screenshot $work/gallery.png"
