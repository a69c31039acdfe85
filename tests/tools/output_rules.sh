#!/bin/sh
# The stream tools keep an existing output unless given --force (exit 2, before any work) and
# replace it whole with it; m4d_export creates its folder only when it writes a frame there.
#   output_rules.sh BIN_DIR STREAM DIR   (BIN_DIR holds m4d_synth, m4d_filter, m4d_decode, m4d_export)
set -u
bin=$1
stream=$2
dir=$3
fail() {
  echo "output_rules: $*" >&2
  exit 1
}
expect() {  # expect STATUS COMMAND...: runs it and checks its exit status
  want=$1
  shift
  "$@" > "$dir/out.txt" 2> "$dir/err.txt"
  got=$?
  [ "$got" -eq "$want" ] || fail "'$*' exited $got, not $want: $(head -c 300 "$dir/err.txt")"
}
kept() { [ "$(cat "$1")" = kept ] || fail "$1 was replaced without --force"; }
rm -rf "$dir"
mkdir -p "$dir"

expect 0 "$bin/m4d_synth" -o "$dir/synth.m4d" --gops 1 --frames-per-gop 2 --static 50 --dynamic 20
echo kept > "$dir/synth.m4d"
expect 2 "$bin/m4d_synth" -o "$dir/synth.m4d" --gops 1 --frames-per-gop 2 --static 50 --dynamic 20
grep -q 'give --force' "$dir/err.txt" || fail "m4d_synth: no word of --force"
kept "$dir/synth.m4d"
expect 0 "$bin/m4d_synth" -o "$dir/synth.m4d" --gops 1 --frames-per-gop 2 --static 50 --dynamic 20 --force
[ -s "$dir/synth.m4d" ] && ! grep -q kept "$dir/synth.m4d" || fail "m4d_synth --force did not replace"
ls "$dir" | grep -q tmp && fail "a temporary file was left: $(ls "$dir")"

echo kept > "$dir/fg.m4d"
expect 2 "$bin/m4d_filter" "$stream" "$dir/fg.m4d"
kept "$dir/fg.m4d"
expect 0 "$bin/m4d_filter" "$stream" "$dir/fg.m4d" --force

echo kept > "$dir/hashes.md5"
expect 2 "$bin/m4d_decode" "$stream" -o "$dir/hashes.md5"
kept "$dir/hashes.md5"
expect 0 "$bin/m4d_decode" -q "$stream" -o "$dir/hashes.md5" --force
grep -q '^0 [0-9a-f]\{32\}$' "$dir/hashes.md5" || fail "m4d_decode -o wrote no hash lines"
ls -a "$dir" | grep -q partial && fail "m4d_decode left its partial file: $(ls -a "$dir")"

# A frame the stream does not hold: nothing written, no folder created.
expect 1 "$bin/m4d_export" "$stream" -o "$dir/export" --frames 40
[ ! -e "$dir/export" ] || fail "m4d_export created its folder and wrote nothing"
expect 0 "$bin/m4d_export" "$stream" -o "$dir/export" --frames 2
echo kept > "$dir/export/frame_00003.ply"
expect 2 "$bin/m4d_export" "$stream" -o "$dir/export" --frames 2:4
kept "$dir/export/frame_00003.ply"
[ ! -e "$dir/export/frame_00004.ply" ] || fail "m4d_export wrote before refusing"
expect 0 "$bin/m4d_export" "$stream" -o "$dir/export" --frames 2:4 --force
[ -s "$dir/export/frame_00004.ply" ] && ! grep -q kept "$dir/export/frame_00003.ply" ||
  fail "m4d_export --force did not replace"
exit 0
