#!/usr/bin/env bash
# The VsCodeGrammar CTest: installs the grammar test's npm dev dependencies
# (vscode-textmate, vscode-oniguruma, pinned by package-lock.json) into the
# build folder, not the source tree, and runs test/tokenize.js against the
# repository.
#
# Usage: run.sh SOURCE_DIR WORK_DIR
#   WORK_DIR gets a copy of package.json and package-lock.json and the
#   node_modules that `npm ci` makes from them. npm ci runs only when the
#   copies differ from the repository's, so a rerun needs no network.
set -euo pipefail

if (($# != 2)); then
  echo "usage: $0 SOURCE_DIR WORK_DIR" >&2
  exit 2
fi
src="$(cd "$1" && pwd)"
work="$2"
ext="$src/editors/vscode"

for tool in node npm; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "VsCodeGrammar: '$tool' not found. Install Node.js with npm (Debian: the nodejs package from" \
         "scripts/install-deps.sh; where Debian's nodejs comes without npm, also the npm package)." >&2
    exit 1
  fi
done

mkdir -p "$work"
if ! cmp -s "$ext/package.json" "$work/package.json" || ! cmp -s "$ext/package-lock.json" "$work/package-lock.json" ||
   [[ ! -d "$work/node_modules/vscode-textmate" || ! -d "$work/node_modules/vscode-oniguruma" ]]; then
  # Copies are written after a successful install only, so that an
  # interrupted one is retried next time.
  rm -f "$work/package.json" "$work/package-lock.json"
  tmp="$(mktemp -d "$work/install.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
  cp "$ext/package.json" "$ext/package-lock.json" "$tmp/"
  # --ignore-scripts: nothing here needs an install script, and none should
  # run in a test.
  (cd "$tmp" && npm ci --no-audit --no-fund --ignore-scripts --loglevel=error)
  rm -rf "$work/node_modules"
  mv "$tmp/node_modules" "$work/node_modules"
  cp "$ext/package.json" "$ext/package-lock.json" "$work/"
  rm -rf "$tmp"
  trap - EXIT
fi

exec node "$ext/test/tokenize.js" --repo "$src" --modules "$work/node_modules"
