#!/usr/bin/env bash
# Builds everything (the `default` preset, into build/) and runs the main job:
# the demo engine renders the Terrain example (examples/scenes/terrain.json)
# on a procedural terrain under the three decision files of paper Figure 5
# (full quality; albedo baked; albedo baked with vertex normal and basic
# lighting), and writes out/demo/{full_quality,baked_albedo,
# baked_vertex_normal,comparison}.png and report.md, printing the table of
# frame time, speedup and error against full quality.
# Usage: scripts/run.sh [extra spire-demo flags...]   (from any directory)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

bash scripts/install-deps.sh

cmake --preset default
cmake --build --preset default

DEMO="$ROOT/build/bin/spire-demo"
if [[ ! -x "$DEMO" ]]; then
  echo "run.sh: $DEMO was not built" >&2
  exit 1
fi
# Timings should not depend on what an earlier run left in Mesa's cache.
export MESA_SHADER_CACHE_DISABLE=true
"$DEMO" examples/scenes/terrain.json -o out/demo "$@"
