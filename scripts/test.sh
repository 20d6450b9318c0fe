#!/usr/bin/env bash
# Builds and runs every test: the `default` preset (build/, RelWithDebInfo,
# GCC), then the `asan` preset (build-asan/, Debug with AddressSanitizer and
# UndefinedBehaviorSanitizer). Exits non-zero if any build or test fails;
# a test failure in one preset still lets the other preset run.
# Usage: scripts/test.sh            (from any directory; this is what CI runs)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

bash scripts/install-deps.sh

# Make sanitizer failures fatal and readable in CTest output.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1}"
# lavapipe's own leaks are suppressed (tests/lsan.supp says why); ours are not.
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$ROOT/tests/lsan.supp}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

# The window tests need a display: without one, an Xvfb server stands in
# (xvfb and xauth come with install-deps.sh), so CI covers them too. With
# -noreset: an X server resets when its last client disconnects, and a test
# that opens a window again right after (as the explorer tests do, one tool
# run after another) is refused while it does. On this 2-core machine under
# load, 18 of 300 back-to-back xdpyinfo runs failed to open the display
# without it and none with it.
runner=()
if [[ -z "${DISPLAY:-}" && -z "${WAYLAND_DISPLAY:-}" ]] && command -v xvfb-run >/dev/null 2>&1 &&
  command -v xauth >/dev/null 2>&1; then
  runner=(xvfb-run --auto-servernum --server-args="-screen 0 1280x1024x24 -noreset")
fi

# The tests' spirec runs start a compile server (docs/integration.md); it
# lives in a folder of the tests' own, and stops when the folder goes.
SPIRE_SERVER_DIR="$(mktemp -d "${TMPDIR:-/tmp}/spire-test-server.XXXXXX")"
export SPIRE_SERVER_DIR
trap 'rm -rf "$SPIRE_SERVER_DIR"' EXIT

failed=()
for preset in default asan; do
  echo "==> [$preset] configure and build"
  cmake --preset "$preset"
  cmake --build --preset "$preset"
  echo "==> [$preset] ctest"
  if ! "${runner[@]}" ctest --preset "$preset" --no-tests=error; then
    failed+=("$preset")
  fi
done

if ((${#failed[@]} > 0)); then
  echo "test.sh: tests failed in preset(s): ${failed[*]}" >&2
  exit 1
fi
echo "test.sh: all tests passed (default, asan)"
