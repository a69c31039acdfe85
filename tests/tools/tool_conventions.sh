#!/bin/sh
# Every tool answers --version (its version, the library's, the bitstream's) and --help with
# exit 0, exits 2 on an unknown option, and run without its input prints its usage and exits 2
# at once (no default work: a bare `m4d encode` once started a 30-minute encode).
#   tool_conventions.sh TOOL...   (the m4d command line is the one named m4d)
set -u
fail() {
  echo "tool_conventions: $*" >&2
  exit 1
}
expect() {  # expect STATUS COMMAND...: runs it (at most 20 s) and checks its exit status
  want=$1
  shift
  timeout 20 "$@" > out.txt 2> err.txt
  got=$?
  [ "$got" -eq "$want" ] || fail "'$*' exited $got, not $want: $(head -c 300 err.txt)"
}
cd "$(mktemp -d)" || exit 1
for tool in "$@"; do
  expect 0 "$tool" --version
  grep -q "^$(basename "$tool") [0-9.]* (libm4d [0-9.]*, bitstream [0-9]*\.[0-9]*)$" out.txt ||
    fail "$tool --version printed '$(cat out.txt)'"
  expect 0 "$tool" --help
  grep -q -i usage out.txt || fail "$tool --help printed no usage"
  expect 2 "$tool" --no-such-option
  expect 2 "$tool"
  grep -q -i usage err.txt || fail "$tool without arguments printed no usage"
  if [ "$(basename "$tool")" = m4d ]; then
    for command in scene train encode rd ablate bench; do
      expect 2 "$tool" $command
      grep -q -i usage err.txt || fail "m4d $command without arguments printed no usage"
    done
  fi
done
[ -z "$(ls)" ] || [ "$(ls)" = "err.txt
out.txt" ] || fail "a tool wrote into the current folder: $(ls)"
