#!/bin/bash
# Start-up cost of hamlie commands, whole process (issue 17: `hamlie
# --version` <= 5 ms; what a command does not use it does not load).
#
# usage: bash bench/startup.sh [path/to/hamlie [runs]]   (default build/hamlie, 30)
#
# For each command: the median and the minimum wall time of `runs` runs
# (bash's $EPOCHREALTIME around the command: no extra process is timed), the
# CPU time (perf stat's task-clock, mean, where perf works), and the median
# as a multiple of /bin/true's.  On a loaded machine the wall times wander;
# the minimum and the task-clock wander least.  The compiled run gets a
# fifth of the runs (it takes seconds).  HAMLIE_BEFORE=path/to/old/hamlie
# adds the same rows for another build, measured in the same loop.
# STARTUP_INSTR=1 first counts instructions (valgrind's callgrind) of the
# quick ones: the figure that load on the machine does not move.
set -u
HAMLIE=${1:-build/hamlie}
RUNS=${2:-30}
[ -x "$HAMLIE" ] || { echo "startup.sh: no executable '$HAMLIE'" >&2; exit 2; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
OSC='(p^2+x^2)/2'
"$HAMLIE" run -H "$OSC" --scheme verlet --dt 0.01 --t 10 --init x=1,p=0 --out "$tmp/run.csv" \
    >/dev/null || { echo "startup.sh: cannot make the CSV to plot" >&2; exit 2; }

have_perf=0
perf stat -e task-clock /bin/true >/dev/null 2>&1 && have_perf=1

# wall_ms N cmd...: "median min" of N runs, in ms
wall_ms() {
    local n=$1 i t0 t1
    shift
    for ((i = 0; i < n; i++)); do
        t0=$EPOCHREALTIME
        "$@" >/dev/null 2>&1
        t1=$EPOCHREALTIME
        echo "$t0 $t1"
    done | awk '{ printf "%.4f\n", ($2 - $1) * 1000 }' | sort -g | awk '{ d[NR] = $1 } END {
        m = (NR % 2) ? d[(NR + 1) / 2] : (d[NR / 2] + d[NR / 2 + 1]) / 2
        printf "%.2f %.2f\n", m, d[1] }'
}

# cpu_ms N cmd...: perf's task-clock (ms, mean of N runs), or "-"
cpu_ms() {
    local n=$1
    shift
    if [ $have_perf = 0 ]; then echo "-"; return; fi
    perf stat -r "$n" -x ';' -e task-clock "$@" 2>&1 >/dev/null |
        awk -F';' '$3 ~ /task-clock/ { printf "%.2f\n", $1; found = 1 } END { if (!found) print "-" }'
}

true_ms=
row() { # row NAME N cmd...
    local name=$1 n=$2 w cpu
    shift 2
    w=$(wall_ms "$n" "$@")
    cpu=$(cpu_ms "$n" "$@")
    read -r med min <<<"$w"
    [ -z "$true_ms" ] && true_ms=$med
    printf "%-34s %9s %9s %9s %8s\n" "$name" "$med" "$min" "$cpu" \
        "$(awk -v a="$med" -v b="$true_ms" 'BEGIN { printf "%.1fx", a / b }')"
}

commands() { # commands LABEL HAMLIE
    local tag=$1 h=$2
    row "$tag --version" "$RUNS" "$h" --version
    row "$tag --help" "$RUNS" "$h" --help
    row "$tag generator (oscillator)" "$RUNS" "$h" generator -H 'p^2/2+q^2/2'
    row "$tag lie HH --order 12" "$RUNS" "$h" lie -H "$HH" --order 12
    row "$tag plot (one CSV, png)" "$RUNS" "$h" plot "$tmp/run.csv" --out "$tmp/figs"
    row "$tag run verlet 1e6 steps (jit)" $(((RUNS + 4) / 5)) "$h" run -H "$OSC" --scheme verlet \
        --dt 0.001 --t 1000 --init x=1,p=0 --no-reference --json
}

# instr cmd...: instructions executed, loader included (callgrind): the one
# figure here that load on the machine does not move
instr() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null |
        awk '/Collected/ { print $NF }'
}
if [ "${STARTUP_INSTR:-0}" = 1 ] && command -v valgrind >/dev/null; then
    echo "instructions (callgrind, STARTUP_INSTR=1):"
    for h in /bin/true "$HAMLIE" ${HAMLIE_BEFORE:-}; do
        if [ "$h" = /bin/true ]; then printf "  %-50s %12s\n" /bin/true "$(instr /bin/true)"; continue; fi
        printf "  %-50s %12s\n" "$h --version" "$(instr "$h" --version)"
        printf "  %-50s %12s\n" "$h generator" "$(instr "$h" generator -H 'p^2/2+q^2/2')"
    done
fi

echo "runs: $RUNS; times in ms; x: median / /bin/true's median"
printf "%-34s %9s %9s %9s %8s\n" "command" "median" "min" "cpu" "x true"
row "/bin/true" "$RUNS" /bin/true
commands hamlie "$HAMLIE"
if [ -n "${HAMLIE_BEFORE:-}" ]; then
    commands before "$HAMLIE_BEFORE"
fi
