#!/usr/bin/env bash
# Builds the Debian package with CPack, checks its size, contents and Depends
# (dpkg-deb), unpacks it into a temporary directory (dpkg -x), checks that its
# static libraries have no debug info, compiles a shader with the unpacked
# spirec, which must find the unpacked Spire library, and configures a project
# that finds the unpacked CMake package with find_package(Spire).
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
size="$(stat -c %s "$deb")"
echo "deb_test: $(basename "$deb"), $size bytes"
# Stripped, the package is 18 MB; with the libraries' debug info it was
# 50 MB (cmake/SpireDebian.cmake).
max_size=$((30 * 1024 * 1024))
((size < max_size)) || fail "the package is $size bytes, over $max_size: are the libraries stripped?"

# Debian's library folder: /usr/lib/<multiarch triplet>.
triplet="$(dpkg-architecture -qDEB_HOST_MULTIARCH)"
libdir="usr/lib/$triplet"
dpkg-deb --contents "$deb" >"$tmp/contents"
for file in usr/bin/spirec usr/bin/spire-demo usr/bin/spire-tune usr/include/spire/driver/compiler.h \
  "$libdir/libspire_compiler.a" "$libdir/libspire_support.a" usr/share/spire/stdlib/lighting.spire \
  usr/share/spire/pipelines/engine.spire "$libdir/cmake/Spire/SpireConfig.cmake" \
  "$libdir/cmake/Spire/SpireConfigVersion.cmake" "$libdir/cmake/Spire/SpireCompilerTargets.cmake" \
  "$libdir/cmake/Spire/SpireShaders.cmake"; do
  grep -q " \./$file\$" "$tmp/contents" || fail "the package has no /$file"
done
if grep -E " \./usr/lib/(libspire_|cmake/)" "$tmp/contents"; then
  fail "the package has libraries or a CMake package outside /$libdir"
fi
depends="$(dpkg-deb --field "$deb" Depends)"
for package in libc6 libstdc++6 libfmt9 libvulkan1 libglfw3; do
  grep -qw "$package" <<<"$depends" || fail "Depends lacks $package: $depends"
done

dpkg -x "$deb" "$tmp/root"
archives=("$tmp/root/$libdir"/libspire_*.a)
((${#archives[@]} == 7)) || fail "expected 7 libraries in /$libdir: ${archives[*]}"
for archive in "${archives[@]}"; do
  # readelf lists the sections of every member of the archive.
  if readelf -S --wide "$archive" | grep -q '\.debug_info'; then fail "$(basename "$archive") has debug info"; fi
done
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

# A project that enables no language finds the package through
# usr/share/cmake/Spire (CMake searches lib/<triplet> only with a language).
mkdir "$tmp/shaders-only" "$tmp/consumer"
cat >"$tmp/shaders-only/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(DebShadersOnly LANGUAGES NONE)
find_package(Spire 0.1 REQUIRED)
get_target_property(configs Spire::spirec IMPORTED_CONFIGURATIONS)
list(GET configs 0 config)
get_target_property(spirec Spire::spirec IMPORTED_LOCATION_${config})
file(REAL_PATH "${spirec}" spirec)
message(STATUS "found: ${spirec}")
CMAKE
root="$(realpath "$tmp/root")"
cmake -S "$tmp/shaders-only" -B "$tmp/shaders-only-build" -DCMAKE_PREFIX_PATH="$root/usr" >"$tmp/shaders-only.log" 2>&1 ||
  { cat "$tmp/shaders-only.log"; fail "find_package(Spire) failed on the unpacked package without a language"; }
grep -qF -- "found: $root/usr/bin/spirec" "$tmp/shaders-only.log" || { cat "$tmp/shaders-only.log"; fail "spirec not found"; }

# A project with CXX enabled finds it under lib/<triplet>, with the
# libraries, and prints where its targets are.
cat >"$tmp/consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(DebConsumer LANGUAGES CXX)
find_package(Spire 0.1 REQUIRED COMPONENTS compiler)
get_target_property(configs Spire::compiler IMPORTED_CONFIGURATIONS)
list(GET configs 0 config)
get_target_property(compiler Spire::compiler IMPORTED_LOCATION_${config})
get_target_property(spirec Spire::spirec IMPORTED_LOCATION_${config})
foreach(file IN ITEMS "${compiler}" "${spirec}")
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "no ${file}")
  endif()
endforeach()
file(REAL_PATH "${Spire_DIR}" dir)
file(REAL_PATH "${Spire_LIBRARY_DIR}" library)
file(REAL_PATH "${compiler}" compiler)
file(REAL_PATH "${spirec}" spirec)
message(STATUS "found: ${dir} ${library} ${compiler} ${spirec}")
CMAKE
cmake -S "$tmp/consumer" -B "$tmp/consumer-build" -DCMAKE_PREFIX_PATH="$root/usr" >"$tmp/consumer.log" 2>&1 ||
  { cat "$tmp/consumer.log"; fail "find_package(Spire) failed on the unpacked package"; }
expected="found: $root/$libdir/cmake/Spire $root/usr/share/spire $root/$libdir/libspire_compiler.a $root/usr/bin/spirec"
grep -qF -- "$expected" "$tmp/consumer.log" || { cat "$tmp/consumer.log"; fail "expected '$expected'"; }
echo "deb_test: passed"
