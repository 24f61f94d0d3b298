#!/usr/bin/env bash
# The Slurm job array of examples/slurm on a real single-node Slurm (Debian's
# slurm-wlm and munge), started here in a folder of its own on free ports and
# stopped at the end: four simulated campaigns, one per array task, then the
# summary job; its summary.csv must be the one `beamid batch` writes on this
# machine for the same four (every column but the wall times).
# slurmd starts jobs as their users and needs root: as another user the test
# is skipped (exit 77).
# Usage: check_slurm_array.sh BUILD_FOLDER SOURCE_FOLDER
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
beamid="$build/beamid"
for program in munged slurmctld slurmd sbatch squeue sinfo; do
  command -v "$program" >/dev/null || { echo "no $program: install slurm-wlm and munge (scripts/install-deps.sh)"; exit 1; }
done
if [ "$(id -u)" -ne 0 ]; then echo "skipped: slurmd runs jobs as their users and needs root"; exit 77; fi

work=$(mktemp -d)
stop() {
  for pid_file in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munge/munged.pid"; do
    [ -s "$pid_file" ] && kill "$(cat "$pid_file")" 2>/dev/null || true
  done
  sleep 1
  rm -rf "$work"
}
trap stop EXIT

# munge: a key of this test's own, its socket in the folder.
mkdir -m 700 "$work/munge"
head -c 1024 /dev/urandom >"$work/munge/munge.key"
chmod 600 "$work/munge/munge.key"
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/seed"

read -r controller_port node_port < <(python3 -c '
import socket
sockets = [socket.socket() for _ in range(2)]
for s in sockets: s.bind(("127.0.0.1", 0))
print(*[s.getsockname()[1] for s in sockets])')
mkdir "$work/state" "$work/spool"
export SLURM_CONF="$work/slurm.conf"
cat >"$SLURM_CONF" <<CONF
ClusterName=beamidtest
SlurmctldHost=localhost
SlurmUser=root
SlurmctldPort=$controller_port
SlurmdPort=$node_port
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
ReturnToService=2
NodeName=localhost CPUs=2 State=UNKNOWN
PartitionName=beamid Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
  sinfo -h -o %T 2>/dev/null | grep -q idle && break
  sleep 0.5
done
sinfo -h -o %T | grep -q idle || { echo "the node never became idle:"; tail -20 "$work/slurmd.log" "$work/slurmctld.log"; exit 1; }

# Four small campaigns from the simulator, one noise seed each.
python3 - "$source/examples/scenarios/paper_base.json" "$work" <<'PY'
import json, sys
scenario = json.load(open(sys.argv[1]))
scenario["levels"] = [
    {"label": "low", "force_amplitude_N": 1.0, "frequencies_Hz": {"start": 53.0, "stop": 55.0, "step": 0.5}},
    {"label": "high", "force_amplitude_N": 4.0, "frequencies_Hz": {"start": 53.0, "stop": 55.0, "step": 0.5}}]
for i in range(4):
    scenario["noise"]["seed"] = 70 + i
    scenario["name"] = "specimen %d" % i
    json.dump(scenario, open("%s/scenario%d.json" % (sys.argv[2], i), "w"))
PY
for i in 0 1 2 3; do
  "$beamid" -q simulate "$work/scenario$i.json" -o "$work/campaigns/specimen_$i"
  echo "$work/campaigns/specimen_$i" >>"$work/campaigns.txt"
done

"$beamid" -q batch --fit acc1,acc2 --validate acc3 -j 2 -o "$work/local" $(cat "$work/campaigns.txt")

submitted=$(BEAMID="$beamid" bash "$source/examples/slurm/submit.sh" "$work/campaigns.txt" "$work/cluster" \
  --fit acc1,acc2 --validate acc3)
echo "$submitted"
collect=$(echo "$submitted" | sed -n 's/.*summary job \([0-9]*\).*/\1/p')
for _ in $(seq 600); do
  [ -z "$(squeue -h -j "$collect" 2>/dev/null)" ] && break
  sleep 0.5
done
[ -z "$(squeue -h -j "$collect" 2>/dev/null)" ] || { echo "the summary job $collect did not end in 5 min"; squeue; exit 1; }

python3 - "$work/local/summary.csv" "$work/cluster/summary.csv" <<'PY'
import csv, sys
local, cluster = ([row for row in csv.DictReader(open(path))] for path in sys.argv[1:3])
if len(local) != 4 or [r["status"] for r in local] != ["fitted"] * 4:
    sys.exit("the local batch did not fit the four campaigns: %s" % [r["status"] for r in local])
for row in local + cluster:
    row.pop("seconds")
if local != cluster:
    sys.exit("the job array's summary differs from the local batch's:\n%s\n%s" % (local, cluster))
PY
for i in 0 1 2 3; do
  [ -s "$work/cluster/specimen_$i/report.html" ] || { echo "no report for specimen_$i"; ls -R "$work/cluster"; exit 1; }
done
grep -q 'href="specimen_3/report.html"' "$work/cluster/index.html" || { echo "index.html links no report"; exit 1; }
echo "Slurm job array over 4 campaigns: the summary equals the local batch's"
