#!/bin/sh
# m4d_probe reports truncation where m4d_decode does and names it as m4d_decode does
# (TRUNCATED, not an error code): on every invalid stream of the conformance suite, the
# lines "truncated: the stream ends inside a packet|frame" of both tools agree, so a complete
# stream whose last frames are skipped after damage is not said to end inside a frame.
#   probe_truncation.sh M4D_PROBE M4D_DECODE CONFORMANCE_DIR
set -eu
probe=$1
decode=$2
dir=$3
truncations() { grep -o 'truncated: the stream ends inside a [a-z]*' || true; }
for s in "$dir"/invalid/*.m4d; do
  p=$("$probe" "$s" 2>&1 | truncations)
  d=$("$decode" -q "$s" 2>&1 >/dev/null | truncations)
  if [ "$p" != "$d" ]; then
    printf '%s: m4d_probe says\n%s\nm4d_decode says\n%s\n' "$s" "$p" "$d"
    exit 1
  fi
done
json=$("$probe" --json "$dir/invalid/truncated_in_payload.m4d" || true)
echo "$json" | grep -q '"name": "TRUNCATED"'
