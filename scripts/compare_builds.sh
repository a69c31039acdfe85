#!/usr/bin/env bash
# Decoding is normative: a clang Debug build must decode bit-identically to the gcc Release
# build. Writes streams of several shapes with the Release tools, decodes each with both
# builds and compares the per-frame hashes.
set -euo pipefail
cd "$(dirname "$0")/.."

release=build/release
debug=build/clang-debug
[ -x "$release/tools/m4d_decode" ] || scripts/build.sh
CC=clang CXX=clang++ cmake -S . -B "$debug" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DM4D_WERROR=ON \
  -DM4D_BUILD_TESTS=OFF -DM4D_BUILD_BENCH=OFF >/dev/null
cmake --build "$debug" --target m4d_decode

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
shapes=(
  "--gops 2 --frames-per-gop 6 --static 3000 --dynamic 2000 --sh-degree 3 --seed 1"
  "--gops 3 --frames-per-gop 4 --static 500 --dynamic 4000 --sh-degree 0 --seed 2"
  "--gops 1 --frames-per-gop 8 --static 0 --dynamic 1500 --sh-degree 1 --seed 3"
)
i=0
for shape in "${shapes[@]}"; do
  # shellcheck disable=SC2086
  "$release/tools/m4d_synth" --force -o "$work/s$i.m4d" $shape >/dev/null
  for layers in all static dynamic; do
    "$release/tools/m4d_decode" -q --force --layers $layers "$work/s$i.m4d" -o "$work/gcc.md5"
    "$debug/tools/m4d_decode" -q --force --layers $layers "$work/s$i.m4d" -o "$work/clang.md5"
    if ! cmp -s "$work/gcc.md5" "$work/clang.md5"; then
      echo "compare_builds: stream $i ($shape, layers $layers): hashes differ" >&2
      diff "$work/gcc.md5" "$work/clang.md5" | head >&2
      exit 1
    fi
  done
  echo "compare_builds: stream $i: $(wc -l <"$work/gcc.md5") frames identical (gcc Release = clang Debug)"
  i=$((i + 1))
done
