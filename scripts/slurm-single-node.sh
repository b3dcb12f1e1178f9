#!/usr/bin/env bash
# A single-node Slurm in a folder of its own, for the fleet's tests and for
# trying `dtg-vib fleet plan --engine slurm` by hand (Debian's slurm-wlm).
#
#   scripts/slurm-single-node.sh start DIR [CTLD_PORT SLURMD_PORT]
#       writes DIR/slurm.conf, starts slurmctld and slurmd, waits until the
#       node is idle; then: SLURM_CONF=DIR/slurm.conf sbatch ...
#   scripts/slurm-single-node.sh stop DIR
#
# No munge: auth/none and cred/none, which Slurm 22.05 still ships, serve
# one machine. Processes are tracked by /proc (no cgroups), so it runs in a
# container. Exit 2 when slurm-wlm is not installed.
set -euo pipefail
cmd=${1:?start or stop}
dir=$(realpath -m "${2:?a folder}")
conf="$dir/slurm.conf"

stop() {
    for d in slurmd slurmctld; do
        if [[ -f "$dir/$d.pid" ]]; then
            kill "$(cat "$dir/$d.pid")" 2>/dev/null || true
        fi
    done
    for d in slurmd slurmctld; do
        for _ in $(seq 50); do
            [[ -f "$dir/$d.pid" ]] && kill -0 "$(cat "$dir/$d.pid")" 2>/dev/null || break
            sleep 0.1
        done
        rm -f "$dir/$d.pid"
    done
}

case "$cmd" in
stop)
    stop
    exit 0
    ;;
start) ;;
*)
    echo "usage: $0 start|stop DIR" >&2
    exit 64
    ;;
esac

for b in slurmctld slurmd sbatch sinfo; do
    if ! command -v "$b" >/dev/null; then
        echo "slurm-single-node: $b not found: install Debian's slurm-wlm (apt-get install slurm-wlm)" >&2
        exit 2
    fi
done
ctld_port=${3:-16817}
slurmd_port=${4:-16818}
host=$(hostname)
cpus=$(nproc)
mem_mib=$(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo)
user=$(id -un)
mkdir -p "$dir/state" "$dir/spool" "$dir/log"
: >"$dir/plugstack.conf"
cat >"$conf" <<CONF
ClusterName=fleet
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/none
CredType=cred/none
SlurmUser=$user
SlurmdUser=$user
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
PlugStackConfig=$dir/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
NodeName=fleet1 NodeHostname=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=fleet Nodes=fleet1 Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$conf"
slurmctld -f "$conf"
slurmd -f "$conf" -N fleet1
for _ in $(seq 100); do
    if sinfo -h -o %t 2>/dev/null | grep -qx idle; then
        echo "$conf"
        exit 0
    fi
    sleep 0.2
done
echo "slurm-single-node: the node did not come up in 20 s; logs in $dir/log" >&2
stop
exit 1
