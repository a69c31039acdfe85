#!/usr/bin/env bash
# Builds everything with clang under AddressSanitizer and UndefinedBehaviorSanitizer
# (build/sanitize, shared with the fuzz targets of scripts/fuzz.sh) and runs the whole test
# suite there. Any report fails the run: UBSan does not recover, leaks are errors except
# inside Mesa's GL driver and LLVM (scripts/lsan_suppressions.txt), which the GL tests load.
#
#   scripts/sanitize.sh [--build-only | --targets TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
dir=build/sanitize
# -O1 and line tables only: stack traces with file and line, at half the build time of -O2 -g.
CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DM4D_SANITIZE=address,undefined -DM4D_FUZZ=ON -DM4D_WERROR=ON -DM4D_BUILD_BENCH=OFF >/dev/null
if [ "${1:-}" = "--targets" ]; then
  shift
  cmake --build "$dir" --target "$@"
  exit 0
fi
cmake --build "$dir"
[ "${1:-}" = "--build-only" ] && exit 0
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$PWD/scripts/lsan_suppressions.txt:print_suppressions=0
ctest --test-dir "$dir" --output-on-failure -j2
