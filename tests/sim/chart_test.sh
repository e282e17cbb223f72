#!/usr/bin/env bash
# The chart end to end: `polysim sweep --quick` writes the CSV, plot_sweep.py draws it as
# PNG and SVG; a CSV that is not a sweep's gets one message naming it, exit 1, no image;
# an unwritable output fails before the runs.
# Usage: chart_test.sh POLYSIM SCENES_DIR PLOT_SCRIPT
set -euo pipefail
polysim=$1 scenes=$2 plot=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$polysim" sweep --quick --scenes "$scenes" --out "$work/sweep.csv"
test ! -e "$work/sweep.csv.partial"
/usr/bin/python3 "$plot" "$work/sweep.csv" "$work/chart"
head -c 8 "$work/chart.png" | grep -q PNG
grep -q "<svg" "$work/chart.svg"
grep -q "polysim bisection" "$work/chart.svg"
grep -q "ode quickstep" "$work/chart.svg"
grep -q "30 solver sweeps" "$work/chart.svg"
grep -q "time to rest" "$work/chart.svg"

echo "scene,engine" > "$work/bad.csv"
if /usr/bin/python3 "$plot" "$work/bad.csv" "$work/bad" 2> "$work/error"; then
  echo "plot_sweep.py accepted a CSV without the sweep's columns" >&2
  exit 1
fi
grep -q "bad.csv" "$work/error"
test "$(wc -l < "$work/error")" -eq 1
test ! -e "$work/bad.png"
# An unwritable CSV path fails at once with one message, leaving nothing behind.
if "$polysim" sweep --quick --scenes "$scenes" --out "$work/missing/sweep.csv" 2> "$work/error"; then
  echo "sweep wrote into a missing folder" >&2
  exit 1
fi
grep -q "missing/sweep.csv: cannot write" "$work/error"
test "$(wc -l < "$work/error")" -eq 1
echo "chart pipeline ok"
