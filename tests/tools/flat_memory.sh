#!/bin/sh
# Memory stays flat over a long capture: frames are loaded when a stage needs them and dropped
# after, so coding 300 frames of a small generated capture peaks at no more memory than coding
# its first 30 (within 10 % and 4 MB: the stream and the per-frame reports, a few kilobytes a
# frame, are all that may grow).
#   flat_memory.sh M4D DIR
set -eu
m4d=$1
dir=$2
opts="--keyframe-iterations 60 --retrain-iterations 20 --motion-iterations 5 \
--compensation-iterations 5 --lookahead 1 --max-gaussians 2000 --max-gop 30"
rm -rf "$dir"
mkdir -p "$dir"
"$m4d" scene -o "$dir/scene" --cameras 4 --width 64 --height 48 --frames 300 --points 1000 \
  > /dev/null
"$m4d" encode "$dir/scene" -o "$dir/short.m4d" --frames 30 $opts > "$dir/short.txt"
"$m4d" encode "$dir/scene" -o "$dir/long.m4d" $opts > "$dir/long.txt"
peak() { grep '"peak_memory_bytes"' "$1" | tr -dc 0-9; }
frames() { grep -c '"hash"' "$1"; }
short=$(peak "$dir/short.m4d.json")
long=$(peak "$dir/long.m4d.json")
echo "peak memory: 30 frames $short bytes, 300 frames $long bytes"
test "$(frames "$dir/short.m4d.json")" -eq 30
test "$(frames "$dir/long.m4d.json")" -eq 300
test "$short" -gt 0
test "$long" -le $((short + short / 10 + 4000000))
