#!/usr/bin/env bash
# The planned sweep end to end: the quick plan run by GNU parallel (-j 2) merges into the
# serial quick sweep's rows with the same error figures (costs are timings and differ);
# the plan runs nothing; a re-run keeps whole results; a failed run and a cut-short result
# are named by the merge; the Slurm array script's arithmetic (which lines a task runs).
# Usage: sweep_plan_test.sh POLYSIM SCENES_DIR SLURM_SCRIPT
set -euo pipefail
polysim=$1 scenes=$2 slurm=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "sweep_plan_test: $*" >&2; exit 1; }
# The columns that are not timings: scene..dt, metric..solver_warnings.
figures() { cut -d, -f1-6,9-13 "$1"; }

"$polysim" sweep --quick --scenes "$scenes" --out serial.csv
"$polysim" sweep --quick --scenes "$scenes" --plan plan.txt --results runs
runs=$(($(wc -l < serial.csv) - 1))
test "$(wc -l < plan.txt)" -eq 50 || fail "the quick plan has $(wc -l < plan.txt) lines, not 50 (5 scenes x 10 settings)"
test -z "$(ls runs)" || fail "--plan ran something: $(ls runs | head -1)"
grep -q -- "--case drop_box --engine polysim --solver bisection --parameter-name tolerance_m --parameter 0.0001 --dt 0.016666666666666666 --out $work/runs/" plan.txt ||
  fail "a plan line does not name its scene, engine, settings and output: $(head -1 plan.txt)"

parallel --will-cite -j 2 < plan.txt
"$polysim" sweep --quick --merge runs --out merged.csv
test "$(wc -l < merged.csv)" -eq "$((runs + 1))" || fail "the merge has $(wc -l < merged.csv) lines, the serial sweep $((runs + 1))"
diff <(figures serial.csv) <(figures merged.csv) || fail "the merged figures differ from the serial sweep's"
awk -F, 'NR > 1 && !($14 > 0 && $15 > 0) { exit 1 }' merged.csv || fail "a run without its CPU time"

# Resumable: whole results are kept, not run again.
stamp=$(stat -c %Y.%s runs/*stack_5.polysim.bisection*0.0166667.csv)
sleep 1
parallel --will-cite -j 2 < plan.txt 2> rerun.err
test "$(stat -c %Y.%s runs/*stack_5.polysim.bisection*0.0166667.csv)" = "$stamp" || fail "a whole result was run again"
test "$(grep -c ": kept" rerun.err)" -eq 50 || fail "the re-run did not keep all 50 results"

# A cut-short result is named by the merge and run again by the plan.
cut_short=$(ls runs/bounce.*.csv | head -1)
head -c 200 "$(ls runs/drop_box.*.csv | head -1)" > "$cut_short"
if "$polysim" sweep --quick --merge runs --out partial.csv 2> merge.err; then fail "a cut-short result merged"; fi
grep -q "merged 49 of 50 runs" merge.err || fail "the merge did not count the cut-short run: $(cat merge.err)"
grep -q "$(basename "$cut_short" .csv): cut short or not this run's" merge.err || fail "the cut-short run is not named"
test "$(wc -l < partial.csv)" -eq "$runs" || fail "the partial merge does not hold the 49 whole runs"
parallel --will-cite -j 2 < plan.txt 2> /dev/null
"$polysim" sweep --quick --merge runs --out merged_again.csv
diff <(figures serial.csv) <(figures merged_again.csv) || fail "the re-run result differs"

# A run that fails (its scene is broken) is reported by the merge with its message.
cp -r "$scenes" broken
echo "{" > broken/bounce.json
"$polysim" sweep --quick --scenes broken --plan broken_plan.txt --results broken_runs
if parallel --will-cite -j 2 < broken_plan.txt 2> broken.err; then fail "runs on a broken scene succeeded"; fi
if "$polysim" sweep --quick --merge broken_runs --out broken.csv 2> merge.err; then fail "the merge hid failed runs"; fi
grep -q "merged 40 of 50 runs" merge.err || fail "not 10 failed runs: $(head -1 merge.err)"
test "$(grep -c "bounce\..*: failed: .*bounce.json" merge.err)" -eq 10 || fail "the failed runs are not named with their message"
test ! -e "$work/missing.csv"
if "$polysim" sweep --quick --merge nowhere --out missing.csv 2> merge.err; then fail "merged a missing folder"; fi
grep -q "nowhere: not a folder of sweep results" merge.err && test ! -e missing.csv || fail "a missing folder: $(cat merge.err)"

# The Slurm array script: how many tasks, and which lines task k runs.
test "$("$slurm" --tasks plan.txt)" -eq 50 || fail "--tasks plan.txt"
test "$("$slurm" --tasks plan.txt 6)" -eq 9 || fail "--tasks plan.txt 6: 50 lines in tasks of 6 are 9 tasks"
sed "s|$work/runs/|$work/slurm_runs/|" plan.txt > slurm_plan.txt
mkdir slurm_runs
SLURM_ARRAY_TASK_ID=9 "$slurm" slurm_plan.txt 6
test "$(ls slurm_runs | wc -l)" -eq 2 || fail "task 9 of 6 lines each ran $(ls slurm_runs | wc -l) runs, not lines 49 and 50"
for n in 49 50; do
  test -e "$(sed -n "${n}p" slurm_plan.txt | sed 's/.* --out //')" || fail "task 9 did not run plan line $n"
done
SLURM_ARRAY_TASK_ID=2 "$slurm" slurm_plan.txt 6
test "$(ls slurm_runs | wc -l)" -eq 8 || fail "task 2 of 6 lines each did not add lines 7 to 12"
SLURM_ARRAY_TASK_ID=10 "$slurm" slurm_plan.txt 6 | grep -q "nothing to run" || fail "task 10 is past the plan"
if SLURM_ARRAY_TASK_ID=0 "$slurm" slurm_plan.txt 2> /dev/null; then fail "task 0 was accepted (tasks count from 1)"; fi
if "$slurm" --tasks plan.txt 0 2> /dev/null; then fail "0 lines a task was accepted"; fi
echo "sweep plan ok"
