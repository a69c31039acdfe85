#!/usr/bin/env bash
# Encoder time per inter frame by stage over image size and camera count, on generated scenes
# (m4d scene, 3 frames each; m4d bench with short settings: a 300-step keyframe of at most
# 60 000 Gaussians, a lookahead of 1, 100 motion steps after the first inter frame's 300 with
# the MLP). Prints a table and writes it beside the runs; pass two m4d binaries to compare
# builds (the second column set is the second binary's).
#
#   scripts/bench_encode_scaling.sh [OUT_DIR] M4D [M4D_BEFORE]
set -euo pipefail
out=${1:-out/encode-scaling}
m4d=${2:-build/release/tools/m4d/m4d}
before=${3:-}
configs=${M4D_SCALING_CONFIGS:-"320x240x16 640x480x16 1352x1014x16 320x240x8 320x240x30"}
opts=(--frames 3 --keyframe-iterations 300 --max-gaussians 60000 --prune-share 0.1
      --lookahead 1 --first-motion-iterations 300 --motion-iterations 100 --decode-runs 1)
mkdir -p "$out"

# "motion compensation total" of bench's mean over inter frames.
inter_mean() { awk '/^inter mean/ && !done {print $5, $6, $9; done = 1}' "$1"; }

run() {  # binary, config, label -> "motion compensation total"
  local w h n scene dir
  IFS=x read -r w h n <<< "$2"
  scene=$out/scene_$2
  [ -d "$scene" ] || "$1" scene -o "$scene" --cameras "$n" --width "$w" --height "$h" \
    --frames 3 > /dev/null 2>&1
  dir=$out/$3_$2
  "$1" bench "$scene" -o "$dir" "${opts[@]}" > "$dir.log" 2>&1
  inter_mean "$dir.log"
}

table=$out/scaling.txt
{
  printf "%-16s %9s %9s %9s" "size x cameras" "motion s" "comp. s" "total s"
  [ -n "$before" ] && printf " | %9s %9s %9s" "before" "" ""
  printf "\n"
} | tee "$table"
for c in $configs; do
  line=$(printf "%-16s %9s %9s %9s" "$c" $(run "$m4d" "$c" after))
  [ -n "$before" ] && line="$line | $(printf "%9s %9s %9s" $(run "$before" "$c" before))"
  echo "$line" | tee -a "$table"
done
