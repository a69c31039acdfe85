#!/bin/sh
# m4d_play on damage: a stream cut inside a packet is reported as truncated (not as an API
# "try again"), a damaged header is skipped to the next GOP, and both exit 1 after playing
# what survives.
#   play_damage.sh M4D_PLAY STREAM WORK_DIR
set -eu
play=$1
stream=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
size=$(wc -c <"$stream")
head -c $((size - 100)) "$stream" >"$work/cut.m4d"
status=0
"$play" "$work/cut.m4d" --orbit --frames 2 --width 32 --height 24 -o "$work/cut" \
  2>"$work/cut.err" >/dev/null || status=$?
grep -q 'truncated: the stream ends inside a packet' "$work/cut.err"
! grep -q 'try again' "$work/cut.err"
[ "$status" -eq 1 ]
[ -s "$work/cut/frame_00000.png" ]
# A flipped sync byte in the first packet: the first GOP is lost, a later one plays.
cp "$stream" "$work/sync.m4d"
printf 'X' | dd of="$work/sync.m4d" bs=1 seek=0 conv=notrunc 2>/dev/null
status=0
"$play" "$work/sync.m4d" --orbit --frames 1 --width 32 --height 24 -o "$work/sync" \
  2>"$work/sync.err" >/dev/null || status=$?
grep -q 'damaged packet header at byte 0' "$work/sync.err"
[ "$status" -eq 1 ]
ls "$work"/sync/frame_*.png >/dev/null
