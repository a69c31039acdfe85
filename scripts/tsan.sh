#!/usr/bin/env bash
# Builds the threaded test suites with clang under ThreadSanitizer (build/tsan) and runs those
# that use threads: the decoder's and renderer's thread pool (decoder threads setting, threaded
# motion application and rendering) and the encoder's (parallel rows, Adam, SSIM, splat
# gradients, view batches, keyframe training on two threads). Any report fails the run.
#
#   scripts/tsan.sh [--build-only]
set -euo pipefail
cd "$(dirname "$0")/.."
dir=build/tsan
# -O1 and line tables only, as scripts/sanitize.sh: reports with file and line, cheap to build.
CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DM4D_SANITIZE=thread -DM4D_WERROR=ON -DM4D_BUILD_BENCH=OFF -DM4D_BUILD_TOOLS=OFF \
  -DM4D_WITH_MPI=OFF >/dev/null
cmake --build "$dir" --target m4d_threaded_tests
[ "${1:-}" = "--build-only" ] && exit 0
tests=(
  StreamInfo.EveryThreadCountDecodesTheSameFrames
  MotionApplicationTest.AThreadPoolGivesTheSameBits
  SplatRendererTest.*Thread*
  ParallelRowsTest.*
  AdamOptimizerTest.ThreadPoolGivesTheSameResult
  SsimTest.LargeImage*
  SplatBackwardTest.GradientsDoNotDependOnThreads
  ViewBatchGradientsTest.ViewsOnTwoThreadsGiveTheOneThreadResultBitForBit
  KeyframeTrainerTest.SameSeedSameModelWhateverTheThreads
)
filter=$(IFS=:; echo "${tests[*]}")
TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 "$dir/tests/m4d_threaded_tests" --gtest_filter="$filter"
