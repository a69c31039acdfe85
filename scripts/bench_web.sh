#!/usr/bin/env bash
# The WebAssembly decoder against the native SDK, and the web player's frame rate:
#   - decode time per packet type, per inter frame and per keyframe, one thread, best of 5
#     (bench/packet_decode_times.cc and web/bench/packet_decode_times.mjs), on a synthetic
#     stream of the decode budgets' size (100k static and 100k dynamic Gaussians, SH degree 3,
#     the paper's grid and MLP) and on any streams given;
#   - frames per second of web/player at 1280x720 in headless Chromium (SwiftShader).
#
#   scripts/bench_web.sh [STREAM...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh m4d_packet_times m4d_synth >/dev/null
scripts/build_web.sh >/dev/null
work=build/web/bench
mkdir -p "$work"
synth=$work/synth_100k_sh3.m4d
[ -f "$synth" ] || build/release/tools/m4d_synth -o "$synth" --gops 1 --frames-per-gop 4 \
  --static 100000 --dynamic 100000 --sh-degree 3 >/dev/null
streams=("$synth" "$@")

printf "%-28s %-18s %12s %12s %8s\n" stream row "native ms" "wasm ms" ratio
for stream in "${streams[@]}"; do
  build/release/bench/m4d_packet_times "$stream" >"$work/native.txt"
  node web/bench/packet_decode_times.mjs "$stream" >"$work/wasm.txt"
  join <(sort "$work/native.txt") <(sort "$work/wasm.txt") |
    awk -v s="$(basename "$stream" .m4d)" '$1 != "sequence_header" {
      ratio = $3 >= 0.01 ? sprintf("%7.2fx", $6 / $3) : "      -"
      printf "%-28s %-18s %12.2f %12.2f %s\n", s, $1, $3, $6, ratio }'
done
echo
printf "%-28s %6s %10s %10s %8s %10s %8s %8s\n" stream fps "render ms" "decode ms" splats \
  "project" "sort" "GL draw"
for stream in "${streams[@]}"; do
  read -r fps render decode splats project sort draw < <(node web/bench/player_fps.mjs "$stream" --seconds 10)
  printf "%-28s %6s %10s %10s %8s %10s %8s %8s\n" "$(basename "$stream" .m4d)" "$fps" "$render" \
    "$decode" "$splats" "$project" "$sort" "$draw"
done
