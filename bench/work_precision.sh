#!/usr/bin/env bash
# Work-precision benchmark (issue 17): final error against the exact
# solution versus integration time, on four systems at t = 1e4 and 1e5, for
# hamlie's Taylor integrator (interpreted, native, Arb at --digits), heyoka
# (only if /opt/heyoka exists: a peer, never a dependency), GSL's rk8pd (if
# libgsl loads) and Boost.Odeint's rkf78 (if its header is found).
#
# Usage: bench/work_precision.sh [build-dir] [reps] [out-dir]
#   defaults: build, 3, build/work-precision
# Environment: WP_T (default 1e4,1e5), WP_TOLS (1e-9,...,1e-16),
#   WP_DIGITS (20,30), WP_REF (40: digits of the Arb reference of
#   Henon-Heiles), WP_FIG (docs/work-precision.png; empty: no figure),
#   HEYOKA_PREFIX (/opt/heyoka).
# Writes out-dir/raw.csv (final states), out-dir/work-precision.csv (errors)
# and out-dir/report.md (references, errors at equal tol, time ratios at
# equal error); the figure to WP_FIG.  Integration alone is timed, in CPU
# time (the best of reps runs); compiling (hamlie native, heyoka's JIT) is
# reported apart.
# The machine may be shared: compare within one run of this script.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-3}
out=${3:-$build/work-precision}
T=${WP_T:-1e4,1e5}
tols=${WP_TOLS:-1e-9,1e-10,1e-11,1e-12,1e-13,1e-14,1e-15,1e-16}
digits=${WP_DIGITS:-20,30}
ref=${WP_REF:-40}
fig=${WP_FIG-docs/work-precision.png}
hy=${HEYOKA_PREFIX:-/opt/heyoka}
py=/usr/bin/python3 # Debian's, with mpmath and matplotlib
mkdir -p "$out"
raw=$out/raw.csv

cmake --build "$build" -j2 --target bench-work_precision >/dev/null
{
    echo "# bench/work_precision.sh  $(date -u '+%F %T UTC')  commit $(git rev-parse --short HEAD)"
    echo "# reps $reps  T $T  tols $tols  digits $digits  load $(cut -d' ' -f1-3 /proc/loadavg)  cpus $(nproc)"
} >"$raw"

# the Arb reference where there is no closed form, and one at fewer digits
# to say how far it is from the truth
"$build/bench-work_precision" sys=2 T="$T" methods=none ref="$ref" >>"$raw"
"$build/bench-work_precision" sys=2 T="$T" methods=none ref=$((ref - 8)) >>"$raw"

"$build/bench-work_precision" reps="$reps" T="$T" tols="$tols" digits="$digits" >>"$raw"

if [ -f /usr/include/boost/numeric/odeint.hpp ]; then
    g++ -O2 -DNDEBUG -std=c++17 bench/work_precision_boost.cpp -o "$out/work_precision_boost"
    "$out/work_precision_boost" "$reps" "$T" "$tols" >>"$raw"
else
    echo "work_precision: Boost.Odeint not found, rkf78 skipped" >&2
fi

if [ -f "$hy/lib/libheyoka.so" ]; then
    g++ -O2 -DNDEBUG -std=c++20 -I"$hy/include" bench/work_precision_heyoka.cpp \
        -o "$out/work_precision_heyoka" -L"$hy/lib" -Wl,-rpath,"$hy/lib" \
        -lheyoka -lfmt -lboost_serialization 2>/dev/null
    "$out/work_precision_heyoka" "$reps" "$T" "$tols" >>"$raw"
else
    echo "work_precision: heyoka not found in $hy, skipped" >&2
fi

$py bench/work_precision.py "$raw" --csv "$out/work-precision.csv" ${fig:+--png "$fig"} \
    | tee "$out/report.md"
