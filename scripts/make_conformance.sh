#!/usr/bin/env bash
# Regenerates conformance/streams/ (from the reference encoder on a small built-in scene, and
# from the synthetic stream writer for the sizes no capture reaches) and records the expected
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

# record NAME: the expected hashes of conformance/streams/NAME.m4d, every layer choice.
record() {
  "$bin/m4d_decode" -q --force "$out/$1.m4d" -o "$out/$1.md5"
  "$bin/m4d_decode" -q --force --layers static "$out/$1.m4d" -o "$out/$1.static.md5"
  "$bin/m4d_decode" -q --force --layers dynamic "$out/$1.m4d" -o "$out/$1.dynamic.md5"
}

# The reference encoder on the built-in scene at 64x48 (6 cameras, 6 frames; an object enters
# at frame 3), with schedules short enough for seconds per stream. The content is not the
# point: together the streams reach every syntax element and coding choice of the encoder.
scene=build/conformance-scene
rm -rf "$scene"
"$bin/m4d/m4d" scene -o "$scene" --cameras 6 --width 64 --height 48 --frames 6 --points 2000
short="--keyframe-iterations 600 --retrain-iterations 60 --motion-iterations 20
  --compensation-iterations 20 --lookahead 2 --max-gaussians 1500 --threads 1
  --appearance-min-views 1"  # its 5 training views would train no colour change
dynamic="--tau-delta 0.05"  # more of this small scene dynamic than the default threshold
# Compensation coded on every frame (it gains too little here to pass the default's test).
always="--compensation-min-gain -1"
bits24=24,24,24,24,24,24
bits1=1,1,1,1,1,1
# name | m4d encode arguments
encoded=(
  "enc_adaptive_gop|$dynamic $always --gop-psnr-drop 1"
  "enc_sh0_fixed_gop|$dynamic --sh-degree 0 --fixed-gop 3"
  "enc_sh2_one_gop|$dynamic --sh-degree 2 --fixed-gop 6"
  "enc_sh3|$dynamic --sh-degree 3 --fixed-gop 3 --random-access 0"
  "enc_no_compensation|$dynamic --no-compensation --fixed-gop 3"
  "enc_all_static|--tau-delta 1e9 --tau-s 1e9 --tau-e 1e9 --fixed-gop 3"
  "enc_all_dynamic|--no-decoupling --fixed-gop 3 $always"
  "enc_no_motion|$dynamic --no-motion --fixed-gop 3 $always"
  "enc_no_rate_term|$dynamic --no-rate --fixed-gop 3"
  "enc_rate_point_r1|$dynamic --rate-point r1 --fixed-gop 3"
  "enc_rate_point_r5|$dynamic --rate-point r5 --fixed-gop 3"
  "enc_bits_24|$dynamic --keyframe-bits $bits24 --compensation-bits $bits24 --fixed-gop 3"
  "enc_bits_1|$dynamic --keyframe-bits $bits1 --compensation-bits $bits1 --fixed-gop 3"
)
for entry in "${encoded[@]}"; do
  name=${entry%%|*}
  args=${entry#*|}
  echo "== $name"
  # shellcheck disable=SC2086
  "$bin/m4d/m4d" encode "$scene" -o "$out/$name.m4d" --force --views "" $short $args | tail -9
  rm -f "$out/$name.m4d.json"
  record "$name"
done
# Foreground-only (spec 2): the adaptive-GOP stream without its KEYFRAME_STATIC packets.
"$bin/m4d_filter" --force "$out/enc_adaptive_gop.m4d" "$out/enc_foreground_only.m4d"
record enc_foreground_only

# The synthetic stream writer: random Gaussian sets and sparse motion.
# name | m4d_synth arguments
streams=(
  "synth_sh3_three_gops|--gops 3 --frames-per-gop 4 --static 2000 --dynamic 600 --sh-degree 3 --motion-fraction 0.002 --seed 11"
  "synth_sh0_short_gops|--gops 4 --frames-per-gop 2 --static 1500 --dynamic 400 --sh-degree 0 --motion-fraction 0.003 --seed 12"
  "synth_sh1_foreground_only|--gops 2 --frames-per-gop 3 --static 0 --dynamic 800 --sh-degree 1 --motion-fraction 0.002 --seed 13"
  "synth_sh2_single_gop|--gops 1 --frames-per-gop 8 --static 1000 --dynamic 500 --sh-degree 2 --motion-fraction 0.001 --seed 14"
  "synth_max_grid_values|--gops 1 --frames-per-gop 3 --static 300 --dynamic 200 --sh-degree 3 --grid 256,1 --mlp-layers 4 --mlp-width 32 --bits 24 --motion-fraction 0.0005 --seed 21"
  "synth_single_gaussian_sets|--gops 2 --frames-per-gop 3 --static 1 --dynamic 100 --sh-degree 1 --motion-fraction 0.01 --seed 23"
  "synth_sh1_dependent_gops|--gops 3 --frames-per-gop 3 --static 1500 --dynamic 400 --sh-degree 1 --motion-fraction 0.002 --seed 31 --dependent-gops --static-change 0.02"
  "synth_sh0_dependent_no_update|--gops 2 --frames-per-gop 2 --static 800 --dynamic 300 --sh-degree 0 --motion-fraction 0.003 --seed 32 --dependent-gops"
  "synth_sh1_appearance|--gops 2 --frames-per-gop 4 --static 600 --dynamic 1500 --sh-degree 1 --motion-fraction 0.002 --seed 34 --appearance-fraction 0.3"
  "synth_v03_appearance|--gops 2 --frames-per-gop 3 --static 600 --dynamic 1500 --sh-degree 1 --motion-fraction 0.002 --seed 35 --appearance-fraction 0.3 --dependent-gops --bitstream-minor 3"
  "synth_sh2_codebooks|--gops 2 --frames-per-gop 3 --static 2000 --dynamic 600 --sh-degree 2 --motion-fraction 0.002 --seed 37 --codebook 16"
  "synth_sh1_codebook_300|--gops 1 --frames-per-gop 2 --static 9700 --dynamic 200 --sh-degree 1 --motion-fraction 0.002 --seed 38 --codebook 300 --attribute-coding draco"
  "synth_v06_sh1|--gops 2 --frames-per-gop 3 --static 600 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 40 --dependent-gops --bitstream-minor 6"
  "synth_v05_sh1|--gops 2 --frames-per-gop 3 --static 600 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 39 --dependent-gops --bitstream-minor 5"
  "synth_v04_sh1|--gops 2 --frames-per-gop 3 --static 600 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 36 --dependent-gops --bitstream-minor 4"
  "synth_v02_sh2|--gops 2 --frames-per-gop 3 --static 600 --dynamic 200 --sh-degree 2 --motion-fraction 0.002 --seed 33 --bitstream-minor 2"
  "synth_max_levels_width|--gops 2 --frames-per-gop 2 --static 300 --dynamic 200 --sh-degree 2 --grid 8,8,16,8,32,8,64,8 --mlp-width 256 --bits 1 --motion-fraction 0.002 --seed 22"
  "synth_edge_cases|--gops 2 --frames-per-gop 3 --static 200 --dynamic 240 --sh-degree 1 --seed 41 --edge-cases"
  "synth_v07_sh1|--gops 2 --frames-per-gop 3 --static 600 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 42 --codebook 16 --bitstream-minor 7"
  "synth_v08_sh1|--gops 2 --frames-per-gop 3 --static 600 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 47 --codebook 16 --attribute-coding adaptive --bitstream-minor 8"
  "synth_v10_own_dc|--gops 2 --frames-per-gop 3 --static 600 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 49 --attribute-coding adaptive --bitstream-minor 10"
  "synth_v09_bricks|--gops 2 --frames-per-gop 3 --static 300 --dynamic 200 --sh-degree 1 --grid 8,4,16,2 --motion-fraction 0.3 --seed 48 --codebook 16 --attribute-coding adaptive --bitstream-minor 9"
  "synth_sh1_adaptive|--gops 2 --frames-per-gop 3 --static 3000 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 43 --codebook 48 --attribute-coding adaptive"
  "synth_sh3_adaptive_bits_12|--gops 1 --frames-per-gop 3 --static 800 --dynamic 200 --sh-degree 3 --motion-fraction 0.002 --seed 44 --bits 12 --attribute-coding adaptive"
  "synth_sh0_adaptive_bits_2|--gops 1 --frames-per-gop 3 --static 500 --dynamic 200 --sh-degree 0 --motion-fraction 0.002 --seed 45 --bits 2 --attribute-coding adaptive"
  "synth_sh1_draco_attributes|--gops 1 --frames-per-gop 3 --static 3000 --dynamic 300 --sh-degree 1 --motion-fraction 0.002 --seed 46 --attribute-coding draco"
)
for entry in "${streams[@]}"; do
  name=${entry%%|*}
  args=${entry#*|}
  echo "== $name"
  # shellcheck disable=SC2086
  "$bin/m4d_synth" --force -o "$out/$name.m4d" $args | tail -5
  record "$name"
done
# Valid streams at the edges of the rules, edited from a small written stream: frame numbers
# that wrap, a non-minimal varuint, a rANS state that starts below L.
"$bin/m4d_make_invalid" --valid-dir "$out"
for stream in "$out"/edit_*.m4d; do record "$(basename "$stream" .m4d)"; done
(cd "$out" && md5sum ./*.m4d >MANIFEST.md5sum)
echo "wrote $(ls "$out"/*.m4d | wc -l) streams to $out"

# Invalid streams: each breaks one rule (conformance/invalid/EXPECTED names the error a decoder
# must report first); <name>.md5 holds the frames the reference decoder still outputs.
invalid=conformance/invalid
mkdir -p "$invalid"
rm -f "$invalid"/*.m4d "$invalid"/*.md5
"$bin/m4d_make_invalid" -o "$invalid"
# Each stream also decoded with one layer alone (spec 6.6, 6.8): a payload of the layer not
# output is skipped unchecked, so the first error and the frames may differ; EXPECTED_LAYERS
# records the reference decoder's first error per layer, <name>.static|dynamic.md5 the frames.
{
  echo "# <stream> <first error with --layers static> <first error with --layers dynamic>"
  for stream in "$invalid"/*.m4d; do
    "$bin/m4d_decode" -q --force "$stream" -o "${stream%.m4d}.md5" 2>/dev/null || true
    row=$(basename "$stream" .m4d)
    for layer in static dynamic; do
      first=$("$bin/m4d_decode" -q --force --layers "$layer" "$stream" -o "${stream%.m4d}.$layer.md5" \
        2>&1 >/dev/null | sed -n 's/^first_error //p' | head -1 || true)
      row="$row ${first:-NONE}"
    done
    echo "$row"
  done
} >"$invalid/EXPECTED_LAYERS"
(cd "$invalid" && md5sum ./*.m4d >MANIFEST.md5sum)
