#!/usr/bin/env bash
# Checks the library boundaries of docs/architecture.md on the includes, and the header guards:
# every include is rooted at the repository (it names the tree that holds it); the SDK includes
# nothing of the encoder; the rasterizer nothing of the encoder but itself; the pipeline
# (m4d_encoder) nothing of the libraries above it; the capture input neither the synthetic
# content nor the runs; none of them the tools or the tests; each header's guard follows its
# path.
set -euo pipefail
cd "$(dirname "$0")/.."

failed=0
# forbid MESSAGE PATTERN DIR...: fails with MESSAGE when a quoted include under the DIRs
# matches the extended regular expression PATTERN (applied to what follows the quote).
forbid() {
  local message=$1 pattern=$2 hits
  shift 2
  hits=$(grep -rnE --include='*.c' --include='*.cc' --include='*.h' "^#include \"$pattern" "$@" ||
         true)
  if [ -n "$hits" ]; then
    printf 'layout: %s:\n%s\n' "$message" "$hits" >&2
    failed=1
  fi
}
# Every quoted include names its tree, or is a public header of the SDK.
unrooted=$(grep -rnE --include='*.c' --include='*.cc' --include='*.h' '^#include "' \
             sdk encoder tools tests bench examples |
           grep -vE ':#include "((sdk/src|encoder/src|tools|tests)/|m4d/m4d(_render)?\.h")' || true)
if [ -n "$unrooted" ]; then
  printf 'layout: an include not rooted at the repository:\n%s\n' "$unrooted" >&2
  failed=1
fi
forbid "the SDK includes the encoder, the tools or the tests" '(encoder|tools|tests)/' sdk
forbid "the rasterizer includes the encoder beyond itself" 'encoder/src/([^r]|r[^a])' \
  encoder/src/raster
above='(run|synthetic|distributed|dataset|video|ply|image_io)'
mapfile -t pipeline < <(ls -d encoder/src/* | grep -vE "/$above\$")
forbid "the pipeline includes a library above it, the tools or the tests" \
  "(encoder/src/$above/|tools/|tests/)" "${pipeline[@]}"
forbid "the capture input includes the synthetic content, the tools or the tests" \
  '(encoder/src/(run|synthetic)/|tools/|tests/)' encoder/src/{dataset,video,ply,image_io}
# A header's guard is its rooted path without "src": sdk/src/render/camera.h guards with
# M4D_SDK_RENDER_CAMERA_H_.
while read -r header; do
  guard=M4D_$(echo "${header%.h}" | sed 's|/src/|/|' | tr 'a-z/.-' 'A-Z___')_H_
  if ! grep -q "^#ifndef $guard\$" "$header"; then
    echo "layout: $header: its guard is not $guard" >&2
    failed=1
  fi
done < <(git ls-files 'sdk/src/*.h' 'encoder/src/*.h' 'tools/*.h' 'tests/*.h' 'bench/*.h')
if [ "$failed" = 0 ]; then
  echo "layout: the library boundaries hold"
fi
exit "$failed"
