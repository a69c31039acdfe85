#!/usr/bin/env bash
# The test command: installs dependencies, builds, checks formatting and the library
# boundaries, checks that a clang Debug build decodes bit-identically to the gcc Release build,
# runs our decoder through the conformance runner, builds the WebAssembly decoder and checks it
# the same way under Node.js (scripts/test_web.sh), runs a short fuzz session, runs the whole
# test suite, installs the SDK alone and builds out-of-tree consumers against it, then builds
# everything with ASan and UBSan and runs the whole test suite again under them, and the
# threaded unit tests under ThreadSanitizer.
#
# --quick: the tier for every change (a few minutes after a first build): build, format,
# library boundaries and the unit tests of every library, nothing else.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0
case "${1:-}" in
  --quick) quick=1 ;;
  "") ;;
  *) echo "usage: scripts/test.sh [--quick]" >&2; exit 2 ;;
esac

# Each step's wall time, at its end and again in a table at the end of the run, so that a
# slow run says where its time went.
steps=()
timed() {
  local start=$SECONDS
  "$@"
  local took=$((SECONDS - start))
  steps+=("$(printf '%-28s %5d s' "${1##*/} ${2:-}" "$took")")
  echo "test.sh: ${1##*/} took $took s"
}
summary() {
  echo "test.sh: time by step"
  printf '  %s\n' "${steps[@]}"
  echo "  total                        $SECONDS s"
}

timed scripts/setup.sh
timed scripts/build.sh
timed scripts/check_format.sh
timed scripts/check_layout.sh
if [ "$quick" = 1 ]; then
  timed ctest --test-dir build/release --output-on-failure -j2 -L 'unit|sdk'
  summary
  exit 0
fi
timed scripts/compare_builds.sh
scripts/conformance_run.sh --layers-flag --layers build/release/tools/m4d_decode | tail -1
timed scripts/test_web.sh
timed scripts/fuzz.sh "${M4D_FUZZ_SECONDS:-60}"
timed ctest --test-dir build/release --output-on-failure -j2
timed scripts/check_install.sh
timed scripts/sanitize.sh
timed scripts/tsan.sh
summary
