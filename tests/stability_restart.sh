#!/bin/sh
# granflow stability --restart: an analysis stopped midway and continued ends as one run through.
# Usage: stability_restart.sh GRANFLOW CASE DIR [LAUNCHER...]   (LAUNCHER: e.g. mpirun -np 2)
# The slope at 40 x 10 cells to t = 2 s (about 1 s a trial): the analysis to a tolerance of 0.3 (four
# trials), then damaged as a stopped analysis may be (its last row dropped, as if killed in that trial;
# a listed trial's directory removed; its table's lines ended CRLF), continued to 0.05, must find the
# factor and the trials (factor, verdict, displacements) of the analysis run to 0.05 at once, taking
# two trials from the earlier analysis and running the other two again. An analysis stopped in its
# first trial (directories, no table) is continued from nothing. A continuation with another case or
# displacement limit is refused, status 2, the earlier analysis kept; so is one where -o is a file or
# holds a run, and an analysis into a run's directory or a run into an analysis's or one of its trials'.
set -f
g=$1 c=$2 d=$3
shift 3
launch="$*"
go() { $launch "$g" stability "$c" --set 'mesh.cells=[40,10]' --set time.end=2 --set output.progress_seconds=0 "$@"; }
fail() { echo "$1"; exit 1; }
rm -rf "$d" "$d.once" "$d.file" "$d.run"
go -o "$d.once" --tolerance 0.05 > "$d.once.log" 2>&1 || { cat "$d.once.log"; exit 1; }
# Its bracket at t = 2 s: F = 1.4375 fails at t = 1.97 s, F = 1.40625 stands having moved 17 % of the limit.
grep -q "^note: time.end = 2 s may have decided the bracket: the trial at F = 1.4375 failed only at t = 1.97 s, and the trial at F = 1.40625 stood having moved 0.0332 m, 17 % of the limit" "$d.once.log" \
  || { cat "$d.once.log"; fail "a bracket decided near time.end not noted"; }
go -o "$d" --tolerance 0.3 > "$d.log" 2>&1 || { cat "$d.log"; exit 1; }
test -d "$d/F_1.25" && test -d "$d/F_2" || fail "no trials F_1.25 and F_2 to damage"
head -n 4 "$d/stability.csv" | sed 's/$/\r/' > "$d/table" && mv "$d/table" "$d/stability.csv"
rm -r "$d/F_2"
go -o "$d" --restart --tolerance 0.05 > "$d.log" 2>&1 || { cat "$d.log"; exit 1; }
cat "$d.log"
test "$(grep -c 'from the earlier analysis)$' "$d.log")" -eq 2 || fail "not two trials taken"
grep -q "F_1.25: a trial the earlier analysis did not finish" "$d.log" || fail "the unfinished trial not said"
grep -q "F_2: the trial at F = 2 that stability.csv lists has no granflow_case.toml there" "$d.log" || fail "the lost trial not said"
grep '^factor of safety' "$d.log" | sed 's/; trials in.*//' > "$d.factor"
grep '^factor of safety' "$d.once.log" | sed 's/; trials in.*//' > "$d.once.factor"
cmp "$d.factor" "$d.once.factor" || { cat "$d.factor" "$d.once.factor"; exit 1; }
cut -d, -f1-5 "$d/stability.csv" > "$d.rows"
cut -d, -f1-5 "$d.once/stability.csv" > "$d.once.rows"
cmp "$d.rows" "$d.once.rows" || { diff "$d.rows" "$d.once.rows"; exit 1; }
# Stopped in its first trial: trial directories, no table.
rm "$d.once/stability.csv"
go -o "$d.once" --restart --tolerance 0.3 > "$d.once.log" 2>&1 || { cat "$d.once.log"; exit 1; }
grep -q "continuing the analysis there (0 trials finished)" "$d.once.log" && grep -q "^factor of safety: 1.375 " "$d.once.log" \
  || { cat "$d.once.log"; fail "not continued from nothing"; }
cp "$d/stability.csv" "$d.kept"
expect_refusal() {  # expect_refusal WHAT PATTERN ARGS...: status 2 and the pattern in the first line
  what=$1 pattern=$2
  shift 2
  go "$@" > "$d.other.log" 2>&1
  status=$?
  test $status -eq 2 && head -n 1 "$d.other.log" | grep -q "$pattern" || { cat "$d.other.log"; fail "$what: status $status"; }
}
expect_refusal "another case" "^error: the analysis in .* is of another case than this one (its trial at F = 1 ran" \
  -o "$d" --restart --set soil.rheology.cohesion=1000
expect_refusal "another limit" "^error: the analysis in .* judged its trials by a displacement of 0.2 m, this one by 0.1 m" \
  -o "$d" --restart --displacement 0.1
cmp "$d/stability.csv" "$d.kept" || fail "a refused continuation changed the table"
touch "$d.file"
expect_refusal "a file" "^error: -o .*\.file: not a directory" -o "$d.file" --restart
"$g" run "$c" -o "$d.run" --overwrite --set 'mesh.cells=[40,10]' --set time.end=0.01 --set output.progress_seconds=0 > /dev/null 2>&1 \
  || fail "the run to continue did not run"
expect_refusal "a run" "^error: .*\.run holds a run (.*), not an analysis: an analysis.s files would lie beside it" \
  -o "$d.run" --restart
expect_refusal "a run, a new analysis" "^error: .*\.run holds a run (.*), not an analysis" -o "$d.run"
# ... nor a run into an analysis's directory.
"$g" run "$c" -o "$d" --overwrite --set time.end=0.01 > "$d.other.log" 2>&1
status=$?
test $status -eq 2 && head -n 1 "$d.other.log" | grep -q "^error: .* holds a stability analysis (.*): a run.s files would lie beside it" \
  || { cat "$d.other.log"; fail "a run into an analysis: status $status"; }
cmp "$d/stability.csv" "$d.kept" || fail "a refused run changed the analysis"
"$g" run "$c" -o "$d/F_1.25/" --overwrite --set time.end=0.01 > "$d.other.log" 2>&1
status=$?
test $status -eq 2 && head -n 1 "$d.other.log" | grep -q "^error: .*/F_1.25/ is a trial of the stability analysis in " \
  || { cat "$d.other.log"; fail "a run into a trial's directory: status $status"; }
echo "continued: the same factor and trials"
