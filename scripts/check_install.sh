#!/usr/bin/env bash
# Builds the SDK alone (M4D_SDK_ONLY) and runs its tests there, configured without an install
# prefix; installs it into a scratch prefix given only at install time (as a packager or
# `cmake --install --prefix` does); checks that m4d.pc points into that prefix, that the licence
# is installed, what the shared library exports (the public m4d_* API only) and its soname;
# then builds two out-of-tree consumers against the installed SDK, one through find_package
# (CMake) and one through pkg-config (a plain Makefile), each linked shared and static, and
# checks that every one decodes a conformance stream to the suite's frame hashes.
set -euo pipefail
cd "$(dirname "$0")/.."
work=${1:-build/install-check}
stream=conformance/streams/synth_sh3_three_gops

rm -rf "$work"
prefix=$(realpath -m "$work/prefix")
cmake -S . -B "$work/sdk" -G Ninja -DCMAKE_BUILD_TYPE=Release -DM4D_WERROR=ON \
  -DM4D_SDK_ONLY=ON -DCMAKE_INSTALL_LIBDIR=lib >/dev/null
cmake --build "$work/sdk" >/dev/null
# The SDK's own tests, without the encoder: what an SDK-only build installs is what is tested.
ctest --test-dir "$work/sdk" -j2 -L sdk --output-on-failure | tail -3
cmake --install "$work/sdk" --prefix "$prefix" >/dev/null

# pkg-config's paths lead into the prefix given at install time, not the configure-time one.
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
for variable in includedir libdir; do
  dir=$(pkg-config --variable=$variable m4d)
  case $variable in includedir) want="$prefix/include" ;; libdir) want="$prefix/lib" ;; esac
  if [ "$(realpath -m "$dir")" != "$want" ]; then
    echo "check_install: m4d.pc's $variable is '$dir', expected $want" >&2
    exit 1
  fi
done
if [ ! -s "$prefix/share/doc/m4d/LICENSE" ]; then
  echo "check_install: LICENSE is not installed (share/doc/m4d/LICENSE)" >&2
  exit 1
fi

api_major=$(sed -n 's/^#define M4D_API_VERSION_MAJOR \([0-9]*\).*/\1/p' sdk/include/m4d/m4d.h)
soname=$(readelf -d "$prefix/lib/libm4d.so" | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
if [ "$soname" != "libm4d.so.$api_major" ]; then
  echo "check_install: soname '$soname', expected libm4d.so.$api_major" >&2
  exit 1
fi
# Every defined dynamic symbol is public API (or the version node).
others=$(nm -D --defined-only "$prefix/lib/libm4d.so" | awk '{print $3}' | grep -v -e '^m4d_' -e '^M4D_1$' || true)
if [ -n "$others" ]; then
  echo "check_install: libm4d.so exports more than the m4d_* API:" >&2
  echo "$others" | head -20 >&2
  exit 1
fi
exported=$(nm -D --defined-only "$prefix/lib/libm4d.so" | grep -c ' T m4d_')
declared=$(grep -ho '^M4D_API [^(]*(' sdk/include/m4d/*.h | grep -c 'm4d_')
if [ "$exported" -ne "$declared" ]; then
  echo "check_install: $exported functions exported, $declared declared in the headers" >&2
  exit 1
fi

cmake -S examples/consumers/cmake -B "$work/find_package" -G Ninja \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/find_package" >/dev/null
mkdir -p "$work/pkg_config"
make -s -C examples/consumers/make \
  OUT="$(realpath "$work/pkg_config")" CFLAGS="-O2 -Wall -Wextra -Werror"

for exe in "$work"/find_package/frame_hashes "$work"/find_package/frame_hashes_static \
           "$work"/pkg_config/frame_hashes "$work"/pkg_config/frame_hashes_static; do
  if ! "$exe" "$stream.m4d" | diff -q - "$stream.md5" >/dev/null; then
    echo "check_install: $exe does not decode $stream.m4d to its hashes" >&2
    exit 1
  fi
done
version=$(pkg-config --modversion m4d)
echo "install check: SDK $version (libm4d.so.$api_major, $exported functions exported)," \
  "installed with --prefix only, find_package and pkg-config consumers, shared and static, decode $stream.m4d bit-exactly"
