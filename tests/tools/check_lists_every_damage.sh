#!/bin/sh
# m4d_check lists every damaged packet, not only the first of a GOP: one byte flipped in the
# payload of KEYFRAME_DYNAMIC (frame 0) and of MOTION_GRID (frame 2) of the first GOP, and the
# header of frame 5's MOTION_GRID damaged (it resynchronises and goes on).
#   check_lists_every_damage.sh M4D_CHECK STREAM DIR
set -eu
check=$1
stream=$2
dir=$3
mkdir -p "$dir"
damaged=$dir/damaged.m4d
cp "$stream" "$damaged"
flip() {
  byte=$(od -An -tu1 -j "$1" -N1 "$damaged" | tr -d ' ')
  printf "\\$(printf '%03o' $((byte ^ 255)))" |
    dd of="$damaged" bs=1 seek="$1" conv=notrunc 2>/dev/null
}
# Packet offsets of synth_sh3_three_gops.m4d (m4d_probe --json).
flip $((67493 + 24 + 1000))   # KEYFRAME_DYNAMIC of frame 0, payload
flip $((93689 + 24 + 10))     # MOTION_GRID of frame 2, payload (42 bytes: an empty grid)
flip $((189030 + 8))          # MOTION_GRID of frame 5, header (frame_index)
if "$check" "$damaged" > "$dir/check.txt"; then
  echo "a damaged stream passed"
  exit 1
fi
cat "$dir/check.txt"
grep -q '^byte 67493: KEYFRAME_DYNAMIC (frame 0): payload CRC mismatch' "$dir/check.txt"
grep -q '^byte 93689: MOTION_GRID (frame 2): payload CRC mismatch' "$dir/check.txt"
grep -q '^byte 189030: packet header: checksum mismatch' "$dir/check.txt"
test "$(grep -c '^byte ' "$dir/check.txt")" -eq 3
