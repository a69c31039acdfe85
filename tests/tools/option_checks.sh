#!/bin/sh
# Bad values are usage errors found when the command line is parsed (exit 2, before any
# work), with the option named and its range as people write it; I/O errors say so; a JSON
# file that does not parse gives its line and column; asking more frames than a capture has is
# said; m4d train writes nothing it was not asked to.
#   option_checks.sh M4D DIR
set -u
m4d=$1
dir=$2
fail() {
  echo "option_checks: $*" >&2
  exit 1
}
expect() {  # expect STATUS COMMAND...: runs it (at most 60 s) and checks its exit status
  want=$1
  shift
  timeout 60 "$@" > "$dir/out.txt" 2> "$dir/err.txt"
  got=$?
  [ "$got" -eq "$want" ] || fail "'$*' exited $got, not $want: $(head -c 300 "$dir/err.txt")"
}
says() { grep -q -e "$1" "$dir/err.txt" || fail "no '$1' in: $(head -c 300 "$dir/err.txt")"; }
rm -rf "$dir"
mkdir -p "$dir/cwd"
"$m4d" scene -o "$dir/scene" --cameras 4 --width 32 --height 24 --frames 3 --points 300 \
  > /dev/null 2>&1 || fail "m4d scene failed"

# The scene is never opened: each value is refused while parsing, naming its option.
expect 2 "$m4d" encode "$dir/scene" --lambda nan
says -- '--lambda' && says 'not a finite number'
expect 2 "$m4d" encode "$dir/scene" --gop-psnr-drop nan
says -- '--gop-psnr-drop'
expect 2 "$m4d" encode "$dir/scene" --seed -1
says -- '--seed'
expect 2 "$m4d" encode "$dir/scene" --rate-point r9
says "unknown rate point 'r9'"
expect 2 "$m4d" encode "$dir/scene" --lambda -1
says '0 or more'
expect 2 "$m4d" encode "$dir/scene" --random-access 2e6
says 'from 0 to 1000000'
! grep -q '[0-9]\{16\}' "$dir/err.txt" || fail "a number of 16 digits or more: $(cat "$dir/err.txt")"

# An existing stream is a usage error (found before any work); an I/O error says I/O, not
# "invalid argument".
: > "$dir/old.m4d"
expect 2 "$m4d" encode "$dir/scene" -o "$dir/old.m4d"
says 'give --force'
expect 1 "$m4d" encode "$dir/scene" -o /proc/m4d_cannot_write_here/out.m4d
says 'I/O error'
! grep -q 'invalid argument' "$dir/err.txt" || fail "an I/O error said 'invalid argument'"

# m4d train's outputs and m4d scene's folder are kept unless --force, refused before any work.
: > "$dir/model.ply"
expect 2 "$m4d" train "$dir/scene" --ply "$dir/model.ply"
says 'give --force'
[ ! -s "$dir/model.ply" ] || fail "m4d train replaced an existing --ply"
expect 2 "$m4d" scene -o "$dir/scene" --cameras 4 --width 32 --height 24 --frames 1
says 'give --force'

# A transforms.json with NaN, a number too large or cut short: its line and column and why.
mkdir -p "$dir/bad"
printf '{\n  "fl_x": NaN\n}\n' > "$dir/bad/transforms.json"
expect 1 "$m4d" train "$dir/bad"
says "line 2, column 11: .*invalid literal"
printf '{"w": 32,\n "fl_x": 1e999}\n' > "$dir/bad/transforms.json"
expect 1 "$m4d" train "$dir/bad"
says "line 2, column 10: a number too large"
printf '{"frames": [\n  {"file_path": "a.png"' > "$dir/bad/transforms.json"
expect 1 "$m4d" train "$dir/bad"
says "line 2, column [0-9]*: .*unexpected end of input"

# --frames beyond the capture is said; a training run writes nothing into the current folder.
cd "$dir/cwd" || exit 1
expect 0 "$m4d" train "$dir/scene" --frames 99 --iterations 10
says 'warning: --frames 99, but the capture has 3 from frame 0: coding 3'
[ -z "$(ls -A)" ] || fail "m4d train wrote into the current folder: $(ls -A)"
