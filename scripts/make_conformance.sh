#!/usr/bin/env bash
# Regenerates conformance/streams/ from the synthetic stream writer and records the expected
# per-frame hashes of the decoded state for every layer choice, then conformance/invalid/.
# Run after a bitstream change (which also bumps the version in the spec); review the diff of
# the .md5 files.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
bin=build/release/tools
out=conformance/streams
mkdir -p "$out"
rm -f "$out"/*.m4d "$out"/*.md5

# name | m4d_synth arguments
streams=(
  "synth_sh3_three_gops|--gops 3 --frames-per-gop 4 --static 2000 --dynamic 600 --sh-degree 3 --motion-fraction 0.002 --seed 11"
  "synth_sh0_short_gops|--gops 4 --frames-per-gop 2 --static 1500 --dynamic 400 --sh-degree 0 --motion-fraction 0.003 --seed 12"
  "synth_sh1_foreground_only|--gops 2 --frames-per-gop 3 --static 0 --dynamic 800 --sh-degree 1 --motion-fraction 0.002 --seed 13"
  "synth_sh2_single_gop|--gops 1 --frames-per-gop 8 --static 1000 --dynamic 500 --sh-degree 2 --motion-fraction 0.001 --seed 14"
)
for entry in "${streams[@]}"; do
  name=${entry%%|*}
  args=${entry#*|}
  echo "== $name"
  # shellcheck disable=SC2086
  "$bin/m4d_synth" -o "$out/$name.m4d" $args | tail -5
  "$bin/m4d_decode" -q "$out/$name.m4d" -o "$out/$name.md5"
  "$bin/m4d_decode" -q --layers static "$out/$name.m4d" -o "$out/$name.static.md5"
  "$bin/m4d_decode" -q --layers dynamic "$out/$name.m4d" -o "$out/$name.dynamic.md5"
done
(cd "$out" && md5sum ./*.m4d >MANIFEST.md5sum)
echo "wrote $(ls "$out"/*.m4d | wc -l) streams to $out"

# Invalid streams: each breaks one rule (conformance/invalid/EXPECTED names the error a decoder
# must report first); <name>.md5 holds the frames the reference decoder still outputs.
invalid=conformance/invalid
mkdir -p "$invalid"
rm -f "$invalid"/*.m4d "$invalid"/*.md5
"$bin/m4d_make_invalid" -o "$invalid"
for stream in "$invalid"/*.m4d; do
  "$bin/m4d_decode" -q "$stream" -o "${stream%.m4d}.md5" 2>/dev/null || true
done
(cd "$invalid" && md5sum ./*.m4d >MANIFEST.md5sum)
