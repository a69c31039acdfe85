#!/usr/bin/env bash
# The main job: installs dependencies, builds, writes a synthetic stream with the reference
# writer (closed loop), decodes it with the SDK and reports sizes, times and hash agreement.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
scripts/build.sh
mkdir -p out
build/release/tools/m4d_synth -o out/synthetic.m4d "$@"
build/release/tools/m4d_decode out/synthetic.m4d -o out/synthetic.md5
echo "per-frame hashes: out/synthetic.md5"
