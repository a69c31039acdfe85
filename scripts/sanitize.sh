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
# Without MPI: Open MPI's own allocations at exit would fail the leak check; the Release build
# tests the MPI path (m4d_encode_chunks_and_mpi), and its chunked single-process half runs here.
CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DM4D_SANITIZE=address,undefined -DM4D_FUZZ=ON -DM4D_WERROR=ON -DM4D_BUILD_BENCH=OFF -DM4D_WITH_MPI=OFF >/dev/null
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
log=$dir/Testing/sanitize_ctest.log
mkdir -p "$dir/Testing"
if ctest --test-dir "$dir" --output-on-failure -j2 2>&1 | tee "$log"; then
  exit 0
fi
# LeakSanitizer's tracer thread sometimes dies while it stops a process with many threads
# (llvmpipe's) and reports "LeakSanitizer has encountered a fatal error": a fault of the
# checker, not a finding. When every failed test failed that way and no sanitizer reported
# anything, those tests run again, twice with the leak check; if its tracer still fails, once
# more without it (AddressSanitizer, UBSan and the test's assertions still apply). A real
# leak, memory error or assertion still fails.
only_tracer_failures() {
  local failed checker findings
  failed=$(grep -c . "$dir/Testing/Temporary/LastTestsFailed.log" || true)
  checker=$(grep -c "LeakSanitizer has encountered a fatal error" "$1" || true)
  findings=$(grep -cE "ERROR: (Address|Leak)Sanitizer|runtime error:|Failure$" "$1" || true)
  [ "$failed" -gt 0 ] && [ "$checker" -ge "$failed" ] && [ "$findings" -eq 0 ]
}
for attempt in 1 2; do
  only_tracer_failures "$log" || exit 1
  echo "sanitize: LeakSanitizer's tracer failed; running the failed test(s) again ($attempt)"
  log=$dir/Testing/sanitize_rerun_$attempt.log
  if ctest --test-dir "$dir" --output-on-failure --rerun-failed 2>&1 | tee "$log"; then
    exit 0
  fi
done
only_tracer_failures "$log" || exit 1
echo "sanitize: LeakSanitizer's tracer failed three times; the failed test(s) once more without"
echo "sanitize: the leak check (it could not run there), every other check still on"
ASAN_OPTIONS=${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0} \
  ctest --test-dir "$dir" --output-on-failure --rerun-failed
