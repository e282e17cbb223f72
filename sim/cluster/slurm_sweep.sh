#!/usr/bin/env bash
# A planned sweep (`polysim sweep --plan PLAN`) as a Slurm job array: array task k runs
# lines (k-1)*PER+1 .. k*PER of the plan, one after another (PER defaults to 1; raise it
# when the plan has more lines than the cluster's MaxArraySize, 1001 by default).
#
#   sbatch --array=1-$(sim/cluster/slurm_sweep.sh --tasks PLAN [PER]) sim/cluster/slurm_sweep.sh PLAN [PER]
#
# The plan's lines hold absolute paths, so the polysim binary, the scenes and the results
# folder must be on a file system every node sees. A run whose results are already whole
# is kept, not re-run, so a failed array can simply be submitted again. A task fails when
# any of its runs failed; the run's message is in the Slurm output file and beside its
# results (NAME.csv.failed), where `polysim sweep --merge` reports it.
#SBATCH --job-name=polysim-sweep
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --output=polysim-sweep-%A_%a.out
set -euo pipefail

usage() {
  echo "usage: slurm_sweep.sh PLAN [PER] (as a Slurm array task), or slurm_sweep.sh --tasks PLAN [PER]" >&2
  exit 2
}

lines_per_task() {
  local per=${1:-1}
  if ! [[ $per =~ ^[1-9][0-9]*$ ]]; then
    echo "slurm_sweep.sh: PER must be a positive whole number, not \"$per\"" >&2
    exit 2
  fi
  echo "$per"
}

plan_lines() {
  if [ ! -r "$1" ]; then
    echo "slurm_sweep.sh: $1: cannot read the plan" >&2
    exit 2
  fi
  wc -l < "$1"
}

if [ "${1:-}" = "--tasks" ]; then  # how many array tasks the plan needs
  [ $# -ge 2 ] || usage
  lines=$(plan_lines "$2")
  per=$(lines_per_task "${3:-1}")
  echo $(((lines + per - 1) / per))
  exit 0
fi

[ $# -ge 1 ] || usage
plan=$1
lines=$(plan_lines "$plan")
per=$(lines_per_task "${2:-1}")
task=${SLURM_ARRAY_TASK_ID:-}
if ! [[ $task =~ ^[1-9][0-9]*$ ]]; then
  echo "slurm_sweep.sh: SLURM_ARRAY_TASK_ID is \"$task\": submit with sbatch --array=1-N (tasks count from 1)" >&2
  exit 2
fi
first=$(((task - 1) * per + 1))
last=$((task * per < lines ? task * per : lines))
if [ "$first" -gt "$lines" ]; then
  echo "slurm_sweep.sh: task $task is past the plan's $lines lines ($per a task); nothing to run"
  exit 0
fi

failed=0
while IFS= read -r line; do
  bash -c "$line" < /dev/null || failed=$((failed + 1))
done < <(sed -n "${first},${last}p" "$plan")
if [ "$failed" -gt 0 ]; then
  echo "slurm_sweep.sh: task $task: $failed of its runs (plan lines $first..$last) failed" >&2
  exit 1
fi
