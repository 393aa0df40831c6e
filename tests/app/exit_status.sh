#!/usr/bin/env bash
# The executable's contract (doc/parameters.md, "Commands"): exit 0 on success,
# non-zero with a one-line "Error: ..." on stderr for bad input, and a failed
# run never destroys the results of an earlier one.
# usage: exit_status.sh PROGRAM SCENE_DIRECTORY
set -u
program=$1
scenes=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
passed=0
failed=0
expect() { # description, expected status (0 or nonzero), command...
  local what=$1 want=$2
  shift 2
  "$@" >stdout 2>stderr
  local status=$?
  if { [ "$want" = 0 ] && [ $status -eq 0 ]; } ||
     { [ "$want" = nonzero ] && [ $status -ne 0 ] && grep -q "^Error: " stderr &&
       [ "$(wc -l <stderr)" -le 2 ]; }; then
    echo "ok: $what (status $status)"
    passed=$((passed + 1))
  else
    echo "FAILED: $what (status $status)"; cat stderr
    failed=$((failed + 1))
  fi
}

expect "--print-parameters" 0 "$program" --print-parameters
expect "--print-results" 0 "$program" --print-results
grep -q "^  max_w, min_w \[length\]" stdout && grep -q "^cycles.goal:" stdout &&
  echo "ok: --print-results lists the declared keys" && passed=$((passed + 1)) ||
  { echo "FAILED: --print-results misses keys"; failed=$((failed + 1)); }
printf 'set Output directory = run\ninclude %s/flexible-square.prm\nset Output directory = run\n' "$scenes" >good.prm
expect "shipped scene" 0 "$program" good.prm
# a finished run says so: "finished": true, then the flag file written last
# (doc/outputs.md, "complete"), and no lock or folder left behind
if grep -q '"finished": true' run/summary.json && [ -f run/complete ] &&
   [ ! -e run/.plate-on-halfspace.lock ] && [ ! -e run/previous-run ]; then
  echo "ok: a finished run is marked complete"; passed=$((passed + 1))
else
  echo "FAILED: no complete flag or \"finished\": true, or a lock left"; failed=$((failed + 1))
fi
cp run/summary.json before.json
expect "missing file" nonzero "$program" no-such.prm
printf 'subsection Plate\n  set Thickness = -1\nend\n' >bad.prm
expect "bad value" nonzero "$program" bad.prm
grep -q "Thickness" stderr && echo "ok: message names the entry" && passed=$((passed + 1)) ||
  { echo "FAILED: message does not name Thickness"; failed=$((failed + 1)); }
cat good.prm >offplate.prm
printf 'subsection Loads\n  set Point loads = 100,0,1\nend\n' >>offplate.prm
expect "point load off the plate, same output directory" nonzero "$program" offplate.prm
if cmp -s before.json run/summary.json && ! ls run/.*.tmp >/dev/null 2>&1 &&
   [ -f run/complete ]; then
  echo "ok: earlier summary.json and complete flag intact, no temporary file left"
  passed=$((passed + 1))
else
  echo "FAILED: earlier results changed"; failed=$((failed + 1))
fi
if grep -qi "nan" run/summary.json run/profile-00.csv; then
  echo "FAILED: NaN in results"; failed=$((failed + 1))
else
  echo "ok: no NaN in results"; passed=$((passed + 1))
fi
printf 'include %s/rigid-disk.prm\nset Output directory = up\nsubsection Foundation\n  set Contact = tensionless\nend\nsubsection Loads\n  set Point loads = 0,0,-1000\nend\n' "$scenes" >upward.prm
expect "upward-only load on a tensionless foundation" nonzero "$program" upward.prm
grep -q "lift the plate" stderr && echo "ok: the mechanism guard names the reason" && passed=$((passed + 1)) ||
  { echo "FAILED: no mechanism message"; failed=$((failed + 1)); }
# out of memory where no memory guard foresaw it (10^6 cells under a 2 GB
# address-space limit): one Error line naming the entries, earlier results kept
printf 'set Output directory = run\ninclude %s/flexible-square.prm\nset Output directory = run\nsubsection Discretization\n  set Subdivisions x = 1000\n  set Subdivisions y = 1000\nend\n' "$scenes" >huge.prm
expect "out of memory under ulimit -v" nonzero bash -c "ulimit -v 2000000; exec \"$program\" huge.prm"
grep -q "^Error: out of memory (std::bad_alloc): .*Discretization/Subdivisions" stderr &&
  cmp -s before.json run/summary.json &&
  echo "ok: out of memory says so and keeps the earlier results" && passed=$((passed + 1)) ||
  { echo "FAILED: no out-of-memory message or earlier results changed"; failed=$((failed + 1)); }
# a Latin-1 byte (not UTF-8) in a comment and a directory name: runs, as
# the checks of the parsed scene never pass its values through a parser
# that insists on UTF-8
printf 'set Output directory = run\ninclude %s/flexible-square.prm\nset Output directory = r\351sults # caf\351\n' "$scenes" >latin1.prm
expect "Latin-1 bytes in a scene" 0 "$program" latin1.prm
# JSON and XML scenes (deal.II reads them by the extension): messages in
# the .prm messages' words, and a valid JSON scene runs
jsonxml() { # description, file, expected text
  expect "$1" nonzero "$program" "$2"
  grep -qF -- "$3" stderr && echo "ok: $1 names it" && passed=$((passed + 1)) ||
    { echo "FAILED: $1 lacks <$3>"; failed=$((failed + 1)); }
}
printf '{"Plate": {"Thickness": "-1"}}' >value.json
jsonxml "JSON value outside its pattern" value.json \
  "Plate/Thickness: the value <-1> is not allowed; it must be a number > 0."
printf '{"Plate": {"Thikness": {"value": "1"}}}' >name.json
jsonxml "JSON misspelt entry" name.json "Did you mean <Thickness>?"
printf '{"Plate": ' >broken.json
jsonxml "malformed JSON" broken.json "broken.json is not a valid JSON scene: line"
printf '<ParameterHandler><Plat><Thickness><value>1</value></Thickness></Plat></ParameterHandler>' >section.xml
jsonxml "XML misspelt subsection" section.xml "subsection <Plat> does not exist"
printf '<Plate></Plate>' >root.xml
jsonxml "XML without its root" root.xml "root element <ParameterHandler>"
python3 -c "print('{\"a\":' * 100000 + '1' + '}' * 100000)" >deep.json
jsonxml "JSON nested 10^5 deep (a stack overflow in the parser)" deep.json "nests its objects 100000 deep"
printf '<ParameterHandler><Plate><!-- the plate --><Thickness>0.2</Thickness></Plate></ParameterHandler>' >comment.xml
jsonxml "XML comment" comment.xml "an XML scene takes no comments"
printf '<ParameterHandler><Plate><Thickness>\n 0.2\n</Thickness></Plate></ParameterHandler>' >padded.xml
jsonxml "XML value with spaces around it" padded.xml "(without spaces around it)"
printf '"hello"' >lone.json
jsonxml "JSON file of one string" lone.json "does not hold a JSON object"
printf '{"Plate": {"": {}}}' >unnamed.json
jsonxml "JSON entry with an empty name" unnamed.json "or an entry named \"\""
cp "$scenes/flexible-square.prm" scene.txt
jsonxml "scene named .txt" scene.txt "scene.txt: a scene file's name ends in .prm, .json or .xml"
cp "$scenes/flexible-square.prm" scene
jsonxml "scene without an ending" scene "this one has no ending"
printf '{"Plate": {"Thickness": "0.2"}}' | iconv -f UTF-8 -t UTF-16 >utf16.json
jsonxml "UTF-16 JSON" utf16.json "(it looks UTF-16 encoded)"
printf '\357\273\277{"Output directory": "bom", "Loads": {"Uniform pressure": "10"}, "Output": {"VTU": "false"}, "Discretization": {"Subdivisions x": "2", "Subdivisions y": "2"}}' >bom.json
expect "JSON scene with a UTF-8 byte-order mark" 0 "$program" bom.json
printf '{"Output directory": "json", "Loads": {"Uniform pressure": "10"}, "Output": {"VTU": "false"}, "Discretization": {"Subdivisions x": "2", "Subdivisions y": "2"}}' >good.json
expect "valid JSON scene" 0 "$program" good.json
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
