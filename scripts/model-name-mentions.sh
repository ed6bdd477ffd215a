#!/usr/bin/env bash
# Files (outside docs/, tests/, *.md and the model's own folder core/src/models/<name>/) that
# mention the model's name in quotes. The models are the registry's (`stex models --json`).
#   usage: scripts/model-name-mentions.sh [BUILD_DIR]   (default: build)
set -euo pipefail
build="$(cd "${1:-$(dirname "$0")/../build}" && pwd)"
cd "$(dirname "$0")/.."
source scripts/registry-models.sh
for m in $(registry_models "$build/cli/stex"); do
  files=$(git grep -l -E "[\"']$m[\"']" -- . ':!docs' ':!tests' ':!*.md' ":!core/src/models/$m" | tr '\n' ' ' || true)
  echo "$m: $(echo $files | wc -w)  $files"
done
