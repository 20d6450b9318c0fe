#!/usr/bin/env bash
# Builds the Debian package with CPack, checks its contents and Depends
# (dpkg-deb), unpacks it into a temporary directory (dpkg -x) and compiles a
# shader with the unpacked spirec, which must find the unpacked Spire library.
# Usage: deb_test.sh BUILD_DIR
set -euo pipefail

build="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

fail() {
  echo "deb_test: $*" >&2
  exit 1
}

cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/out" >"$tmp/cpack.log" || { cat "$tmp/cpack.log"; fail "cpack failed"; }
debs=("$tmp"/out/*.deb)
[[ ${#debs[@]} -eq 1 && -f "${debs[0]}" ]] || fail "cpack made no single .deb: ${debs[*]}"
deb="${debs[0]}"
echo "deb_test: $(basename "$deb"), $(du -h "$deb" | cut -f1)"

dpkg-deb --contents "$deb" >"$tmp/contents"
for file in usr/bin/spirec usr/bin/spire-demo usr/bin/spire-tune usr/include/spire/driver/compiler.h \
  usr/lib/libspire_compiler.a usr/share/spire/stdlib/lighting.spire usr/share/spire/pipelines/engine.spire \
  usr/lib/cmake/Spire/SpireConfig.cmake usr/lib/cmake/Spire/SpireShaders.cmake; do
  grep -q " \./$file\$" "$tmp/contents" || fail "the package has no /$file"
done
depends="$(dpkg-deb --field "$deb" Depends)"
for package in libc6 libstdc++6 libfmt9 libvulkan1 libglfw3; do
  grep -qw "$package" <<<"$depends" || fail "Depends lacks $package: $depends"
done

dpkg -x "$deb" "$tmp/root"
spirec="$tmp/root/usr/bin/spirec"
"$spirec" --help | grep -qF "$tmp/root/usr/share/spire" || fail "the unpacked spirec does not find its library"
cat >"$tmp/flat.spire" <<'SPIRE'
using "pipelines/engine.spire";
shader Flat using EnginePipeline {
    @FrameUniform mat4 matMVP;
    @MaterialUniform vec3 color;
    vec4 projPos = matMVP * vec4(vert_pos, 1.0);
    vec4 output = vec4(color, 1.0);
}
SPIRE
"$spirec" "$tmp/flat.spire" -o "$tmp/kernels" -Werror || fail "the unpacked spirec failed"
[[ -f "$tmp/kernels/Flat/Fragment.spv" ]] || fail "no kernels/Flat/Fragment.spv"
echo "deb_test: passed"
