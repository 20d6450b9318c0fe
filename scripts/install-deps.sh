#!/usr/bin/env bash
# Installs the Debian 12 packages that spirec, its tests, the benchmarks, the
# fuzzer and the engine demo need. Idempotent: every package is checked with
# dpkg-query first, and apt-get runs only when something is missing (so it is
# silent and offline on a machine that already has everything).
set -euo pipefail

PACKAGES=(
  # toolchain
  cmake g++ ninja-build pkg-config ccache
  # the InstallAndUsePackage test builds a project with Unix Makefiles too
  make
  # the Format test (.clang-format) and the .clang-tidy checks
  clang-format clang-tidy
  # shader tooling and Vulkan (code generation checks, engine demo)
  glslang-dev glslang-tools spirv-tools
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  libglfw3-dev libglm-dev libtinygltf-dev libstb-dev
  # spire-explore's panels (libimgui.a has the GLFW and Vulkan backends)
  libimgui-dev
  # libraries used by the compiler
  nlohmann-json3-dev libcli11-dev libfmt-dev
  # tests and benchmarks (python3-jsonschema: the reflection schema test;
  # xvfb and xauth, which xvfb-run needs but xvfb only recommends: the
  # window tests without a display)
  libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth python3-jsonschema
  # CompileServerTest runs spirec under strace: a traced run stays in its
  # own process
  strace
  # libFuzzer targets (fuzz preset); llvm: llvm-symbolizer, which
  # bench/fuzz-all's coverage report (-print_coverage) needs
  clang libclang-rt-14-dev llvm
  # the VsCodeGrammar test (editors/vscode) runs Node.js and npm. Only
  # nodejs: NodeSource's nodejs bundles npm and conflicts with Debian's npm
  # package, so where Debian's own nodejs lacks npm, install npm by hand
  # (the test says so when npm is missing).
  nodejs
  # the ReportHtmlInChromium test opens spire-tune's report.html in a real
  # browser (headless, no display): the page must render without console
  # errors and show its plot
  chromium
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  status="$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)"
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

echo "install-deps: installing ${#missing[@]} missing package(s): ${missing[*]}" >&2

SUDO=()
if [[ "$(id -u)" -ne 0 ]]; then
  if ! command -v sudo >/dev/null 2>&1; then
    echo "install-deps: not root and sudo is not available; install as root: apt-get install ${missing[*]}" >&2
    exit 1
  fi
  SUDO=(sudo)
fi

export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update </dev/null
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" </dev/null
