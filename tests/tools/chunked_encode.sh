#!/bin/sh
# Chunked encoding end to end on a tiny generated scene (chunked_encode.h):
#   chunked_encode.sh M4D M4D_CHECK DIR [MPIEXEC]
# One process codes 4 frames in 2 chunks, each from a random-access keyframe, into a stream the
# SDK decodes to the encoder's hashes and the stream checker passes. A run stopped after one chunk writes no stream and keeps
# the chunk; the same command then codes only the other one, and the stream is byte for byte
# the uninterrupted run's. A chunk whose process died between its stream and its report, or
# whose report is damaged, is coded again. A checkpoint directory of other settings is refused.
# With a given first keyframe the second chunk still trains its own, and in one process a later
# GOP retrains its own, so the automatic keyframe choices are made (recorded in the report), not
# left unresolved. With MPIEXEC, two ranks
# code one chunk each into the same stream (so the same decode, frame by frame), and a killed
# rank's chunk is coded again on resume.
set -eu
m4d=$1
check=$2
dir=$3
mpiexec=${4:-}
opts="--keyframe-iterations 60 --retrain-iterations 20 --motion-iterations 5 \
--compensation-iterations 5 --lookahead 1 --max-gaussians 3000 --chunk-frames 2"
rm -rf "$dir"
mkdir -p "$dir"
"$m4d" scene -o "$dir/scene" --cameras 5 --width 48 --height 36 --frames 4 --points 1500 \
  > /dev/null
hashes() { grep '"hash"' "$1"; }

"$m4d" encode "$dir/scene" -o "$dir/one.m4d" $opts > "$dir/one.txt"
grep -q 'every hash equal' "$dir/one.txt"
"$check" "$dir/one.m4d" | grep -q '^conforms'
test "$(grep -c '"random_access": true' "$dir/one.m4d.json")" -eq 2
test "$(grep -c '"chunk":' "$dir/one.m4d.json")" -eq 2

"$m4d" encode "$dir/scene" -o "$dir/resumed.m4d" $opts --max-chunks 1 > "$dir/stopped.txt"
grep -q '1 of 2 chunks done' "$dir/stopped.txt"
test ! -e "$dir/resumed.m4d"
test -s "$dir/resumed.m4d.chunks/chunk_00000.json"
test ! -e "$dir/resumed.m4d.chunks/chunk_00001.json"
"$m4d" encode "$dir/scene" -o "$dir/resumed.m4d" $opts > "$dir/resumed.txt"
grep -q '1 of 2 chunks already done' "$dir/resumed.txt"
test "$(grep -c 'coded in' "$dir/resumed.txt")" -eq 1
cmp "$dir/one.m4d" "$dir/resumed.m4d"

rm "$dir/resumed.m4d" "$dir/resumed.m4d.chunks/chunk_00001.json"
"$m4d" encode "$dir/scene" -o "$dir/resumed.m4d" $opts > "$dir/redone.txt"
grep -q 'chunk 1 (frames 2-3) coded' "$dir/redone.txt"
cmp "$dir/one.m4d" "$dir/resumed.m4d"
rm "$dir/resumed.m4d"
echo '{"first": "damaged"}' > "$dir/resumed.m4d.chunks/chunk_00001.json"
"$m4d" encode "$dir/scene" -o "$dir/resumed.m4d" $opts > "$dir/damaged.txt"
grep -q 'chunk 1 (frames 2-3) coded' "$dir/damaged.txt"
cmp "$dir/one.m4d" "$dir/resumed.m4d"

if "$m4d" encode "$dir/scene" -o "$dir/other.m4d" --checkpoint-dir "$dir/resumed.m4d.chunks" \
  $opts --seed 7 2> "$dir/other.txt"; then
  exit 1
fi
grep -q 'other settings' "$dir/other.txt"
test ! -e "$dir/other.m4d"

"$m4d" train "$dir/scene" --iterations 60 --max-gaussians 3000 --ply "$dir/kf.ply" \
  > /dev/null 2>&1
"$m4d" encode "$dir/scene" -o "$dir/given.m4d" $opts --keyframe-ply "$dir/kf.ply" > /dev/null
grep -q '"prune_share_selection": {' "$dir/given.m4d.json"
# In one process too: the GOP at frame 2 retrains its keyframe with the chosen prune share (no
# keyframe is trained from scratch, so no start share is chosen).
"$m4d" encode "$dir/scene" -o "$dir/given_one.m4d" $(echo "$opts" | sed 's/--chunk-frames 2//') \
  --fixed-gop 2 --keyframe-ply "$dir/kf.ply" > "$dir/given_one.txt"
grep -q 'later GOPs may retrain' "$dir/given_one.txt"
grep -q '"prune_share_selection": {' "$dir/given_one.m4d.json"
grep -q '"start_size_selection": null' "$dir/given_one.m4d.json"

[ -n "$mpiexec" ] || exit 0
# Open MPI refuses root unless told; CI containers run as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$mpiexec" --oversubscribe -np 2 "$m4d" encode "$dir/scene" -o "$dir/mpi.m4d" $opts \
  > "$dir/mpi.txt"
grep -q 'rank 0: chunk 0 (frames 0-1) coded' "$dir/mpi.txt"
grep -q 'rank 1: chunk 1 (frames 2-3) coded' "$dir/mpi.txt"
grep -q 'every hash equal' "$dir/mpi.txt"
hashes "$dir/one.m4d.json" > "$dir/one_hashes.txt"
hashes "$dir/mpi.m4d.json" > "$dir/mpi_hashes.txt"
test "$(wc -l < "$dir/mpi_hashes.txt")" -eq 4
cmp "$dir/one_hashes.txt" "$dir/mpi_hashes.txt"
cmp "$dir/one.m4d" "$dir/mpi.m4d"

rm "$dir/mpi.m4d" "$dir/mpi.m4d.chunks/chunk_00001.json"
"$mpiexec" --oversubscribe -np 2 "$m4d" encode "$dir/scene" -o "$dir/mpi.m4d" $opts \
  > "$dir/mpi_resumed.txt"
grep -q '1 of 2 chunks already done' "$dir/mpi_resumed.txt"
test "$(grep -c 'coded in' "$dir/mpi_resumed.txt")" -eq 1
cmp "$dir/one.m4d" "$dir/mpi.m4d"
