#!/usr/bin/env bash
# The planned quick sweep run as a Slurm job array on a one-node Slurm that this test sets
# up and tears down (Debian's slurmctld, slurmd, slurm-client and munge; as root, in a
# temporary folder, on ports 16817-16818, addressed as 127.0.0.1): the array's results
# merge into the serial sweep's figures. Exits 77 (skipped) when not root.
# Usage: slurm_sweep_test.sh POLYSIM SCENES_DIR SLURM_SCRIPT
set -euo pipefail
polysim=$1 scenes=$2 slurm=$3
if [ "$(id -u)" -ne 0 ]; then
  echo "slurm_sweep_test: needs root to start munged, slurmctld and slurmd; skipped"
  exit 77
fi
work=$(mktemp -d)
stop_daemons() {
  for pid in "$work"/slurmd.pid "$work"/slurmctld.pid "$work"/munge/munged.pid; do
    [ -s "$pid" ] && kill "$(cat "$pid")" 2> /dev/null || true
  done
  sleep 1
  rm -rf "$work"
}
trap stop_daemons EXIT
fail() {
  echo "slurm_sweep_test: $*" >&2
  tail -n 5 "$work"/log/*.log >&2 || true
  exit 1
}
cd "$work"
mkdir -p state spool log munge
chmod 700 munge
node=$(hostname -s)
cat > slurm.conf << CONF
ClusterName=polysim-test
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldPort=16817
SlurmdPort=16818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
head -c 1024 /dev/urandom > munge/munge.key
chmod 600 munge/munge.key
munged --force --socket="$work/munge/munge.socket" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/log/munged.log" --seed-file="$work/munge/seed"
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
  sinfo -h -o %t 2> /dev/null | grep -q idle && break
  sleep 1
done
sinfo -h -o %t | grep -q idle || fail "the one-node Slurm did not come up"

"$polysim" sweep --quick --scenes "$scenes" --out serial.csv
"$polysim" sweep --quick --scenes "$scenes" --plan plan.txt --results runs
tasks=$("$slurm" --tasks plan.txt 5)
timeout 600 sbatch --wait --quiet --array="1-$tasks" --output="$work/log/task-%a.out" "$slurm" plan.txt 5 ||
  fail "the array job failed: $(cat log/task-*.out)"
test "$(ls log/task-*.out | wc -l)" -eq "$tasks" || fail "not $tasks array tasks ran"
"$polysim" sweep --quick --merge runs --out merged.csv
diff <(cut -d, -f1-6,9-13 serial.csv) <(cut -d, -f1-6,9-13 merged.csv) || fail "the array's figures differ from the serial sweep's"
echo "slurm sweep ok: $tasks array tasks"
