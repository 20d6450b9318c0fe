#!/usr/bin/env bash
# Builds spirec (the `default` preset, into build/) and runs the main job.
#
# For now the main job prints the choice file of every example:
#   build/bin/spirec --choices examples/<name>.spire
# Usage: scripts/run.sh            (from any directory)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

bash scripts/install-deps.sh

cmake --preset default
cmake --build --preset default

SPIREC="$ROOT/build/bin/spirec"
if [[ ! -x "$SPIREC" ]]; then
  echo "run.sh: $SPIREC was not built" >&2
  exit 1
fi

shopt -s nullglob
examples=(examples/*.spire)
shopt -u nullglob
if ((${#examples[@]} == 0)); then
  echo "run.sh: no examples in examples/*.spire"
  exit 0
fi

for example in "${examples[@]}"; do
  echo "== $example"
  "$SPIREC" "$example" --choices
  echo
done
