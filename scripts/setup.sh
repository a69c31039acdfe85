#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs to build, test, benchmark and run, then
# what the web build needs (Draco's sources, web/'s npm packages).
# Runs apt-get only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  clang clang-format libclang-rt-14-dev
  libdraco-dev libglm-dev libeigen3-dev libzstd-dev
  libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libpng-dev libjpeg-dev zlib1g-dev
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev gnuplot-nox
  openmpi-bin libopenmpi-dev
  emscripten dpkg-dev chromium
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# Node.js and npm (the web decoder's tests): Debian's, unless a Node.js is installed already
# (another distribution of it brings its own npm, which Debian's npm package would conflict
# with).
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)

if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "setup: all ${#packages[@]} Debian packages present"
fi

# For the WebAssembly build and its tests (web/): Draco's sources from Debian's source
# package, and the npm packages of web/package-lock.json.
"$(dirname "$0")/fetch_draco_source.sh"
(cd "$(dirname "$0")/../web" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
