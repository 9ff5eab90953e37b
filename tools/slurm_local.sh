#!/bin/bash
# A one-machine SLURM for testing the batch recipe of docs/cluster.md (issue 46): controller and
# compute node on this host, all its CPUs in one partition `debug`, munge for authentication.
#
#   tools/slurm_local.sh start    start munged, slurmctld and slurmd; wait until the node is idle
#   tools/slurm_local.sh stop     stop what start started and remove its directory
#   tools/slurm_local.sh status   the daemons and sinfo
#   tools/slurm_local.sh env      the line that points SLURM's commands at this cluster
#
# Needs root and Debian's slurm-wlm and munge (`make slurm` installs them).  Everything SLURM keeps
# (slurm.conf, state, spool, logs, the job completion log) is in $SPHFSI_SLURM_DIR
# (/tmp/sphfsi-slurm); /etc/slurm is not touched, so give the commands SLURM_CONF=DIR/slurm.conf
# (`eval "$(tools/slurm_local.sh env)"`).  A munged that already answers is used as it is.
# No cgroups (a container): proctrack/linuxproc and task/none.  No slurmdbd: sacct has no data;
# the exit codes are in `scontrol show job` (kept MinJobAge = 1 h) and the completion log
# DIR/jobcomp.txt (jobcomp/filetxt).
set -u
DIR=${SPHFSI_SLURM_DIR:-/tmp/sphfsi-slurm}
CONF=$DIR/slurm.conf
export SLURM_CONF=$CONF
NODE=$(hostname -s)

say() { echo "slurm_local: $*"; }
die() { echo "slurm_local: error: $*" >&2; exit 1; }

munge_ok() { munge -n 2>/dev/null | unmunge >/dev/null 2>&1; }
pid_alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }
ctld_ok() { scontrol ping 2>/dev/null | grep -q "is UP"; }
node_state() { sinfo -h -N -n "$NODE" -o %t 2>/dev/null | head -1; }

write_conf() {
    # the node as slurmd finds it (CPUs, sockets, cores, threads, memory)
    local hw
    hw=$(slurmd -C 2>/dev/null | head -1 | sed 's/^NodeName=[^ ]* //') || true
    [ -n "$hw" ] || die "slurmd -C printed nothing"
    cat > "$CONF.tmp" <<EOF
# written by tools/slurm_local.sh: one host is controller and compute node
ClusterName=sphfsi
SlurmctldHost=$NODE(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
MpiDefault=none
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$DIR/jobcomp.txt
MinJobAge=3600
KillWait=30
InactiveLimit=0
NodeName=$NODE NodeAddr=127.0.0.1 $hw State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
    mv "$CONF.tmp" "$CONF"
}

start() {
    [ "$(id -u)" = 0 ] || die "must run as root"
    for c in munged slurmctld slurmd sinfo scontrol; do
        command -v $c >/dev/null || die "$c not found (apt-get install slurm-wlm munge)"
    done
    mkdir -p "$DIR/state" "$DIR/spool" "$DIR/log"
    if ! munge_ok; then
        [ -s /etc/munge/munge.key ] || {
            say "creating /etc/munge/munge.key"
            mkdir -p /etc/munge
            dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none
            chown munge:munge /etc/munge/munge.key 2>/dev/null; chmod 400 /etc/munge/munge.key
        }
        mkdir -p /run/munge /var/log/munge /var/lib/munge
        chown munge:munge /run/munge /var/log/munge /var/lib/munge 2>/dev/null
        if id munge >/dev/null 2>&1; then runuser -u munge -- munged || die "munged did not start"
        else munged --force || die "munged did not start"; fi
        touch "$DIR/munged.ours"
        for _ in $(seq 50); do munge_ok && break; sleep 0.1; done
        munge_ok || die "munge does not answer"
        say "munged started"
    fi
    [ -f "$CONF" ] || write_conf
    if ! pid_alive "$DIR/slurmctld.pid"; then
        slurmctld -f "$CONF" || die "slurmctld did not start: $DIR/log/slurmctld.log"
        say "slurmctld started"
    fi
    for _ in $(seq 100); do ctld_ok && break; sleep 0.2; done
    ctld_ok || die "slurmctld does not answer: $DIR/log/slurmctld.log"
    if ! pid_alive "$DIR/slurmd.pid"; then
        slurmd -f "$CONF" || die "slurmd did not start: $DIR/log/slurmd.log"
        say "slurmd started"
    fi
    local st=
    for _ in $(seq 150); do
        st=$(node_state)
        case $st in idle|mix|alloc) break ;; esac
        sleep 0.2
    done
    case $st in
        idle|mix|alloc) ;;
        *) scontrol update nodename="$NODE" state=resume >/dev/null 2>&1; sleep 1; st=$(node_state) ;;
    esac
    case $st in
        idle|mix|alloc) say "node $NODE is $st; $(env_line)" ;;
        *) die "node $NODE is '${st:-?}', not idle: $DIR/log/slurmd.log" ;;
    esac
}

stop() {
    local f p jobs
    # this cluster's jobs first: cancelled, with the time to stop that KillWait gives them
    if [ -f "$CONF" ] && ctld_ok; then
        jobs=$(squeue -h -o %i 2>/dev/null)
        if [ -n "$jobs" ]; then
            scancel $jobs 2>/dev/null
            for _ in $(seq 200); do [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break; sleep 0.2; done
            say "jobs cancelled: $(echo $jobs)"
        fi
    fi
    for f in slurmd slurmctld; do
        if pid_alive "$DIR/$f.pid"; then
            p=$(cat "$DIR/$f.pid")
            kill "$p"
            for _ in $(seq 100); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
            kill -0 "$p" 2>/dev/null && kill -9 "$p"
            say "$f stopped"
        fi
    done
    if [ -f "$DIR/munged.ours" ]; then
        munged --stop >/dev/null 2>&1 || { p=$(cat /run/munge/munged.pid 2>/dev/null) && kill "$p"; }
        say "munged stopped"
    fi
    rm -rf "$DIR"
}

status() {
    local f
    for f in slurmctld slurmd; do
        if pid_alive "$DIR/$f.pid"; then echo "$f: running (pid $(cat "$DIR/$f.pid"))"; else echo "$f: not running"; fi
    done
    if munge_ok; then echo "munge: answers"; else echo "munge: does not answer"; fi
    [ -f "$CONF" ] && sinfo 2>&1
}

env_line() { echo "export SLURM_CONF=$CONF"; }

case ${1:-} in
    start) start ;;
    stop) stop ;;
    status) status ;;
    env) env_line ;;
    *) echo "usage: $0 start|stop|status|env" >&2; exit 2 ;;
esac
