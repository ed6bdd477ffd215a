#!/usr/bin/env bash
# Files (outside docs/, tests/, *.md and the model's own folder core/src/models/<name>/) that
# mention the model's name in quotes.
set -euo pipefail
cd "$(dirname "$0")/.."
for m in wavelet gabor tiling lrp ptm; do
  files=$(git grep -l -E "[\"']$m[\"']" -- . ':!docs' ':!tests' ':!*.md' ":!core/src/models/$m" | tr '\n' ' ' || true)
  echo "$m: $(echo $files | wc -w)  $files"
done
