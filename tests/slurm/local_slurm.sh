# A single-node Slurm on localhost for the Slurm tests (run_slurm_test.sh,
# run_slurm_mpi_test.sh), sourced by them:
#
#   source tests/slurm/local_slurm.sh
#   require_local_slurm "what the test does"   # exits 77 (skipped) unless root and no Slurm
#                                               # runs; installs slurm-wlm and munge if missing
#   start_local_slurm WORK_DIR PYTHON          # munged, slurmctld, slurmd with a configuration
#                                               # under WORK_DIR (cleared; free ports); exports
#                                               # SLURM_CONF; stops them on exit, also on failure
#
# The caller defines say MESSAGE (progress), fail MESSAGE (exit 1) and skip REASON (exit 77)
# and sets wait_limit (seconds). On failure the daemons' last log lines are printed.

require_local_slurm() {  # WHAT
    ((EUID == 0)) || skip "$1 installs slurm-wlm and starts its own daemons as root"
    if pgrep -x slurmctld >/dev/null || pgrep -x slurmd >/dev/null; then
        skip "a Slurm (slurmctld or slurmd) already runs on this machine; this test starts its own"
    fi
    if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
        || ! command -v munged >/dev/null || ! command -v sbatch >/dev/null; then
        say "installing slurm-wlm and munge"
        timeout 900 apt-get update -qq
        DEBIAN_FRONTEND=noninteractive timeout 900 apt-get install -y -qq \
            -o DPkg::Lock::Timeout=900 slurm-wlm munge >/dev/null
    fi
}

local_slurm_pids=()
local_slurm_work=

stop_local_slurm() {
    local status=$?
    if [[ -n "${SLURM_CONF:-}" && -f "${SLURM_CONF}" ]]; then
        timeout 10 scancel --quiet --user="$(id -un)" 2>/dev/null || true
        timeout 10 scontrol shutdown >/dev/null 2>&1 || true
    fi
    local pid
    for pid in "${local_slurm_pids[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in "${local_slurm_pids[@]}"; do
        for _ in $(seq 50); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.1
        done
        kill -9 "$pid" 2>/dev/null || true
    done
    if [[ $status -ne 0 ]]; then
        say "logs of the daemons (last lines):"
        tail -n 20 "$local_slurm_work"/log/*.log 2>/dev/null || true
    fi
    say "daemons stopped; exit status $status"
}

start_local_slurm() {  # WORK_DIR PYTHON
    local work=$1 python=$2
    local_slurm_work=$work
    rm -rf "$work"
    mkdir -p "$work"/{munge,state,spool,run,log}
    chmod 700 "$work/munge"
    trap stop_local_slurm EXIT

    local ctld_port slurmd_port
    ctld_port=$(local_slurm_free_port "$python")
    slurmd_port=$(local_slurm_free_port "$python")
    while [[ "$slurmd_port" == "$ctld_port" ]]; do slurmd_port=$(local_slurm_free_port "$python"); done

    dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
    chmod 600 "$work/munge/munge.key"
    munged --foreground --force -S "$work/munge/munge.socket" \
        --key-file="$work/munge/munge.key" --log-file="$work/log/munged.log" \
        --pid-file="$work/run/munged.pid" --seed-file="$work/munge/munge.seed" \
        >>"$work/log/munged.log" 2>&1 &
    local_slurm_pids+=($!)

    export SLURM_CONF="$work/slurm.conf"
    cat >"$SLURM_CONF" <<EOF
ClusterName=ddc2dtest
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/run/slurmctld.pid
SlurmdPidFile=$work/run/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
# start array tasks as soon as resources are free (the default delays batch jobs by 3 s)
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
    # A deadline, not a count of polls: munged starts slowly on a loaded machine.
    local munge_deadline=$((SECONDS + wait_limit))
    until [[ -S "$work/munge/munge.socket" ]]; do
        ((SECONDS < munge_deadline)) || fail "munged did not start within ${wait_limit} s"
        sleep 0.1
    done
    slurmctld -D -i -f "$SLURM_CONF" >>"$work/log/slurmctld.stderr" 2>&1 &
    local_slurm_pids+=($!)
    slurmd -D -f "$SLURM_CONF" -N localhost >>"$work/log/slurmd.stderr" 2>&1 &
    local_slurm_pids+=($!)

    local deadline=$((SECONDS + wait_limit))
    until sinfo -h -N -o '%T' 2>/dev/null | grep -E '^(idle|mixed|allocated)' >/dev/null; do
        ((SECONDS < deadline)) || fail "the node did not come up within ${wait_limit} s"
        sleep 0.5
    done
    say "slurmctld and slurmd up on localhost (ports $ctld_port, $slurmd_port)"
}

local_slurm_free_port() {  # PYTHON
    "$1" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0))
print(s.getsockname()[1])'
}
