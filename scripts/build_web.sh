#!/usr/bin/env bash
# Builds the WebAssembly decoder (web/, build/web/module: m4d.mjs and m4d.wasm) with
# Debian's Emscripten. Draco is compiled from the sources of Debian's draco source package,
# the version libdraco-dev is built from, fetched once into build/web/ with apt's source
# index kept there too (the machine's apt configuration is not changed).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
web=$root/build/web
mkdir -p "$web"

draco_version=$(dpkg-query -W -f='${source:Version}' libdraco-dev)
draco_src=$web/draco-$draco_version
if [ ! -f "$draco_src/src/draco/compression/decode.cc" ]; then
  echo "build_web: fetching Debian's draco $draco_version sources"
  apt_dir=$web/apt
  mkdir -p "$apt_dir/lists/partial" "$apt_dir/sources"
  cat >"$apt_dir/sources/debian-src.sources" <<SOURCES
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SOURCES
  apt_opts=(-o Dir::Etc::SourceList=/dev/null -o "Dir::Etc::SourceParts=$apt_dir/sources"
            -o "Dir::State::Lists=$apt_dir/lists" -o APT::Sandbox::User=root)
  apt-get "${apt_opts[@]}" update >/dev/null
  rm -rf "$apt_dir/download" && mkdir -p "$apt_dir/download"
  (cd "$apt_dir/download" && apt-get "${apt_opts[@]}" source --download-only \
     "draco=$draco_version" >/dev/null)
  rm -rf "$draco_src.tmp"
  dpkg-source -x "$apt_dir"/download/draco_*.dsc "$draco_src.tmp" >/dev/null
  mv "$draco_src.tmp" "$draco_src"
fi

# Emscripten's JavaScript optimiser needs Debian's acorn (node-acorn), which a Node.js other
# than Debian's does not look for.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
emcmake cmake -S web -B "$web/module" -G Ninja -DDRACO_SOURCE_DIR="$draco_src" 2>&1 >/dev/null |
  { grep -v '^configure: ' || true; } >&2
cmake --build "$web/module"
