#!/usr/bin/env bash
# Configures and builds the Release tree (build/release) with warnings as errors: every
# target, or only the targets named as arguments.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DM4D_WERROR=ON >/dev/null
cmake --build build/release ${1:+--target "$@"}
