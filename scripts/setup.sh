#!/usr/bin/env bash
# Installs every Debian package depthprec needs. Idempotent: packages already present are
# not touched, so a second run costs one dpkg query and no network.
set -euo pipefail

PACKAGES=(
  build-essential cmake
  pocl-opencl-icd ocl-icd-opencl-dev opencl-clhpp-headers clinfo
  libglm-dev libtinygltf-dev libpng-dev catch2 libcli11-dev nlohmann-json3-dev libfmt-dev
  gnuplot-nox clang-format parallel python3 chromium
  pkg-config libepoxy-dev libegl1 libgl1 libegl-mesa0 libgl1-mesa-dri dpkg-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
