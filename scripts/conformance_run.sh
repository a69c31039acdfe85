#!/usr/bin/env bash
# Checks a decoder against the conformance suite through the command-line contract of
# conformance/README.md: `DECODER... STREAM` prints "<frame_index> <md5>" per decoded frame
# (bitstream-spec 7) on stdout, exits 0 for a valid stream and non-zero (without crashing)
# when it reports an error, and prints the first error it reports as the stderr line
# "first_error NAME" (a code name of bitstream-spec 9, or TRUNCATED).
#
#   scripts/conformance_run.sh [--layers-flag FLAG] DECODER [ARGS...]
#
# Valid streams (conformance/streams/) must give exactly <name>.md5 and exit 0; with
# --layers-flag, also `DECODER FLAG static|dynamic STREAM` against <name>.static|dynamic.md5.
# Invalid streams (conformance/invalid/) must exit non-zero, not by a signal or the timeout,
# name the first error invalid/EXPECTED gives, and output exactly <name>.md5 (the frames
# before the damage and the GOPs after it); those EXPECTED marks NONE must decode as valid
# ones do, without error. With --layers-flag each is also decoded with one layer alone
# against <name>.static|dynamic.md5 and the first error invalid/EXPECTED_LAYERS gives (a
# payload of the layer not output is skipped unchecked, spec 6.6).
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
layers_flag=""
if [ "${1:-}" = "--layers-flag" ]; then
  layers_flag=$2
  shift 2
fi
if [ $# -lt 1 ]; then
  sed -n '2,17p' "$0" >&2
  exit 2
fi
decoder=("$@")
timeout_s=${M4D_CONFORMANCE_TIMEOUT:-120}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0
fail=0

for dir in streams invalid; do
  if ! (cd "$root/conformance/$dir" && md5sum --quiet -c MANIFEST.md5sum); then
    echo "conformance/$dir: files differ from MANIFEST.md5sum" >&2
    exit 2
  fi
done

# check NAME EXPECTED_MD5_FILE FIRST_ERROR ARGS...: runs the decoder, compares, prints a row.
# FIRST_ERROR is the code name the decoder must report first, or NONE for no error.
check() {
  local name=$1 expected=$2 want_error=$3
  shift 3
  local status=0
  timeout "$timeout_s" "${decoder[@]}" "$@" >"$work/out" 2>"$work/err" || status=$?
  local first
  first=$(sed -n 's/^first_error //p' "$work/err" | head -1)
  local verdict=PASS why=""
  if [ "$status" -ge 124 ]; then
    verdict=FAIL why="crashed or timed out (exit $status)"
  elif [ "$want_error" = NONE ] && [ "$status" -ne 0 ]; then
    verdict=FAIL why="exit $status on a stream without error"
  elif [ "$want_error" != NONE ] && [ "$status" -eq 0 ]; then
    verdict=FAIL why="no error reported"
  elif [ "$want_error" != NONE ] && [ "$first" != "$want_error" ]; then
    verdict=FAIL why="first error ${first:-not named}, expected $want_error"
  elif ! diff -q "$work/out" "$expected" >/dev/null; then
    verdict=FAIL why="frame hashes differ"
  fi
  printf "%-44s %6s %s %s\n" "$name" "$(wc -l <"$work/out")" "$verdict" "$why"
  if [ "$verdict" = PASS ]; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
}

printf "%-44s %6s %s\n" "stream" "frames" "result"
for stream in "$root"/conformance/streams/*.m4d; do
  name=$(basename "$stream" .m4d)
  check "$name" "${stream%.m4d}.md5" NONE "$stream"
  if [ -n "$layers_flag" ]; then
    for layer in static dynamic; do
      expected="${stream%.m4d}.$layer.md5"
      [ -f "$expected" ] && check "$name ($layer)" "$expected" NONE "$layers_flag" "$layer" "$stream"
    done
  fi
done
for stream in "$root"/conformance/invalid/*.m4d; do
  name=$(basename "$stream" .m4d)
  want=$(awk -v n="$name" '$1 == n { print $2 }' "$root/conformance/invalid/EXPECTED")
  if [ -z "$want" ]; then
    echo "conformance/invalid/EXPECTED has no line for $name" >&2
    exit 2
  fi
  check "invalid/$name" "${stream%.m4d}.md5" "$want" "$stream"
  if [ -n "$layers_flag" ]; then
    for column in 2:static 3:dynamic; do
      layer=${column#*:}
      want=$(awk -v n="$name" -v c="${column%%:*}" '$1 == n { print $c }' \
        "$root/conformance/invalid/EXPECTED_LAYERS")
      if [ -z "$want" ] || [ ! -f "${stream%.m4d}.$layer.md5" ]; then
        echo "conformance/invalid: no $layer expectation for $name" >&2
        exit 2
      fi
      check "invalid/$name ($layer)" "${stream%.m4d}.$layer.md5" "$want" "$layers_flag" "$layer" "$stream"
    done
  fi
done
echo "conformance: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
