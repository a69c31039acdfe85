#!/bin/sh
# m4d_probe --gop-index: prints the GOP index, or writes it with -o, refusing to replace a file
# without --force; its GOPs start at the packets m4d_probe --json lists first in each keyframe;
# a damaged stream is an error that writes nothing; -o without --gop-index is a usage error.
#   gop_index_output.sh M4D_PROBE STREAM DAMAGED_STREAM WORK_DIR
set -eu
probe=$1
stream=$2
damaged=$3
work=$4
rm -rf "$work"
mkdir -p "$work"
out=$work/s.m4d.gops.json
"$probe" --gop-index "$stream" > "$work/stdout.json"
grep -q '"format": "m4d-gop-index"' "$work/stdout.json"
"$probe" --gop-index "$stream" -o "$out" > /dev/null
cmp "$out" "$work/stdout.json"
# The offsets of the GOPs are those of the first packet of each keyframe in m4d_probe --json.
"$probe" --json "$stream" > "$work/probe.json"
grep -o '"offset": [0-9]*' "$out" | grep -o '[0-9]*$' > "$work/gop_offsets.txt"
tr -d ' \n' < "$work/probe.json" | grep -o '"keyframe":true,"packets":\[{"bytes":[0-9]*,"damaged":false,"offset":[0-9]*' |
  grep -o '[0-9]*$' > "$work/keyframe_offsets.txt"
test -s "$work/gop_offsets.txt"
cmp "$work/gop_offsets.txt" "$work/keyframe_offsets.txt"
# Existing output: refused (exit 2) and kept without --force, replaced with it.
echo kept > "$out"
status=0
"$probe" --gop-index "$stream" -o "$out" 2> "$work/refused.txt" || status=$?
test "$status" -eq 2
grep -q 'give --force' "$work/refused.txt"
grep -q kept "$out"
"$probe" --gop-index "$stream" -o "$out" --force > /dev/null
cmp "$out" "$work/stdout.json"
# A damaged stream: exit 1, a message with the byte, no file.
status=0
"$probe" --gop-index "$damaged" -o "$work/damaged.json" 2> "$work/damaged.txt" || status=$?
test "$status" -eq 1
grep -q 'byte [0-9]*: ' "$work/damaged.txt"
test ! -e "$work/damaged.json"
# -o belongs to --gop-index.
status=0
"$probe" "$stream" -o "$work/x.json" > /dev/null 2>&1 || status=$?
test "$status" -eq 2
