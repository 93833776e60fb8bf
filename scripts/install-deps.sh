#!/usr/bin/env bash
# Installs the Debian 12 packages Fissure builds and tests with, skipping those already present.
# Usage: scripts/install-deps.sh [--gui]   (--gui adds what the studio's screenshot test needs)
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config git
  libeigen3-dev libspectra-dev libcgal-dev libgmp-dev libmpfr-dev libtbb-dev
  libsuitesparse-dev libopenblas-dev
  libgmsh-dev gmsh
  libassimp-dev assimp-utils libpugixml-dev
  libopencv-dev
  libpng-dev libjpeg62-turbo-dev libtiff-dev zlib1g-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev
  qtbase5-dev libqt5opengl5-dev libglfw3-dev libgl-dev
  python3
)
if [[ "${1:-}" == "--gui" ]]; then
  packages+=(xvfb xauth mesa-utils libgl1-mesa-dri)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
