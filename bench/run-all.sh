#!/usr/bin/env bash
# The benchmarks issue 14's acceptance names, in one run, so that figures
# before and after a change come from the same machine and the same script.
# Usage: bench/run-all.sh [build-dir] [reps]   (default: build, 3)
#   bench/run-lie.sh        symbolic Lie series vs SymPy
#   bench/run-errors.sh     error fields v_k vs SymPy (+ the `errors` command)
#   bench/run-exact.sh      exact pendulum step vs one Taylor step
#   bench-taylor_flow       Taylor integrator vs GSL rk8pd (if libgsl loads): the
#                           fields written by hand, interpreted; then from H and
#                           compiled to machine code (the README's figures)
#   bench-run_fixed         fixed-step runs vs hand-written C, and with jit
#   bench-tape_jit          tape interpreter vs gccjit vs hand-written C
#   bench-lie_series        the hamlie half of run-lie.sh alone
#   bench-errors_analysis   the hamlie half of run-errors.sh alone
# The machine may be shared: compare the ratios against the peer measured in
# the same process, not the absolute times of two runs.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-3}
cmake --build "$build" -j2 --target hamlie_cli bench-taylor_flow bench-run_fixed \
    bench-tape_jit bench-lie_series bench-errors_analysis bench-exact_step >/dev/null

echo "# bench/run-all.sh  $(date -u '+%F %T UTC')  commit $(git rev-parse --short HEAD)"
echo "# build: $build ($(grep -m1 '^CMAKE_BUILD_TYPE' "$build/CMakeCache.txt" | cut -d= -f2))" \
     " reps: $reps  load: $(cut -d' ' -f1-3 /proc/loadavg)  cpus: $(nproc)"

section() {
    echo
    echo "## $*"
    local t0 t1
    t0=$(date +%s.%N)
    "$@"
    t1=$(date +%s.%N)
    echo "# wall $(echo "$t1 - $t0" | bc) s"
}

section bench/run-lie.sh "$build"
section bench/run-errors.sh "$build"
section bench/run-exact.sh "$build"
section "$build/bench-taylor_flow" "$reps"
section "$build/bench-taylor_flow" "$reps" gsl -1 fromH native
section "$build/bench-run_fixed" "$reps"
section "$build/bench-run_fixed" "$reps" jit
section "$build/bench-tape_jit" "$reps"
section "$build/bench-lie_series" "$reps"
section "$build/bench-errors_analysis" "$reps"
