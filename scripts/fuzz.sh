#!/usr/bin/env bash
# Builds the libFuzzer decode target with clang (ASan + UBSan) and fuzzes for N seconds
# (default 60) from a seed corpus of synthetic streams. Prints executions and exits non-zero
# when the fuzzer finds a crash (the reproducer is left in build/fuzz/).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}

fuzz=build/fuzz
CC=clang CXX=clang++ cmake -S . -B "$fuzz" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DM4D_FUZZ=ON -DM4D_BUILD_BENCH=OFF >/dev/null
cmake --build "$fuzz" --target decode_fuzzer m4d_synth

corpus="$fuzz/corpus"
if [ ! -d "$corpus" ]; then
  mkdir -p "$corpus"
  seed=1
  for sh in 0 1 2 3; do
    # A leading mode byte, then a small stream (see tests/fuzz/decode_fuzzer.cc).
    "$fuzz/tools/m4d_synth" -o "$fuzz/seed.m4d" --gops 2 --frames-per-gop 3 --static 60 \
      --dynamic 40 --sh-degree $sh --motion-fraction 0.001 --seed $seed >/dev/null
    for mode in 0 4 13 22; do
      { printf "\\x$(printf %02x $mode)"; cat "$fuzz/seed.m4d"; } >"$corpus/seed_${sh}_$mode"
    done
    seed=$((seed + 1))
  done
fi
cd "$fuzz"
status=0
ASAN_OPTIONS=detect_leaks=1 ./tests/decode_fuzzer -max_total_time="$seconds" -rss_limit_mb=4096 \
  -max_len=262144 -print_final_stats=1 corpus >fuzz.log 2>&1 || status=$?
grep -E "stat::number_of_executed_units|stat::peak_rss_mb|ERROR|SUMMARY|Test unit written" fuzz.log || true
if [ "$status" -ne 0 ]; then
  echo "fuzz: the fuzzer failed (exit $status); see $fuzz/fuzz.log" >&2
  exit "$status"
fi
echo "fuzz: ${seconds}s without a finding"
