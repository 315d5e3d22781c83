#!/usr/bin/env bash
# The render-farm recipe of docs/guide/turntables-and-farms.md on a real Slurm cluster.
#
#   slurm_turntable.sh PELAGE_BINARY SOURCE_DIR
#
# A single-node cluster on loopback (munged, slurmctld and slurmd with their keys,
# sockets, state and logs in a private temporary folder, on ports no installed Slurm
# uses) runs scenes/farm/turntable.sbatch as an array job and scenes/farm/movie.sbatch
# behind an afterok dependency on it, as the guide submits them. One task is cancelled
# while its frame renders: the movie must then never start. Submitted again, the array
# must skip every complete frame (--resume) and render the missing one, every frame must
# equal, byte for byte, a render of the same frames outside Slurm, and the movie job
# behind the new array must encode every frame. scenes/farm/still_tiles.sbatch renders a
# still as an array of tiles and scenes/farm/merge.sbatch, behind afterok on it, joins
# them: the same file, byte for byte, as the still rendered whole outside Slurm. The
# guide must show all four files verbatim.
#
# Exit 77 (CTest's "skipped") only when Slurm or munge is not installed or the daemons
# cannot start. Every wait is bounded, and the daemons and jobs are stopped on any exit.
set -euo pipefail

[ $# -eq 2 ] || { echo "usage: $0 PELAGE_BINARY SOURCE_DIR" >&2; exit 2; }
pelage=$(realpath "$1")
src=$(realpath "$2")
recipe="$src/scenes/farm"
guide="$src/docs/guide/turntables-and-farms.md"
export PATH="$PATH:/usr/sbin:/sbin"

# The frames and settings of the test render: small, so that the whole run takes a
# minute or two on two cores, yet each frame takes long enough to be cancelled mid-way.
array=0-5
nframes=6
spp=96
res=320x180
# The tiled still: a few bands of a small still, quick next to the turntable.
ntiles=4
still_spp=64
still_res=320x180

fail() {
    echo "FAIL: $*" >&2
    exit 1
}
skip() {
    echo "SKIP: $*" >&2
    exit 77
}

# Nothing may outlive the test's own time limit (CTest's TIMEOUT kills without a trap).
budget_end=$((SECONDS + 480))

# wait_for SECONDS COMMAND...: polls COMMAND until it succeeds; 1 after SECONDS or when
# the test's budget runs out.
wait_for() {
    local deadline=$((SECONDS + $1))
    shift
    [ $deadline -le $budget_end ] || deadline=$budget_end
    until "$@"; do
        [ $SECONDS -lt $deadline ] || return 1
        sleep 0.2
    done
}

# --- What users read is what runs: the guide shows each recipe file verbatim ---------
check_guide_shows_recipe() {
    local f
    for f in turntable.sbatch movie.sbatch still_tiles.sbatch merge.sbatch; do
        python3 - "$guide" "$recipe/$f" <<'EOF' ||
import re, sys
guide, recipe = (open(p, encoding="utf-8").read() for p in sys.argv[1:3])
blocks = re.findall(r"^```[a-z]*\n(.*?)^```$", guide, re.M | re.S)
sys.exit(0 if recipe in blocks else 1)
EOF
            fail "$guide does not show $recipe/$f verbatim in a code block"
    done
}
check_guide_shows_recipe

for tool in munged slurmctld slurmd sbatch squeue sinfo scontrol scancel; do
    command -v "$tool" >/dev/null ||
        skip "$tool is not installed (Debian: apt-get install slurm-wlm munge)"
done
command -v ffprobe >/dev/null || fail "ffprobe is not installed (Debian: ffmpeg)"
scene="$src/scenes/cow_turntable.json"
[ -f "$src/scenes/meshes/cow.off" ] || fail "no sample meshes: run scenes/fetch_meshes.sh"

work=$(mktemp -d "${TMPDIR:-/tmp}/pelage-slurm.XXXXXX")
chmod 711 "$work" # munged needs its socket folder searchable by all
munged_pid="" ctld_pid="" slurmd_pid=""

# --- The cluster ----------------------------------------------------------------------

# Two free TCP ports: the kernel picks them, so an installed Slurm (6817/6818) or a
# parallel run of this test cannot collide.
free_ports() {
    python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))'
}

write_slurm_conf() {
    local user ctld_port slurmd_port cpus
    user=$(id -un)
    read -r ctld_port slurmd_port < <(free_ports)
    cpus=$(nproc)
    mkdir -p "$work/state" "$work/spool"
    # No cgroups, no accounting, no systemd: the plugins that work in any container.
    # MinJobAge keeps finished jobs in scontrol's view for the checks.
    cat >"$work/slurm.conf" <<EOF
ClusterName=pelagetest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$work/munge.socket
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
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=600
KillWait=5
MailProg=/bin/true
NodeName=pelage-node NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=pelage-node Default=YES MaxTime=60 State=UP
EOF
    export SLURM_CONF="$work/slurm.conf"
}

start_munged() {
    dd if=/dev/urandom of="$work/munge.key" bs=1024 count=1 status=none
    chmod 400 "$work/munge.key"
    local force=()
    [ "$(id -u)" -ne 0 ] || force=(--force)
    munged --foreground "${force[@]}" --key-file="$work/munge.key" \
        --socket="$work/munge.socket" --pid-file="$work/munged.pid" \
        --log-file="$work/munged.log" --seed-file="$work/munged.seed" \
        >"$work/munged.out" 2>&1 &
    munged_pid=$!
    wait_for 20 test -S "$work/munge.socket" ||
        skip "munged does not start: $(tail -n 3 "$work/munged.out" "$work/munged.log" \
            2>/dev/null)"
}

node_idle() { [ "$(sinfo -h -n pelage-node -o %T 2>/dev/null)" = idle ]; }

start_slurm() {
    slurmctld -D -c -f "$SLURM_CONF" >"$work/slurmctld.out" 2>&1 &
    ctld_pid=$!
    wait_for 30 scontrol ping >/dev/null 2>&1 ||
        skip "slurmctld does not start: $(tail -n 5 "$work/slurmctld.log" \
            "$work/slurmctld.out" 2>/dev/null)"
    slurmd -D -N pelage-node -f "$SLURM_CONF" >"$work/slurmd.out" 2>&1 &
    slurmd_pid=$!
    wait_for 60 node_idle ||
        skip "slurmd does not register: $(sinfo -N -l 2>&1; tail -n 5 \
            "$work/slurmd.log" "$work/slurmd.out" 2>/dev/null)"
    echo "cluster up: $(sinfo -h -o '%P %a %D %T %N')"
}

# An exited process its parent has not reaped yet (a zombie, state Z) is gone too: a
# cancelled task's shell may die before its pelage, which is then reparented to PID 1,
# and a container's PID 1 need not reap it.
gone() {
    local stat
    kill -0 "$1" 2>/dev/null || return 0
    read -r stat 2>/dev/null <"/proc/$1/stat" || return 0
    stat=${stat##*) } # the fields after "pid (comm) "
    [ "${stat%% *}" = Z ]
}

stopped_or_gone() { [[ "$(state_of "$1")" == [TZ] || "$(state_of "$1")" == gone ]]; }

# A process's state letter (R, S, T, Z, ...), or "gone".
state_of() {
    local stat
    read -r stat 2>/dev/null <"/proc/$1/stat" || {
        echo gone
        return 0
    }
    stat=${stat##*) }
    echo "${stat%% *}"
}

# stop PID: TERM, then KILL after 10 s.
stop() {
    local pid=$1
    [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null || return 0
    kill -TERM "$pid" 2>/dev/null || true
    wait_for 10 gone "$pid" || kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
}

# our_pids NAME: the processes called NAME that belong to this cluster (pelage in its
# jobs, slurmstepd): their environment names its configuration file.
our_pids() {
    local p comm
    for p in /proc/[0-9]*; do
        # `read`, not `cat`: a fork per process made a scan take seconds on a busy
        # machine, longer than the frame it looks for takes to render.
        { read -r comm <"$p/comm"; } 2>/dev/null || continue
        [ "$comm" = "$1" ] || continue
        tr '\0' '\n' 2>/dev/null <"$p/environ" | grep -qxF "SLURM_CONF=$SLURM_CONF" &&
            echo "${p#/proc/}"
    done
    return 0
}
no_step_left() { [ -z "$(our_pids slurmstepd)" ]; }

queue_empty() { [ -z "$(squeue -h -o %i 2>/dev/null)" ]; }

cleanup() {
    local status=$?
    trap - EXIT
    set +e
    if [ -n "$ctld_pid" ]; then
        local ids p
        mapfile -t ids < <(squeue -h -o %A 2>/dev/null)
        [ ${#ids[@]} -eq 0 ] || scancel --full "${ids[@]}" 2>/dev/null
        wait_for 20 queue_empty
        for p in $(our_pids pelage); do kill -KILL "$p" 2>/dev/null; done
    fi
    stop "$slurmd_pid"
    stop "$ctld_pid"
    # A job's slurmstepd finishes on its own once its job is over.
    if [ -n "$slurmd_pid" ] && ! wait_for 15 no_step_left; then
        for p in $(our_pids slurmstepd); do kill -KILL "$p" 2>/dev/null; done
    fi
    stop "$munged_pid"
    if [ $status -ne 0 ] && [ $status -ne 77 ]; then
        local f
        for f in "$work"/slurmctld.log "$work"/slurmd.log "$work"/logs/*; do
            [ -f "$f" ] && { echo "--- $f"; tail -n 20 "$f"; }
        done
    fi
    rm -rf "$work"
    exit $status
}
trap cleanup EXIT
trap 'exit 1' INT TERM

# --- The stages -----------------------------------------------------------------------

# state JOB: the JobState of a job or array task.
state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }

# The pid of the pelage process rendering task TASK of array JOB, if it runs.
task_pid() {
    local p env
    for p in $(our_pids pelage); do
        env=$(tr '\0' '\n' 2>/dev/null <"/proc/$p/environ") || continue
        grep -qxF "SLURM_ARRAY_JOB_ID=$1" <<<"$env" &&
            grep -qxF "SLURM_ARRAY_TASK_ID=$2" <<<"$env" && echo "$p"
    done
    return 0
}

frame() { printf '%s/cow.%04d.exr' "$1" "$2"; }

# Whether task TASK of array JOB renders or has written its frame.
started_or_done() { [ -n "$(task_pid "$1" "$2")" ] || [ -f "$(frame "$OUT" "$2")" ]; }

# Whether JOB (every task of an array) has left the queue.
done_() { [ -z "$(squeue -h -j "$1" -o %i 2>/dev/null)" ]; }

# Whether JOB waits for a dependency that can no longer be met.
never_satisfied() { [ "$(squeue -h -j "$1" -o %r)" = DependencyNeverSatisfied ]; }

# submit FILE SBATCH_OPTION...: the job id of scenes/farm/FILE, submitted from $work.
submit() {
    local file=$1 id
    shift
    id=$(cd "$work" && sbatch --parsable "$@" "$recipe/$file") ||
        fail "sbatch $* $file failed"
    echo "${id%%;*}"
}

# The array of the guide with fewer, smaller frames: two CPUs render two tasks at once.
submit_turntable() { submit turntable.sbatch --array="$array" --cpus-per-task=1; }

# The guide's submission, then a task cancelled while its frame renders: the movie behind
# afterok must never start and is cancelled, and the array submitted again renders only
# the missing frame. Sets $turntable_job.
stage_turntable() {
    export PELAGE="$pelage" SCENE="$scene" OUT="$work/frames" SPP="$spp" RES="$res"
    export MOVIE="$work/cow.mp4"
    mkdir -p "$OUT" "$work/local" "$work/logs"
    local job movie
    job=$(submit_turntable)
    movie=$(submit movie.sbatch --dependency=afterok:"$job")
    echo "turntable array: job $job, frames $array; movie: job $movie"

    # Cancel the first task caught while its pelage renders. Slurm suspends it first
    # (SIGSTOP), so that the frame cannot finish while scancel is on its way; a task
    # that finishes before is left alone and the next one is tried.
    local k pid killed=""
    for ((k = 0; k < nframes; ++k)); do
        wait_for 120 started_or_done "$job" "$k" ||
            fail "task ${job}_$k neither ran nor wrote its frame"
        pid=$(task_pid "$job" "$k")
        [ -n "$pid" ] || continue
        sleep 0.5 # past loading the scene (about 0.3 s), into the frame's samples
        scontrol suspend "${job}_$k" || continue # it has just finished
        # Cancelled only once SIGSTOP has reached it: a cancel that overtakes the
        # suspension left pelage stopped for good (state T, 1 run in 4 here).
        wait_for 10 stopped_or_gone "$pid" || fail "scontrol suspend did not stop pelage"
        scancel "${job}_$k"
        wait_for 30 gone "$pid" ||
            fail "scancel left pelage running (pid $pid, state $(state_of "$pid"))"
        [ -f "$(frame "$OUT" $k)" ] && continue # finished before the signal came
        killed=$k
        break
    done
    [ -n "$killed" ] || fail "every frame finished before it could be cancelled"
    wait_for 240 done_ "$job" || fail "the array does not finish: $(squeue)"
    [ "$(state "${job}_$killed")" = CANCELLED ] ||
        fail "task ${job}_$killed is $(state "${job}_$killed"), not CANCELLED"
    echo "cancelled task ${job}_$killed while it rendered"
    for ((k = 0; k < nframes; ++k)); do
        if [ $k -eq "$killed" ]; then
            [ ! -e "$(frame "$OUT" $k)" ] || fail "the cancelled frame $k was written"
        else
            [ "$(state "${job}_$k")" = COMPLETED ] || fail "task ${job}_$k failed"
            [ -f "$(frame "$OUT" $k)" ] || fail "frame $k is missing"
        fi
    done
    wait_for 30 never_satisfied "$movie" ||
        fail "movie job $movie is $(squeue -h -j "$movie" -o '%T %r'), not held forever"
    [ ! -e "$MOVIE" ] || fail "the movie was written although a frame is missing"
    scancel "$movie"

    # Submitted again: the complete frames are skipped, the cancelled one is rendered.
    job=$(submit_turntable)
    echo "turntable array again: job $job"
    wait_for 240 done_ "$job" || fail "the array does not finish: $(squeue)"
    for ((k = 0; k < nframes; ++k)); do
        [ "$(state "${job}_$k")" = COMPLETED ] ||
            fail "task ${job}_$k is $(state "${job}_$k")"
        local log="$work/logs/turntable-${job}_$k.log" expect
        if [ $k -eq "$killed" ]; then
            expect="1 frame(s) rendered, 0 skipped"
        else
            expect="$(frame "$OUT" $k): complete, skipped"
        fi
        grep -qF "$expect" "$log" || fail "$log does not say \"$expect\""
    done

    # The same frames outside Slurm, in one run with every core: the same bytes.
    "$pelage" render "$SCENE" --frames "$array" --threads "$(nproc)" -q \
        --sampler-seed 1 --spp "$SPP" --res "$RES" -o "$work/local/cow.####.exr"
    for ((k = 0; k < nframes; ++k)); do
        cmp "$(frame "$OUT" $k)" "$(frame "$work/local" $k)" ||
            fail "frame $k rendered by Slurm differs from the local render"
    done
    echo "all $nframes frames identical to a local render"
    turntable_job=$job
}

# The guide's tiled still with fewer tiles: scenes/farm/still_tiles.sbatch as an array of
# $ntiles tasks, each rendering one band of a small still, and scenes/farm/merge.sbatch
# behind afterok on it. The merged EXR must equal, byte for byte, a whole render of the
# same still outside Slurm, and each task's log must show its tile rendered.
stage_tiles() {
    local dir="$work/tiles" still="$work/still.exr" scene="$src/scenes/cow.json"
    mkdir -p "$dir" "$work/local"
    # The still's settings go to these two jobs alone: the movie stage still reads the
    # turntable's OUT.
    local job merge
    job=$(TILES=$ntiles OUT="$dir" SCENE="$scene" SPP=$still_spp RES=$still_res \
        submit still_tiles.sbatch --array=0-$((ntiles - 1)) --cpus-per-task=1)
    merge=$(TILES=$ntiles OUT="$dir" STILL="$still" \
        submit merge.sbatch --dependency=afterok:"$job")
    echo "still tiles: job $job, $ntiles tiles; merge: job $merge"
    wait_for 180 done_ "$merge" || fail "the tiles and merge do not finish: $(squeue)"
    local i log
    for ((i = 0; i < ntiles; ++i)); do
        [ "$(state "${job}_$i")" = COMPLETED ] ||
            fail "tile task ${job}_$i is $(state "${job}_$i")"
        log="$work/logs/still-${job}_$i.log"
        grep -qF "$dir/cow.tile$((i + 1)).exr: $still_res tile $((i + 1))/$ntiles," \
            "$log" || fail "$log does not show tile $((i + 1))/$ntiles rendered"
    done
    [ "$(state "$merge")" = COMPLETED ] || fail "merge job $merge is $(state "$merge")"
    grep -qF "$still: $still_res from $ntiles tiles" "$work/logs/merge-$merge.log" ||
        fail "the merge log does not show $ntiles tiles joined"

    # The same still outside Slurm, whole, with every core; its preview (film.preview)
    # goes to the test's folder, not next to the scene.
    "$pelage" render "$scene" --threads "$(nproc)" -q --sampler-seed 1 --spp "$still_spp" \
        --res "$still_res" --preview "$work/local/still.png" -o "$work/local/still.exr"
    cmp "$still" "$work/local/still.exr" ||
        fail "the still merged from Slurm's tiles differs from a whole local render"
    echo "still merged from $ntiles tiles identical to a whole local render"
}

# The movie job behind afterok on the complete array.
stage_movie() {
    local job
    job=$(submit movie.sbatch --dependency=afterok:"$turntable_job")
    wait_for 120 done_ "$job" || fail "the movie job does not finish: $(squeue)"
    [ "$(state "$job")" = COMPLETED ] || fail "movie job $job is $(state "$job")"
    local count size
    count=$(ffprobe -v error -count_frames -select_streams v:0 \
        -show_entries stream=nb_read_frames -of csv=p=0 "$MOVIE")
    size=$(ffprobe -v error -select_streams v:0 -show_entries stream=width,height \
        -of csv=p=0:s=x "$MOVIE")
    [ "$count" = "$nframes" ] || fail "the movie has $count frames, not $nframes"
    [ "$size" = "$res" ] || fail "the movie is $size, not $res"
    echo "movie: job $job, $count frames of $size"
}

write_slurm_conf
start_munged
start_slurm
stage_turntable
stage_tiles
stage_movie
echo "PASS"
