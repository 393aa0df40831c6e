#!/usr/bin/env bash
# The table of malformed scenes: every tests/app/bad_input/NAME.prm
# is a scene with one mistake, run through the real executable. Each must
# exit with status 1 (no signal, no time-out) and one "Error: ..." line on
# stderr that contains every "# expect: TEXT" line of the file (the
# section/entry and the allowed values) and one of its "# expect-any: TEXT"
# lines, if it has any (for scenes where the OpenBLAS kernel's rounding
# decides which of two refusals comes first), and none of its "# reject: TEXT"
# lines (not even in a warning); an "# env: VAR=VALUE" line sets an
# environment variable for the run; a "# setup: COMMAND" line runs COMMAND
# (bash) in the working directory first (the files an include cycle, a
# link or a FIFO needs); a "# filter: COMMAND" line writes the scene through
# COMMAND, for bytes a text file cannot hold (UTF-16, NUL and other control
# characters: tr '@' '\000'). No message may hold a raw control character
# (doc/errors-and-limits.md). A valid run in the same directory comes
# first, and no failed run may change its results or leave a temporary file;
# a "# failed-run: CYCLES" line says the run fails after writing CYCLES
# cycles, whose results must then be in results/failed-run/.
# Prints the table (name | message) that README.md's "Errors you may see"
# summarises.
# usage: bad_input.sh PROGRAM TESTS_APP_DIRECTORY
set -u
program=$1
here=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$here/bad_input_base.prm" "$work/base.prm"
cp "$here"/*.msh "$work/"
cd "$work"
passed=0
failed=0
fail() { echo "FAILED: $*"; failed=$((failed + 1)); }

"$program" base.prm >stdout 2>stderr || { fail "the valid base scene"; cat stderr; }
snapshot() { (cd results && find . -maxdepth 1 -type f -exec md5sum {} + | sort); }
snapshot >before.md5

run_bad() { # name, then the command
  local name=$1
  shift
  timeout 60 "$@" >stdout 2>stderr
  local status=$?
  local errors
  errors=$(grep -v '^Warning: ' stderr)
  if [ $status -ne 1 ]; then
    fail "$name: exit status $status (1 expected)"; cat stderr; return 1
  fi
  if [ "$(printf '%s\n' "$errors" | wc -l)" -ne 1 ] ||
     [[ "$errors" != "Error: "* ]]; then
    fail "$name: stderr is not one 'Error: ...' line"; cat -v stderr; return 1
  fi
  if [ "$(LC_ALL=C tr -d '\n\040-\176\200-\377' <stderr | wc -c)" -ne 0 ]; then
    fail "$name: stderr holds a raw control character"; cat -v stderr; return 1
  fi
  if ! snapshot | cmp -s - before.md5 ||
     [ -n "$(find . -name '*.tmp')" ] || [ -e results/previous-run ]; then
    fail "$name: the earlier results changed or a temporary file or results/previous-run is left"
    return 1
  fi
  return 0
}

echo "| scene | message |"
echo "|---|---|"
for scene in "$here"/bad_input/*.prm; do
  name=$(basename "$scene" .prm)
  setup=$(sed -n 's/^# setup: //p' "$scene")
  [ -z "$setup" ] || bash -c "$setup" || fail "$name: its setup failed"
  filter=$(sed -n 's/^# filter: //p' "$scene")
  if [ -n "$filter" ]; then
    bash -c "$filter" <"$scene" >"$name.prm" || fail "$name: its filter failed"
  else
    cp "$scene" "$name.prm"
  fi
  environment=()
  while IFS= read -r line; do
    environment+=("$line")
  done < <(sed -n 's/^# env: //p' "$scene")
  if run_bad "$name" env "${environment[@]}" "$program" "$name.prm"; then
    ok=1
    while IFS= read -r expected; do
      if ! grep -qF -- "$expected" stderr; then
        fail "$name: the message lacks <$expected>"; cat stderr; ok=0
      fi
    done < <(sed -n 's/^# expect: //p' "$scene")
    alternatives=$(sed -n 's/^# expect-any: //p' "$scene")
    if [ -n "$alternatives" ]; then
      matched=0
      while IFS= read -r expected; do
        grep -qF -- "$expected" stderr && matched=1
      done <<<"$alternatives"
      if [ $matched -eq 0 ]; then
        fail "$name: the message lacks each of the '# expect-any:' texts"; cat stderr; ok=0
      fi
    fi
    while IFS= read -r unwanted; do
      if grep -qF -- "$unwanted" stderr; then
        fail "$name: stderr holds <$unwanted>"; cat stderr; ok=0
      fi
    done < <(sed -n 's/^# reject: //p' "$scene")
    if [ -z "$(sed -n 's/^# expect: //p' "$scene")$alternatives" ]; then
      fail "$name: no '# expect:' line"; ok=0
    fi
    cycles=$(sed -n 's/^# failed-run: //p' "$scene")
    if [ -n "$cycles" ]; then
      if [ "$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(len(d["cycles"]))' results/failed-run/summary.json 2>/dev/null)" != "$cycles" ]; then
        fail "$name: results/failed-run/summary.json with $cycles cycle(s) expected"; ok=0
      fi
      grep -q "failed-run" stdout || { fail "$name: the log does not name failed-run"; ok=0; }
    elif [ -e results/failed-run ]; then
      fail "$name: failed before writing anything, yet results/failed-run exists"; ok=0
    fi
    rm -rf results/failed-run
    [ $ok = 1 ] && passed=$((passed + 1)) &&
      echo "| $name | $(sed 's/^Error: //; s/|/\\|/g' stderr | grep -v '^Warning: ') |"
  fi
done

# The command line itself.
run_bad "no parameter file" "$program" no-such.prm && grep -q "no-such.prm" stderr &&
  passed=$((passed + 1)) || fail "missing parameter file not named"
run_bad "a directory as parameter file" "$program" . && grep -q "<.>" stderr &&
  passed=$((passed + 1)) || fail "directory as parameter file not named"
"$program" >stdout 2>stderr
[ $? -eq 2 ] && grep -q "usage" stderr && passed=$((passed + 1)) ||
  fail "no argument: usage and status 2 expected"

# An argument that begins with '-' and is no option of the program (a
# misspelt or extended option, a lone '-', a scene named -x.prm even when
# it exists): the usage, status 2; that scene runs as ./-x.prm.
sed 's/^set Output directory = .*/set Output directory = dash-results/' base.prm >./-x.prm
for option in --help=1 --print-parameter -x.prm -; do
  "$program" "$option" >stdout 2>stderr
  [ $? -eq 2 ] && grep -q "usage" stderr &&
    grep -qF -- "unknown option <$option>" stderr && [ ! -s stdout ] &&
    [ ! -e dash-results ] && passed=$((passed + 1)) ||
    { fail "$option: unknown option, usage and status 2 expected"; cat stderr; }
done
for option in --help -h; do
  "$program" $option >stdout 2>stderr && grep -q "usage" stdout && [ ! -s stderr ] &&
    passed=$((passed + 1)) || fail "$option: usage on stdout and status 0 expected"
done
if "$program" ./-x.prm >stdout 2>stderr && [ -s dash-results/summary.json ] &&
   [ ! -s stderr ]; then
  passed=$((passed + 1))
else
  fail "./-x.prm: a scene whose name begins with - must run"; cat stderr
fi

# A UTF-8 byte-order mark is text: a scene and an included file that begin
# with one run (doc/errors-and-limits.md, "Include files, encodings and
# control characters").
{ printf '\357\273\277'; sed 's/^set Output directory = .*/set Output directory = bom-results/' base.prm; } >bom.prm
{ printf '\357\273\277include bom.prm\n'; } >bom-includer.prm
for scene in bom.prm bom-includer.prm; do
  rm -rf bom-results
  if "$program" $scene >stdout 2>stderr && [ -s bom-results/summary.json ] &&
     [ ! -s stderr ]; then
    passed=$((passed + 1))
  else
    fail "$scene: a UTF-8 byte-order mark must be accepted"; cat -v stderr
  fi
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
