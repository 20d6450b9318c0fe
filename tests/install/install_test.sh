#!/usr/bin/env bash
# Installs Spire into a temporary prefix, moves the prefix (the install must be
# relocatable), then builds tests/install/project, a user's project using
# find_package(Spire) and spire_add_shaders(), once with Ninja and once with
# Unix Makefiles. For each: a second build does nothing; after the file that
# only lit.spire uses is touched, the build tool's own dry run names lit.spire
# and not flat.spire, and the rebuild rewrites Lit's kernels and not Flat's.
# The kernels of both builds are the same bytes (no build directory in them).
# With Ninja the project also links a program on Spire::compiler and runs it.
# Usage: install_test.sh BUILD_DIR PROJECT_DIR
set -euo pipefail

build="$1"
project="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

fail() {
  echo "install_test: $*" >&2
  exit 1
}

cmake --install "$build" --prefix "$tmp/staging" >"$tmp/install.log"
mv "$tmp/staging" "$tmp/prefix"
prefix="$tmp/prefix"
for file in bin/spirec include/spire/driver/compiler.h share/spire/stdlib/lighting.spire \
  share/spire/pipelines/engine.spire lib/cmake/Spire/SpireConfig.cmake lib/cmake/Spire/SpireConfigVersion.cmake; do
  [[ -e "$prefix/$file" ]] || fail "the install has no $file"
done
"$prefix/bin/spirec" --help | grep -qF "$prefix/share/spire" || fail "the moved spirec does not name its library"
cp -r "$project" "$tmp/src"

# mtime of FILE in nanoseconds
mtime() { stat -c %.9Y "$1"; }

# check_rebuild GENERATOR BUILD_DIR: a second build does nothing; after
# shared.spire is touched, the build compiles lit.spire and not flat.spire.
check_rebuild() {
  local generator="$1" dir="$2" dry lit flat
  lit="$(mtime "$dir/kernels/Lit/reflection.json")"
  flat="$(mtime "$dir/kernels/Flat/reflection.json")"
  cmake --build "$dir" >"$dir/second.log"
  [[ "$(mtime "$dir/kernels/Lit/reflection.json")" == "$lit" ]] || fail "$generator: a second build compiled again"
  touch "$tmp/src/shaders/shared.spire"
  if [[ "$generator" == Ninja ]]; then
    dry="$(cmake --build "$dir" -- -n -d explain 2>&1)"
  else
    dry="$(cmake --build "$dir" -- -n 2>&1)"
  fi
  grep -q "lit.spire" <<<"$dry" || fail "$generator: the dry run does not rebuild lit.spire: $dry"
  if grep -q "flat.spire" <<<"$dry"; then fail "$generator: the dry run rebuilds flat.spire too: $dry"; fi
  cmake --build "$dir" >"$dir/third.log"
  [[ "$(mtime "$dir/kernels/Lit/reflection.json")" != "$lit" ]] || fail "$generator: Lit was not rebuilt"
  [[ "$(mtime "$dir/kernels/Flat/reflection.json")" == "$flat" ]] || fail "$generator: Flat was rebuilt"
}

for generator in Ninja "Unix Makefiles"; do
  dir="$tmp/build-${generator// /-}"
  link=OFF
  [[ "$generator" == Ninja ]] && link=ON
  cmake -S "$tmp/src" -B "$dir" -G "$generator" -DCMAKE_PREFIX_PATH="$prefix" \
    -DSPIRE_CONSUMER_LINK_LIBRARY="$link" >"$tmp/configure.log" || { cat "$tmp/configure.log"; fail "$generator: configure failed"; }
  cmake --build "$dir" >"$dir/first.log" 2>&1 || { cat "$dir/first.log"; fail "$generator: build failed"; }
  for shader in Lit Flat; do
    [[ -f "$dir/kernels/$shader/reflection.json" ]] || fail "$generator: no kernels/$shader/reflection.json"
  done
  check_rebuild "$generator" "$dir"
  echo "install_test: $generator: touching shared.spire rebuilt Lit only"
done
diff -r "$tmp/build-Ninja/kernels" "$tmp/build-Unix-Makefiles/kernels" || fail "the kernels depend on the build directory"
"$tmp/build-Ninja/compile_lit" "$tmp/src/shaders/lit.spire" "$(cat "$tmp/build-Ninja/library_dir.txt")"
echo "install_test: passed"
