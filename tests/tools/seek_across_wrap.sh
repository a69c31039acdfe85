#!/bin/sh
# m4d_decode --start-frame outputs the frame sought and every frame after it in stream order,
# also where frame numbers wrap at 2^32: each frame of a stream numbered 2^32 - 2, 2^32 - 1,
# 0, 1, 2, 3 is sought in turn and the output compared with the reference hashes from it on.
#   seek_across_wrap.sh M4D_DECODE STREAM (without .m4d; STREAM.md5 holds the hashes)
set -eu
decode=$1
stream=$2
line=1
for frame in $(cut -d' ' -f1 "$stream.md5"); do
  expected=$(tail -n +"$line" "$stream.md5")
  actual=$("$decode" "$stream.m4d" --start-frame "$frame" -q)
  if [ "$actual" != "$expected" ]; then
    printf 'seek to frame %s printed\n%s\nnot\n%s\n' "$frame" "$actual" "$expected"
    exit 1
  fi
  line=$((line + 1))
done
