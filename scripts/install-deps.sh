#!/bin/sh
# Installs every Debian package crowdbake needs to build, test and run.
# Idempotent: when everything is already installed it prints nothing and exits 0.
set -eu

PACKAGES="cmake g++ ninja-build pkg-config ccache clang-format
  libassimp-dev assimp-utils libopenmesh-dev libdraco-dev draco libtinygltf-dev libcli11-dev nlohmann-json3-dev
  libcgal-dev
  libgtest-dev libgmock-dev libbenchmark-dev libeigen3-dev libglm-dev libmeshoptimizer-dev libtbb-dev libstb-dev libjpeg-dev libzstd-dev gnuplot-nox
  libvulkan-dev mesa-vulkan-drivers vulkan-tools vulkan-validationlayers glslc glslang-tools spirv-tools
  clang libclang-rt-14-dev"

missing=""
for p in $PACKAGES; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
# Node.js (for the Khronos glTF validator used by tests) may come from Debian or nodesource.
command -v npm >/dev/null 2>&1 || missing="$missing nodejs npm"
[ -z "$missing" ] && exit 0

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "installing:$missing"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
