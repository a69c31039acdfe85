#!/usr/bin/env bash
# The test command: installs dependencies, builds, checks formatting, checks that a clang
# Debug build decodes bit-identically to the gcc Release build, runs our decoder through the
# conformance runner, builds the WebAssembly decoder and checks it the same way under Node.js
# (scripts/test_web.sh), runs a short fuzz session, runs the whole test suite, installs the SDK
# alone and builds out-of-tree consumers against it, then builds
# everything with ASan and UBSan and runs the whole test suite again under them, and the
# threaded unit tests under ThreadSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."

# Each step's wall time, so that a slow run says where its time went.
timed() {
  local start=$SECONDS
  "$@"
  echo "test.sh: ${1##*/} took $((SECONDS - start)) s"
}

timed scripts/setup.sh
timed scripts/build.sh
timed scripts/check_format.sh
timed scripts/compare_builds.sh
scripts/conformance_run.sh --layers-flag --layers build/release/tools/m4d_decode | tail -1
timed scripts/test_web.sh
timed scripts/fuzz.sh "${M4D_FUZZ_SECONDS:-60}"
timed ctest --test-dir build/release --output-on-failure -j2
timed scripts/check_install.sh
timed scripts/sanitize.sh
timed scripts/tsan.sh
