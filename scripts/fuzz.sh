#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan, in scripts/sanitize.sh's tree),
# fuzzes the whole decode loop for N seconds (default 60) from a seed corpus of synthetic and
# conformance streams, then each other stream target (packet headers, every layer decoder,
# allocation failure) for M4D_FUZZ_EACH seconds (default 10), then the encoder's file parsers
# (PLY, COLMAP, PNG/JPEG, NPY/NPZ) for M4D_FUZZ_FILES seconds (default 5). Prints executions
# per target and exits non-zero when a fuzzer finds a crash (the reproducer is left in
# build/sanitize/).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}

fuzz=build/sanitize
targets=(packet_header_fuzzer gaussian_set_fuzzer mlp_weights_fuzzer motion_grid_fuzzer
  symbol_block_fuzzer inter_frame_fuzzer alloc_failure_fuzzer)
# The encoder's input parsers: capture files come from anywhere too.
file_targets=(ply_fuzzer colmap_fuzzer image_decode_fuzzer npy_fuzzer npz_fuzzer)
scripts/sanitize.sh --targets decode_fuzzer m4d_synth "${targets[@]}" "${file_targets[@]}"

corpus="$fuzz/corpus"
if [ ! -d "$corpus" ]; then
  mkdir -p "$corpus"
  seed=1
  for sh in 0 1 2 3; do
    # A leading mode byte, then a small stream (see tests/fuzz/decode_fuzzer.cc).
    "$fuzz/tools/m4d_synth" --force -o "$fuzz/seed.m4d" --gops 2 --frames-per-gop 3 --static 60 \
      --dynamic 40 --sh-degree $sh --motion-fraction 0.001 --seed $seed >/dev/null
    for mode in 0 4 13 22; do
      { printf "\\x$(printf %02x $mode)"; cat "$fuzz/seed.m4d"; } >"$corpus/seed_${sh}_$mode"
    done
    seed=$((seed + 1))
  done
  # The conformance streams, every layer choice, checksums off (mode 0..2).
  for stream in conformance/streams/*.m4d; do
    for mode in 0 1 2; do
      { printf "\\x0$mode"; cat "$stream"; } >"$corpus/$(basename "$stream" .m4d)_$mode"
    done
  done
fi
cd "$fuzz"
# run TARGET SECONDS CORPUS...: fuzzes, prints executions, stops the script on a finding.
run() {
  local target=$1 seconds=$2 status=0
  shift 2
  mkdir -p "corpus_$target"
  ASAN_OPTIONS=detect_leaks=1 "./tests/$target" -max_total_time="$seconds" -rss_limit_mb=4096 \
    -max_len=262144 -print_final_stats=1 "corpus_$target" "$@" >"$target.log" 2>&1 || status=$?
  printf "%-24s %8s s %12s executions\n" "$target" "$seconds" \
    "$(grep -o 'stat::number_of_executed_units: [0-9]*' "$target.log" | grep -o '[0-9]*$')"
  if [ "$status" -ne 0 ]; then
    grep -E "ERROR|SUMMARY|Test unit written" "$target.log" || true
    echo "fuzz: $target failed (exit $status); see $fuzz/$target.log" >&2
    exit "$status"
  fi
}
run decode_fuzzer "$seconds" corpus
run packet_header_fuzzer "${M4D_FUZZ_EACH:-10}" ../../conformance/streams
for target in "${targets[@]:1}"; do run "$target" "${M4D_FUZZ_EACH:-10}"; done
for target in "${file_targets[@]}"; do run "$target" "${M4D_FUZZ_FILES:-5}"; done
echo "fuzz: no finding"
