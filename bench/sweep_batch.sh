#!/usr/bin/env bash
# The sweep's lie members in SIMD lanes (issue 15 part 5): members per
# second of `hamlie sweep --scheme lie` on Henon-Heiles (tol 1e-15, t =
# 1000, random points on invariant curves and in the sea below E = 1/6),
# one thread, with the lanes (HAMLIE_SWEEP_BATCH=1) against one member at
# a time (=0), and the ratio; the two CSVs compared byte for byte.
#
# CPU time of the whole process (user + sys, /usr/bin/time), the best of
# reps; both modes in this one script (the machine is shared: compare
# within a run).  The lanes' code is compiled once into a fresh cache
# first (that run timed on its own: "compile"); the modes then load it.
# "single-native": one at a time with the single recursion's compiled code
# kept in the cache (a long `hamlie run` put it there), which the sweep's
# runs load: the fastest one-at-a-time path.
#
# Usage: bench/sweep_batch.sh [build-dir] [members] [reps] [dt]
#   defaults: build, 128, 3, 1000 (one row per member: max_dH at t = 0
#   and 1000; dt = 1 measures H at 1000 rows each)
#
# Measured 2026-11-28 (commit 3b48e1d; AMD EPYC, 2 cores shared by several
# jobs, load ~19; CPU seconds of the process, the best of 3; /usr/bin/time
# counts 10 ms, so take the larger sweeps):
#   256 members, dt 1000: lanes-4 0.11 s (2327 members/s), single-interp
#     0.49 s (522/s), single-native 0.24 s (1067/s): 4.45x and 2.18x; the
#     first run, compiling the lanes into an empty cache, 0.44 s (582/s)
#   256 members, dt 1 (1000 rows, H at each): lanes-4 1707/s,
#     single-interp 502/s, single-native 985/s: 3.40x and 1.73x
#   128 members, dt 1000: 1829, 388 and 1067/s: 4.71x and 1.71x
#   every CSV the same bytes in the three modes.
#
# Then the fixed-step members (hl_run_fixed_batch's compiled loop in the
# machine's lanes): `--scheme stormer-verlet-kdk --dt 0.01 --t 1000` on the
# same points (10^5 steps each), lanes (=1) against one member at a time
# (=0: hl_run_fixed's own compiled scalar loop, the fastest single path),
# both with their code in the cache (a first run each puts it there).
#   FIXED_MEMBERS (env): default 256.
# Measured 2026-11-28 (commit 55411d2, same machine, load ~4-8, AVX-512: 8
# lanes; CPU seconds, the best of 3): 256 members, lanes 0.06 s (4267
# members/s) against 0.27 s (948/s) one at a time: 4.5x; 1024 members
# (FIXED_MEMBERS=1024; /usr/bin/time's 10 ms matter less) 0.19 s (5389/s)
# against 1.11 s (923/s): 5.8x (10.8 ns a step alone, 1.9 ns a member-step
# in lanes); the CSVs the same bytes.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
M=${2:-128}
reps=${3:-3}
dt=${4:-1000}
out=$build/sweep-batch
mkdir -p "$out"
export HAMLIE_CACHE_DIR=$out/cache
rm -rf "$HAMLIE_CACHE_DIR"
hamlie=$build/hamlie
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
args=(sweep -H "$HH" --random 'x=0,y=-0.25:0.25,px=-0.35:0.35,py=0.2' --count "$M" --seed 5
    --scheme lie --tol 1e-15 --t 1000 --dt "$dt" --threads 1)

cmake --build "$build" -j2 --target hamlie_cli >/dev/null

# cpu MODE CSV: the CPU seconds of one sweep
cpu() {
    HAMLIE_SWEEP_BATCH=$1 /usr/bin/time -f "%U %S" -o "$out/time" "$hamlie" "${args[@]}" \
        --out "$2" >/dev/null 2>&1
    awk '{printf "%.3f\n", $1 + $2}' "$out/time"
}
best() { # best MODE CSV: the least of reps
    local b=
    for _ in $(seq "$reps"); do
        local c
        c=$(cpu "$1" "$2")
        b=$(awk -v a="$b" -v c="$c" 'BEGIN {print (a == "" || c < a) ? c : a}')
    done
    echo "$b"
}
rate() { awk -v m="$M" -v s="$1" 'BEGIN {printf "%.0f", m / s}'; }

echo "# bench/sweep_batch.sh  $(date -u '+%F %T UTC')  commit $(git rev-parse --short HEAD)"
echo "# members $M  dt $dt  reps $reps  load $(cut -d' ' -f1-3 /proc/loadavg)  cpus $(nproc)"
compile=$(cpu 1 "$out/lanes.csv")
lanes=$(best 1 "$out/lanes.csv")
single=$(best 0 "$out/single.csv")
cmp -s "$out/lanes.csv" "$out/single.csv" && same=yes || same=NO
# the single recursion compiled and kept: a long run compiles it
"$hamlie" run -H "$HH" --scheme lie --tol 1e-15 --t 2e5 --dt 2e5 --init 'x=0,y=0.1,px=0.3,py=0.2' \
    >/dev/null 2>&1 || true
native=$(best 0 "$out/native.csv")
cmp -s "$out/lanes.csv" "$out/native.csv" && same_n=yes || same_n=NO
echo "mode,cpu_s,members_per_s"
echo "lanes-4 (first run, compiling),$compile,$(rate "$compile")"
echo "lanes-4,$lanes,$(rate "$lanes")"
echo "single-interp,$single,$(rate "$single")"
echo "single-native,$native,$(rate "$native")"
awk -v a="$single" -v n="$native" -v b="$lanes" \
    'BEGIN {printf "# lanes against single-interp: %.2fx; against single-native: %.2fx\n", a / b, n / b}'
echo "# the same CSV bytes: lanes/single-interp $same, lanes/single-native $same_n"

# ---- fixed-step members ----------------------------------------------------------------
M=${FIXED_MEMBERS:-256}
args=(sweep -H "$HH" --random 'x=0,y=-0.25:0.25,px=-0.35:0.35,py=0.2' --count "$M" --seed 5
    --scheme stormer-verlet-kdk --dt 0.01 --t 1000 --threads 1)
cpu 1 "$out/fixed-lanes.csv" >/dev/null # the codes into the cache
cpu 0 "$out/fixed-single.csv" >/dev/null
flanes=$(best 1 "$out/fixed-lanes.csv")
fsingle=$(best 0 "$out/fixed-single.csv")
cmp -s "$out/fixed-lanes.csv" "$out/fixed-single.csv" && same_f=yes || same_f=NO
echo "# stormer-verlet-kdk, dt 0.01, t 1000, $M members"
echo "mode,cpu_s,members_per_s"
echo "fixed-lanes,$flanes,$(rate "$flanes")"
echo "fixed-single-native,$fsingle,$(rate "$fsingle")"
awk -v a="$fsingle" -v b="$flanes" 'BEGIN {printf "# fixed lanes against single-native: %.2fx\n", a / b}'
echo "# the same CSV bytes: fixed lanes/single $same_f"
