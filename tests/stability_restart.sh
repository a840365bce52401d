#!/bin/sh
# granflow stability --restart: an analysis stopped midway and continued ends as one run through.
# Usage: stability_restart.sh GRANFLOW CASE DIR
# The slope at 40 x 10 cells to t = 2 s (about 1 s a trial): the analysis to a tolerance of 0.3 (four
# trials), its last row then dropped from the table as if it had been killed in that trial, continued
# to 0.05, must find the factor and the trials (factor, verdict, displacements) of the analysis run
# to 0.05 at once, taking three trials from the earlier analysis and running the unfinished one again.
# A continuation with another case or displacement limit is refused, status 2, the earlier analysis
# kept.
set -f
g=$1 c=$2 d=$3
run() { "$g" stability "$c" --set 'mesh.cells=[40,10]' --set time.end=2 --set output.progress_seconds=0 "$@"; }
rm -rf "$d" "$d.once"
run -o "$d.once" --tolerance 0.05 > "$d.once.log" 2>&1 || { cat "$d.once.log"; exit 1; }
run -o "$d" --tolerance 0.3 > "$d.log" 2>&1 || { cat "$d.log"; exit 1; }
test -d "$d/F_1.25" || { echo "no trial F_1.25 to leave unfinished"; exit 1; }
head -n 4 "$d/stability.csv" > "$d/table" && mv "$d/table" "$d/stability.csv"
run -o "$d" --restart --tolerance 0.05 > "$d.log" 2>&1 || { cat "$d.log"; exit 1; }
cat "$d.log"
test "$(grep -c 'from the earlier analysis)$' "$d.log")" -eq 3 || { echo "not three trials taken"; exit 1; }
grep -q "F_1.25: a trial the earlier analysis did not finish" "$d.log" || { echo "the unfinished trial not said"; exit 1; }
grep '^factor of safety' "$d.log" | sed 's/; trials in.*//' > "$d.factor"
grep '^factor of safety' "$d.once.log" | sed 's/; trials in.*//' > "$d.once.factor"
cmp "$d.factor" "$d.once.factor" || { cat "$d.factor" "$d.once.factor"; exit 1; }
cut -d, -f1-5 "$d/stability.csv" > "$d.rows"
cut -d, -f1-5 "$d.once/stability.csv" > "$d.once.rows"
cmp "$d.rows" "$d.once.rows" || { diff "$d.rows" "$d.once.rows"; exit 1; }
cp "$d/stability.csv" "$d.kept"
run -o "$d" --restart --set soil.rheology.cohesion=1000 > "$d.other.log" 2>&1
status=$?
test $status -eq 2 && grep -q "^error: the analysis in .* is of another case than this one (its trial at F = 1 ran" "$d.other.log" \
  || { echo "another case: status $status"; cat "$d.other.log"; exit 1; }
run -o "$d" --restart --displacement 0.1 > "$d.other.log" 2>&1
status=$?
test $status -eq 2 && grep -q "^error: the analysis in .* judged its trials by a displacement of 0.2 m, this one by 0.1 m" "$d.other.log" \
  || { echo "another limit: status $status"; cat "$d.other.log"; exit 1; }
cmp "$d/stability.csv" "$d.kept" || { echo "the refused continuation changed the table"; exit 1; }
echo "continued: the same factor and trials"
