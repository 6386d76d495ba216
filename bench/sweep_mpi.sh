#!/usr/bin/env bash
# What MPI costs a sweep on one machine (issue 15: "MPI adds no more than a
# few per cent over threads"): the same sweep with --threads 2, and under
# `mpirun -np 2 --threads 1` (rank 0 computes too), and `-np 3` with rank 0
# only serving (HAMLIE_MPI_MASTER_IDLE=1: what the master's polling costs).
# Runs alternate, so a shared machine's load falls on all alike; the
# median of REPS wall and CPU (user + sys of all processes) seconds each.
# Then rank 0's intake: bench-sweep_mpi_rate (rows per CPU second).
# Usage: bench/sweep_mpi.sh [build-dir] [reps]    (default: build, 3)
#   SWEEP_ARGS='...' to change the sweep (default: 10^4 members of the
#   pendulum, Stormer-Verlet and RK4, t = 1000); RUNS='threads2 mpi2' to time
#   only some of threads1 threads2 mpi2 mpi3idle; NO_BUILD=1 to time the
#   binaries as they are (while another build dir is worked on)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-3}
[ -n "${NO_BUILD:-}" ] ||
    cmake --build "$build" -j2 --target hamlie_cli hamlie_mpi_plugin bench-sweep_mpi_rate >/dev/null
runs=${RUNS:-threads1 threads2 mpi2 mpi3idle}
hamlie=$build/hamlie
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export HAMLIE_CACHE_DIR=${HAMLIE_CACHE_DIR:-$build/bench-cache}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck disable=SC2206
args=(${SWEEP_ARGS:-sweep -H 'p^2/2-cos(q)' --grid q=-3:3:100,p=-2:2:50 --scheme stormer-verlet-kdk,rk4 --dt 0.1 --t 1e3 --quiet})

echo "# bench/sweep_mpi.sh  $(date -u '+%F %T UTC')  commit $(git rev-parse --short HEAD)"
echo "# reps: $reps  load: $(cut -d' ' -f1-3 /proc/loadavg)  cpus: $(nproc)  $(mpirun --version | head -1)"
echo "# hamlie ${args[*]}"

# warm the cache of compiled code: no run pays for a compilation
"$hamlie" "${args[@]}" --threads 2 --out "$tmp/warm.csv" >/dev/null

# one timed run: "wall cpu" on stdout; the file compared with the first
timed() {
    local name=$1
    shift
    /usr/bin/time -f "%e %U %S" -o "$tmp/time" "$@" --out "$tmp/$name.csv" >/dev/null 2>"$tmp/err" ||
        { echo "failed: $*" >&2; cat "$tmp/err" >&2; exit 1; }
    cmp -s "$tmp/$name.csv" "$tmp/warm.csv" || { echo "$name: another file" >&2; exit 1; }
    awk '{printf "%s %.2f\n", $1, $2 + $3}' "$tmp/time" >>"$tmp/$name.times"
}

run_one() {
    case $1 in
        threads1) timed threads1 "$hamlie" "${args[@]}" --threads 1 ;;
        threads2) timed threads2 "$hamlie" "${args[@]}" --threads 2 ;;
        mpi2) timed mpi2 mpirun -np 2 "$hamlie" "${args[@]}" --threads 1 ;;
        mpi3idle) timed mpi3idle env HAMLIE_MPI_MASTER_IDLE=1 mpirun -np 3 -x HAMLIE_MPI_MASTER_IDLE \
            "$hamlie" "${args[@]}" --threads 1 ;;
    esac
}
for _ in $(seq "$reps"); do
    for name in $runs; do run_one "$name"; done
done

median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
best() { sort -g | head -1; }
printf "%-44s %9s %9s %9s %9s\n" "run (the same file each time)" "wall s" "CPU s" "best wall" "best CPU"
for name in $runs; do
    w=$(cut -d' ' -f1 "$tmp/$name.times" | median)
    c=$(cut -d' ' -f2 "$tmp/$name.times" | median)
    bw=$(cut -d' ' -f1 "$tmp/$name.times" | best)
    bc=$(cut -d' ' -f2 "$tmp/$name.times" | best)
    case $name in
        threads1) label="--threads 1" ;;
        threads2) label="--threads 2" ;;
        mpi2) label="mpirun -np 2 --threads 1" ;;
        mpi3idle) label="mpirun -np 3 --threads 1, rank 0 serving only" ;;
    esac
    printf "%-44s %9s %9s %9s %9s\n" "$label" "$w" "$c" "$bw" "$bc"
    eval "${name}_w=$w ${name}_c=$c ${name}_bw=$bw ${name}_bc=$bc"
done
if [ -n "${threads2_w:-}" ] && [ -n "${mpi2_w:-}" ]; then
    awk -v tw="$threads2_w" -v mw="$mpi2_w" -v tc="$threads2_c" -v mc="$mpi2_c" \
        -v tbw="$threads2_bw" -v mbw="$mpi2_bw" -v tbc="$threads2_bc" -v mbc="$mpi2_bc" 'BEGIN {
        printf "mpirun -np 2 over --threads 2: median wall %+.1f%%, CPU %+.1f%%; best wall %+.1f%%, CPU %+.1f%%\n",
               100 * (mw / tw - 1), 100 * (mc / tc - 1), 100 * (mbw / tbw - 1), 100 * (mbc / tbc - 1) }'
fi

[ -n "${NO_INTAKE:-}" ] && exit 0
echo
echo "## rank 0's intake (instant members, 25 columns; rank 0 only serving)"
for np in 2 3; do
    mpirun -np $np "$build/bench-sweep_mpi_rate" "$build/hamlie-mpi.so" 25 300000
    mpirun -np $np "$build/bench-sweep_mpi_rate" "$build/hamlie-mpi.so" 25 300000 "$tmp/journal"
done
