#!/usr/bin/env bash
# Builds the WebAssembly decoder (web/, build/web/module: m4d.mjs, m4d_wasm.mjs and
# m4d_wasm.wasm) with Debian's Emscripten. Draco is compiled from the sources of Debian's
# draco source package, which scripts/setup.sh fetches (scripts/fetch_draco_source.sh):
# nothing is downloaded here.
set -euo pipefail
cd "$(dirname "$0")/.."
web=$PWD/build/web

draco_src=$(scripts/fetch_draco_source.sh --print-dir)
if [ ! -f "$draco_src/src/draco/compression/decode.cc" ]; then
  echo "build_web: no Draco sources in $draco_src: run scripts/setup.sh" >&2
  exit 2
fi

# Emscripten's JavaScript optimiser needs Debian's acorn (node-acorn), which a Node.js other
# than Debian's does not look for.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
emcmake cmake -S web -B "$web/module" -G Ninja -DDRACO_SOURCE_DIR="$draco_src" 2>&1 >/dev/null |
  { grep -v '^configure: ' || true; } >&2
cmake --build "$web/module"
