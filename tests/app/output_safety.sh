#!/usr/bin/env bash
# The output directory's safety (doc/outputs.md, "Safety of the output
# directory"): a planted link is never followed, a NUL in the name never
# deletes a directory, a second run into a busy directory is refused, SIGINT
# and SIGTERM restore the earlier results and exit with 128 + the signal,
# a killed run leaves no `complete` flag and the next run recovers, an
# unwritable directory is refused before anything is computed, and sweep.csv
# is a result file. Prints one verdict per check; no timing, no paths.
# usage: output_safety.sh PROGRAM TESTS_APP_DIRECTORY
set -u
program=$1
here=$2
work=$(mktemp -d)
background=
cleanup() {
  [ -n "$background" ] && kill -KILL "$background" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
cp "$here/bad_input_base.prm" "$work/base.prm"
cd "$work"
passed=0
failed=0
check() { # description, then a command that must succeed
  local what=$1
  shift
  if "$@"; then
    echo "ok: $what"
    passed=$((passed + 1))
  else
    echo "FAILED: $what"
    failed=$((failed + 1))
  fi
}
# the regular files of a directory (hidden ones too) and their checksums
snapshot() { (cd "$1" && find . -maxdepth 1 -type f -exec md5sum {} + | sort); }
same_snapshot() { [ "$(snapshot "$1")" = "$2" ]; }
one_error_line() { # stderr file: exactly one line, "Error: ..."
  [ "$(grep -vc '^Warning: ' "$1")" -eq 1 ] && grep -q '^Error: ' "$1"
}
json() { # file, Python expression on d
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if eval(sys.argv[2]) else 1)' "$1" "$2" 2>/dev/null
}
finished_run() { # directory: a finished, committed run and nothing left over
  [ -f "$1/complete" ] && json "$1/complete" '"finished" in d and d["cycles"] >= 1' &&
    json "$1/summary.json" 'd["finished"] is True and d["converged"] is True' &&
    [ ! -e "$1/previous-run" ] && [ ! -e "$1/failed-run" ] &&
    [ -z "$(find "$1" -maxdepth 1 -name '.*.tmp')" ] &&
    [ ! -e "$1/.plate-on-halfspace.lock" ]
}
wait_for() { # seconds, then a command; polls every 0.05 s
  local limit=$(($1 * 20))
  shift
  for ((i = 0; i < limit; ++i)); do
    "$@" && return 0
    sleep 0.05
  done
  return 1
}
no_link_left() { [ -z "$(find "$1" -maxdepth 1 -type l)" ]; }

# Scenes: quick (2 x 2 cells, well under a second), a sweep, one that fails
# before writing anything, and a slow one (tensionless, three cycles of
# global refinement: several seconds) that writes its first cycle early.
quick() { printf 'include base.prm\nset Output directory = %s\n' "$1" >"$2"; }
quick_vtu() {
  quick "$1" "$2"
  printf 'subsection Output\n  set VTU = true\nend\n' >>"$2"
}
failing() { # a point load off the plate: fails before writing anything
  quick "$1" "$2"
  printf 'subsection Loads\n  set Point loads = 100,0,1\nend\n' >>"$2"
}
sweep() {
  quick "$1" "$2"
  printf 'subsection Loads\n  set Axles = single, 0, 0, 0, 20, 700\n  set Sweep = -0.2, 0, 0.2, 0, 3\nend\n' >>"$2"
}
slow() {
  quick "$1" "$2"
  printf 'subsection Foundation\n  set Contact = tensionless\nend\nsubsection Loads\n  set Point loads = 0.3,0.2,50\nend\nsubsection Discretization\n  set Subdivisions x = 6\n  set Subdivisions y = 6\n  set Symmetry = none\nend\nsubsection Adaptivity\n  set Cycles = 3\n  set Refinement = global\nend\nsubsection Output\n  set Verbosity = 1\nend\n' >>"$2"
}
start_slow() { # directory: the slow scene in the background, pid in $background
  slow "$1" slow.prm
  "$program" slow.prm >slow.out 2>slow.err &
  background=$!
}
new_cycle_written() { # directory: the slow run set the earlier results aside and wrote cycle 0
  [ -d "$1/previous-run" ] && [ -f "$1/summary.json" ] && json "$1/summary.json" 'd["finished"] is False'
}

# 1. A finished run marks itself: `complete`, "finished": true, no lock left.
quick done done.prm
"$program" done.prm >stdout 2>stderr
check "a finished run writes complete last and leaves no lock, temporary or folder" finished_run done

# 2. Links planted at every temporary name, at a final name, at the probe
#    name: the run writes its own files and the victims keep their content.
echo precious >victim.txt
echo precious >victim2.txt
mkdir links
for name in summary.json convergence.txt profile-00.csv nodes-00.csv \
  gauss-profile-00.csv solution-00.vtu solution.pvd complete; do
  ln -s "$work/victim.txt" "links/.$name.tmp"
done
ln -s "$work/victim.txt" links/.plate-on-halfspace.probe.tmp
ln -s "$work/victim2.txt" links/profile-00.csv
quick_vtu links links.prm
"$program" links.prm >stdout 2>stderr
status=$?
check "planted links at the temporary names: the run succeeds" [ $status -eq 0 ]
check "planted links at the temporary names: the victims are untouched" \
  [ "$(cat victim.txt victim2.txt)" = "$(printf 'precious\nprecious')" ]
check "planted links at the temporary names: the results are regular files, no link is left" \
  eval '[ -f links/summary.json ] && [ ! -L links/profile-00.csv ] && [ ! -L links/summary.json ] && no_link_left links && finished_run links'

# 3. A link planted as previous-run/ (or failed-run/) pointing at a victim
#    folder with result-like files: the victim is untouched, so are the
#    earlier results.
mkdir victim_dir
echo '{"victim": true}' >victim_dir/summary.json
echo keep >victim_dir/convergence.txt
echo keep >victim_dir/notes.txt
victim_before=$(snapshot victim_dir)
quick prev prev.prm
"$program" prev.prm >stdout 2>stderr
earlier=$(snapshot prev)
ln -s "$work/victim_dir" prev/previous-run
failing prev prev_bad.prm
"$program" prev_bad.prm >stdout 2>stderr
status=$?
check "previous-run is a planted link, failing run: status 1 with one Error line" \
  eval '[ $status -eq 1 ] && one_error_line stderr'
"$program" prev.prm >stdout 2>stderr
status=$?
check "previous-run is a planted link, good run: refused, naming previous-run" \
  eval '[ $status -eq 1 ] && one_error_line stderr && grep -q "previous-run" stderr'
check "previous-run is a planted link: the victim folder is untouched" same_snapshot victim_dir "$victim_before"
check "previous-run is a planted link: the earlier results are untouched" same_snapshot prev "$earlier"
rm -rf prev/previous-run
# failed-run/ as a link, with a run that fails after writing a cycle
ln -s "$work/victim_dir" prev/failed-run
quick prev second.prm
printf 'subsection Discretization\n  set Symmetry = none\nend\nsubsection Adaptivity\n  set Cycles = 2\n  set Refinement = global\nend\n' >>second.prm
PLATE_ON_HALFSPACE_MEMORY_LIMIT=100K "$program" second.prm >stdout 2>stderr
status=$?
check "failed-run is a planted link, run failing in cycle 1: status 1" [ $status -eq 1 ]
check "failed-run is a planted link: the victim folder is untouched" same_snapshot victim_dir "$victim_before"
check "failed-run is a planted link: the earlier results are back" same_snapshot prev "$earlier"
rm -rf prev/failed-run
# a link at the lock file's name
ln -s "$work/victim.txt" prev/.plate-on-halfspace.lock
"$program" prev.prm >stdout 2>stderr
status=$?
check "the lock file is a planted link: refused, the victim and the results untouched" \
  eval '[ $status -eq 1 ] && one_error_line stderr && [ "$(cat victim.txt)" = precious ] && [ -L prev/.plate-on-halfspace.lock ]'
rm -f prev/.plate-on-halfspace.lock
check "the lock file is a planted link: the earlier results are untouched" same_snapshot prev "$earlier"
# a hard link at the lock file's name: the pid must not overwrite the victim
ln "$work/victim.txt" prev/.plate-on-halfspace.lock
"$program" prev.prm >stdout 2>stderr
status=$?
check "the lock file is a planted hard link: refused, the victim untouched" \
  eval '[ $status -eq 1 ] && one_error_line stderr && [ "$(cat victim.txt)" = precious ]'
rm -f prev/.plate-on-halfspace.lock
check "the lock file is a planted hard link: the earlier results are untouched" same_snapshot prev "$earlier"

# 4. A NUL inside Output directory: the system calls would see the parent.
mkdir parent
echo keep >parent/sentinel.txt
quick parent/results parent_results.prm
"$program" parent_results.prm >stdout 2>stderr
parent_before=$(snapshot parent)$(snapshot parent/results)
printf 'include base.prm\nset Output directory = %s/parent\000/results\n' "$work" >nul.prm
"$program" nul.prm >stdout 2>stderr
status=$?
check "a NUL in Output directory: non-zero status and one Error line" \
  eval '[ $status -ne 0 ] && one_error_line stderr'
check "a NUL in Output directory: the parent directory and its files survive" \
  eval '[ "$(snapshot parent)$(snapshot parent/results)" = "$parent_before" ]'

# 5. Two runs into one directory: the second is refused at once, naming the
#    first's pid; the first finishes with its results whole.
quick busy busy_quick.prm
"$program" busy_quick.prm >stdout 2>stderr
start_slow busy
first=$background
wait_for 60 test -f busy/.plate-on-halfspace.lock
"$program" busy_quick.prm >second.out 2>second.err
status=$?
check "a second run into a busy directory: status 1, one Error line naming the first run's pid" \
  eval '[ $status -eq 1 ] && one_error_line second.err && grep -q "^Error: Output directory: <busy> is in use by another run (pid $first)" second.err'
wait "$first"
status=$?
background=
check "the first run finishes with its results whole" \
  eval '[ $status -eq 0 ] && finished_run busy && json busy/summary.json "len(d[\"cycles\"]) == 3"'

# 6. SIGTERM and SIGINT during the run: exit 128 + signal, the earlier
#    results back (with their `complete`), this run's files in failed-run/
#    marked unfinished, no lock left.
for signal in TERM INT; do
  quick "sig$signal" q.prm
  "$program" q.prm >stdout 2>stderr
  earlier=$(snapshot "sig$signal")
  start_slow "sig$signal"
  if ! wait_for 60 new_cycle_written "sig$signal"; then
    echo "FAILED: SIG$signal: the slow run did not write its first cycle"
    failed=$((failed + 1))
  fi
  kill "-$signal" "$background"
  # it must stop within a contact iteration, not run to its end
  wait_for 60 eval '! kill -0 $background 2>/dev/null'
  wait "$background"
  status=$?
  background=
  want=$((128 + $(kill -l "$signal")))
  check "SIG$signal: exit status $want" [ $status -eq $want ]
  check "SIG$signal: one Error line 'interrupted by SIG$signal'" \
    eval 'one_error_line slow.err && grep -q "^Error: interrupted by SIG$signal;" slow.err'
  check "SIG$signal: the earlier results are back, complete included, no lock or temporary left" \
    eval 'same_snapshot "sig$signal" "$earlier" && [ -f "sig$signal/complete" ] && [ ! -e "sig$signal/previous-run" ]'
  check "SIG$signal: the interrupted run's files are in failed-run/, unfinished, without complete" \
    eval 'json "sig$signal/failed-run/summary.json" "d[\"finished\"] is False and d[\"converged\"] is False" && [ ! -e "sig$signal/failed-run/complete" ]'
done

# 7. SIGKILL: no `complete` beside the killed run's files, its summary.json
#    unfinished; the next run recovers (a failing one restores the results
#    before the killed run, a good one finishes cleanly). sweep.csv is set
#    aside like every result file.
sweep killed sweep.prm
"$program" sweep.prm >stdout 2>stderr
check "a sweep run writes sweep.csv" test -f killed/sweep.csv
earlier=$(snapshot killed)
start_slow killed
wait_for 60 new_cycle_written killed
kill -KILL "$background"
wait "$background" 2>/dev/null
background=
check "SIGKILL: no complete flag beside the killed run's files" \
  eval '[ ! -e killed/complete ] && [ -f killed/previous-run/complete ]'
check "SIGKILL: the visible summary.json says unfinished, not converged" \
  json killed/summary.json 'd["finished"] is False and d["converged"] is False'
check "SIGKILL: sweep.csv was set aside with the earlier results" \
  eval '[ ! -e killed/sweep.csv ] && [ -f killed/previous-run/sweep.csv ]'
failing killed killed_bad.prm
"$program" killed_bad.prm >stdout 2>stderr
status=$?
check "after SIGKILL, a failing run: status 1, the results before the killed run are back" \
  eval '[ $status -eq 1 ] && same_snapshot killed "$earlier" && [ ! -e killed/previous-run ]'
check "after SIGKILL, the killed run's files are in failed-run/" \
  json killed/failed-run/summary.json 'd["finished"] is False'
quick killed killed_good.prm
"$program" killed_good.prm >stdout 2>stderr
status=$?
check "after SIGKILL, a good run finishes cleanly and drops the earlier sweep.csv" \
  eval '[ $status -eq 0 ] && finished_run killed && [ ! -e killed/sweep.csv ]'

# 8. Killed while moving the earlier results aside (the state built by
#    hand: part of them in previous-run/ with its .moving marker): the next
#    run puts them back first.
quick moving moving.prm
"$program" moving.prm >stdout 2>stderr
earlier=$(snapshot moving)
mkdir moving/previous-run
: >moving/previous-run/.moving
mv moving/complete moving/summary.json moving/previous-run/
failing moving moving_bad.prm
"$program" moving_bad.prm >stdout 2>stderr
check "killed while setting the results aside: the next run restores them all" \
  eval 'same_snapshot moving "$earlier" && [ ! -e moving/previous-run ] && [ ! -e moving/failed-run ]'

# 9. A directory that takes no new file (root ignores permission bits: a
#    directory of /proc): refused before anything is computed.
slow /proc/self unwritable.prm
"$program" unwritable.prm >stdout 2>stderr
status=$?
check "an unwritable directory: status 1, 'cannot write in', before cycle 0" \
  eval '[ $status -eq 1 ] && one_error_line stderr && grep -q "^Error: Output directory: cannot write in </proc/self>" stderr && ! grep -q "^cycle" stdout'

# 10. sweep.csv on failure: a run failing after writing a cycle restores it.
sweep sw sweep2.prm
"$program" sweep2.prm >stdout 2>stderr
earlier=$(snapshot sw)
quick sw sw_second.prm
printf 'subsection Discretization\n  set Symmetry = none\nend\nsubsection Adaptivity\n  set Cycles = 2\n  set Refinement = global\nend\n' >>sw_second.prm
PLATE_ON_HALFSPACE_MEMORY_LIMIT=100K "$program" sw_second.prm >stdout 2>stderr
check "a run failing in cycle 1 after a sweep: sweep.csv and the rest restored" \
  eval 'same_snapshot sw "$earlier" && [ -f sw/sweep.csv ] && [ ! -e sw/failed-run/sweep.csv ] && [ -f sw/failed-run/summary.json ]'

# 11. Files whose names only look like results (the program writes NN as
#     two digits, at most 30 cycles): finished runs leave them alone.
look_alike="profile-2024.csv nodes-7.csv solution-123.vtu gauss-profile-000.csv summary.json.bak notes.txt profile-99.csv solution-42.vtu nodes-30.csv gauss-profile-75.csv"
kept_look_alike() {
  local f
  for f in $look_alike; do
    [ "$(cat "alike/$f")" = mine ] || return 1
  done
}
quick alike alike.prm
mkdir alike
for f in $look_alike; do echo mine >"alike/$f"; done
"$program" alike.prm >stdout 2>stderr
status=$?
check "files named like results with other digits: the run succeeds and keeps them" \
  eval '[ $status -eq 0 ] && finished_run alike && kept_look_alike'
"$program" alike.prm >stdout 2>stderr
check "files named like results with other digits: a second run keeps them too" \
  eval 'finished_run alike && kept_look_alike'
echo mine >alike/.profile-99.csv.tmp
"$program" alike.prm >stdout 2>stderr
check "a hidden file named like a temporary of a cycle never written (99) is kept" \
  eval '[ "$(cat alike/.profile-99.csv.tmp)" = mine ] && kept_look_alike'

# 12. A FIFO planted at previous-run/.moving (the marker of results being
#     moved): the run refuses at once instead of waiting for a reader, and
#     the earlier results stay.
quick fifo fifo.prm
"$program" fifo.prm >stdout 2>stderr
earlier=$(snapshot fifo)
mkdir fifo/previous-run
mkfifo fifo/previous-run/.moving
timeout 60 "$program" fifo.prm >stdout 2>stderr
status=$?
check "a FIFO at previous-run/.moving: refused (status 1, no wait), the marker named, earlier results kept" \
  eval '[ $status -eq 1 ] && grep -q "previous-run/.moving" stderr && same_snapshot fifo "$earlier" && [ -p fifo/previous-run/.moving ]'

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
