#!/usr/bin/env bash
# The main job: installs dependencies, builds, generates the built-in synthetic scene, encodes
# it with the reference encoder (keyframe training, lookahead decoupling, motion estimation,
# compensation, adaptive GOP; closed loop on the SDK), checks that the SDK decodes the written
# stream to the encoder's reconstruction, renders the held-out camera's first frame beside its
# ground truth, and prints the per-frame table. Extra arguments go to `m4d encode`.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
scripts/build.sh m4d_cli m4d_decode m4d_play  # the tests and benchmarks are scripts/test.sh's
mkdir -p out
m4d=build/release/tools/m4d/m4d
# The demo codes the scene's first 8 frames with a 1000-iteration first keyframe, so that
# everything, build included, takes well under a quarter of an hour on two cores;
# `m4d encode default` alone codes all 20 frames with the full short schedule (7000 iterations).
"$m4d" encode default -o out/default.m4d --force --frames 8 --keyframe-iterations 1000 \
  --views out/default-views "$@"
build/release/tools/m4d_decode --force out/default.m4d -o out/default.md5
# The player's view: the SDK decodes and renders the held-out camera with OpenGL ES (headless).
mkdir -p out/default-play
build/release/tools/m4d_play out/default.m4d --capture out/default-scene -o out/default-play --force \
  --mp4 out/default-play.mp4 | tail -3
echo "per-frame hashes of the SDK's decode: out/default.md5; report: out/default.m4d.json"
echo "held-out view (truth | decoded render | difference x4): out/default-views/ (PNG, views.mp4)"
echo "the SDK's GL render of the held-out camera: out/default-play/ (PNG), out/default-play.mp4"
