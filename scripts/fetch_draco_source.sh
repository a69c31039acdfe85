#!/usr/bin/env bash
# Fetches the sources of Debian's draco source package, the version the installed
# libdraco-dev is built from, into build/web/draco-<version> (once), for the WebAssembly
# build (scripts/build_web.sh). apt keeps its source index in build/web/apt: the machine's
# apt configuration is not changed. Called by scripts/setup.sh.
#
#   scripts/fetch_draco_source.sh [--print-dir]   (--print-dir: only print where they go)
set -euo pipefail
cd "$(dirname "$0")/.."
web=$PWD/build/web
draco_version=$(dpkg-query -W -f='${source:Version}' libdraco-dev)
draco_src=$web/draco-$draco_version
if [ "${1:-}" = "--print-dir" ]; then
  echo "$draco_src"
  exit 0
fi
if [ ! -f "$draco_src/src/draco/compression/decode.cc" ]; then
  echo "setup: fetching Debian's draco $draco_version sources"
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
  # apt checked the files against the signed index; the .dsc's own signature needs the
  # Debian developers' keyring, which is not installed.
  dpkg-source --no-check -x "$apt_dir"/download/draco_*.dsc "$draco_src.tmp" >/dev/null
  rm -f "$web"/draco_*.orig.tar.*
  mv "$draco_src.tmp" "$draco_src"
fi
