#!/bin/sh
# Renditions for adaptive bitrate on a tiny generated scene:
#   renditions.sh M4D M4D_CHECK DIR
# `m4d encode --renditions r4,r1` writes two streams from one first keyframe, r4 deciding the
# GOPs (here of 2 frames, random-access and dependent ones), and a manifest. Each stream
# decodes to the encoder's hashes and passes the stream checker; the manifest lists r1 before
# r4 (bandwidth ascending), r1 smaller, with the streams' real sizes and names, and the same
# GOPs (first frame, frames, random_access) in both. Existing outputs are kept without --force.
set -eu
m4d=$1
check=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir"
"$m4d" scene -o "$dir/scene" --cameras 5 --width 48 --height 36 --frames 6 --points 1500 \
  > /dev/null 2>&1
opts="--keyframe-iterations 60 --retrain-iterations 20 --motion-iterations 5 \
--compensation-iterations 5 --lookahead 1 --max-gaussians 3000 --max-gop 2 --random-access 0.1"
"$m4d" encode "$dir/scene" -o "$dir/abr.m4d" $opts --renditions r4,r1 > "$dir/out.txt" 2> "$dir/progress.txt"
grep -q '2 renditions, every frame decoded by the SDK' "$dir/out.txt"
test ! -e "$dir/abr.m4d"
for r in r1 r4; do
  "$check" "$dir/abr.$r.m4d" | grep -q '^conforms'
  grep -q '"keyframe_shared_with"' "$dir/abr.$r.m4d.json"
done
manifest=$dir/abr.manifest.json
grep -q '"format": "m4d-manifest"' "$manifest"
grep -q '"version": 1' "$manifest"
grep -q '"frames": 6,' "$manifest"
grep -q '"fps": 30.0' "$manifest"
# One line per rendition: id url bandwidth bytes, then its GOPs as frame/frames/random_access.
awk '
  /^      "bandwidth":/ { if (n++) print line; gsub(/[",]/, ""); bw = $2; gops = "" }
  /^      "bytes":/ { gsub(/[",]/, ""); bytes = $2 }
  /^          "frame":/ { gsub(/[",]/, ""); gops = gops " " $2 }
  /^          "frames":/ { gsub(/[",]/, ""); gops = gops "/" $2 }
  /^          "random_access":/ { gsub(/[",]/, ""); gops = gops "/" $2 }
  /^      "id":/ { gsub(/[",]/, ""); id = $2 }
  /^      "url":/ { gsub(/[",]/, ""); line = id " " $2 " " bw " " bytes gops }
  END { print line }' "$manifest" > "$dir/renditions.txt"
test "$(wc -l < "$dir/renditions.txt")" -eq 2
set -- $(sed -n 1p "$dir/renditions.txt")
test "$1 $2" = "r1 abr.r1.m4d"
low_bw=$3 low_bytes=$4
test "$low_bytes" -eq "$(stat -c %s "$dir/abr.r1.m4d")"
shift 4
low_gops="$*"
set -- $(sed -n 2p "$dir/renditions.txt")
test "$1 $2" = "r4 abr.r4.m4d"
test "$4" -eq "$(stat -c %s "$dir/abr.r4.m4d")"
test "$low_bw" -lt "$3"
test "$low_bytes" -lt "$4"
shift 4
test "$low_gops" = "$*"
test "$low_gops" = "0/2/true 2/2/false 4/2/true"

# Outputs kept without --force (a usage error, before any work), replaced with it.
if "$m4d" encode "$dir/scene" -o "$dir/abr.m4d" $opts --renditions r1,r4 2> "$dir/err.txt"; then
  exit 1
else
  test $? -eq 2
fi
grep -q 'exists: give --force' "$dir/err.txt"
"$m4d" encode "$dir/scene" -o "$dir/abr.m4d" $opts --renditions r1,r4 --force > /dev/null 2>&1
! "$m4d" encode "$dir/scene" -o "$dir/x.m4d" --renditions r1,r1 2> /dev/null
! "$m4d" encode "$dir/scene" -o "$dir/x.m4d" --renditions r1,r9 2> /dev/null
test ! -e "$dir/x.manifest.json"
