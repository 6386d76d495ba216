#!/usr/bin/env bash
# Batch-mode benchmark (issue 15 part 5): members per second of the Taylor
# integrator on an ensemble (Henon-Heiles, tol 1e-15, t = 1000, 64 members
# from invariant curves to the chaotic sea), hamlie one member at a time
# (interpreted, compiled) against its batch mode (2, 4, 8 SIMD lanes), and
# heyoka 7.2.1's scalar and batch integrators on the same members (only if
# $HEYOKA_PREFIX, default /opt/heyoka, exists: a peer, never a dependency;
# built here with Debian's g++ 12 at -O2 against the prebuilt libheyoka of
# /work/shared/peers/heyoka, LLVM JIT inside it).
#
# Usage: bench/taylor_batch.sh [build-dir] [reps] [members] [T]
#   defaults: build, 5, 64, 1000
# Then the compilation itself (cache off, wall clock) and, with
# TB_CALLGRIND=1, instruction counts per mode (valgrind --tool=callgrind,
# 16 members to t = 100: the machine is shared and wall times are noisy).
# CPU time of the integration alone, the best of reps; compare within one
# run of this script.
#
# Measured 2026-11-28 (commit 2b4fe38; AMD EPYC with AVX-512, 2 cores shared
# by several jobs, load ~16; members per second, 64 members, the best of 5):
#   hamlie  single-interp 415   single-native 1069   batch-2 2067
#           batch-4 2671   batch-8 2838   (every member bit for bit the
#           single run's; 177655 steps in all)
#   heyoka  scalar 1153   batch-2 1793   batch-4 2678   batch-8 3341
#           (177610 steps)
#   compiling, cache off, wall: single 1.3 s, 4 lanes 1.1 s, 8 lanes 1.5 s
#   (loaded machine; a cached entry loads in well under 1 ms)
#   callgrind, 16 members to t = 100 (4436 steps both), instructions a
#   member-step inside the integration calls: hamlie single-interp 8770,
#   single-native 3063, batch-2 2166, batch-4 1747, batch-8 2262; heyoka
#   scalar 2484, batch-4 1066, batch-8 1066 (valgrind's CPU has no
#   AVX-512: 8 lanes are two AVX2 vectors there).  Of hamlie's batch-4
#   step some 600 are the recursion and the rest the per-lane step logic
#   (norms, logs, exp, the time), which heyoka runs in SIMD too.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-5}
B=${3:-64}
T=${4:-1000}
hy=${HEYOKA_PREFIX:-/opt/heyoka}
out=$build/taylor-batch
mkdir -p "$out"
export HAMLIE_CACHE_DIR=${HAMLIE_CACHE_DIR:-$out/cache}

cmake --build "$build" -j2 --target bench-taylor_batch >/dev/null
echo "# bench/taylor_batch.sh  $(date -u '+%F %T UTC')  commit $(git rev-parse --short HEAD)"
echo "# reps $reps  members $B  T $T  load $(cut -d' ' -f1-3 /proc/loadavg)  cpus $(nproc)"
"$build/bench-taylor_batch" "$B" "$T" "$reps"
if [ -f "$hy/lib/libheyoka.so" ]; then
    g++ -O2 -DNDEBUG -std=c++20 -I"$hy/include" bench/taylor_batch_heyoka.cpp \
        -o "$out/taylor_batch_heyoka" -L"$hy/lib" -Wl,-rpath,"$hy/lib" \
        -lheyoka -lfmt -lboost_serialization 2>/dev/null
    "$out/taylor_batch_heyoka" "$B" "$T" "$reps" | tail -n +1
else
    echo "# heyoka not found at $hy: bash /work/shared/peers/heyoka/install.sh" >&2
fi

echo "# compile (HAMLIE_CACHE=off, in process, wall ms): mode setup_ms"
for m in single-native batch-4 batch-8; do
    HAMLIE_CACHE=off "$build/bench-taylor_batch" 4 1 1 "$m" | awk -F, -v m="$m" '$1 == m {print "#", m, $8}'
done

if [ "${TB_CALLGRIND:-0}" = 1 ] && command -v valgrind >/dev/null; then
    # instructions inside the integration calls alone (--toggle-collect),
    # 16 members to t = 100; the cache is filled under valgrind first: its
    # CPU has no AVX-512, so the key (-march) differs from the machine's
    echo "# callgrind: instructions in hl_flow_evolve / hl_flow_batch_evolve / heyoka's propagate_until_impl, 16 members to t = 100"
    cg() { valgrind --tool=callgrind --callgrind-out-file=/dev/null --toggle-collect="$1" "${@:2}" 2>&1 >/dev/null |
        awk '/refs:/ {gsub(",", "", $4); print $4; exit}'; }
    for m in single-interp single-native batch-2 batch-4 batch-8; do
        valgrind --tool=none "$build/bench-taylor_batch" 16 1 1 "$m" noref >/dev/null 2>&1
        f=hl_flow_evolve
        [ "${m#batch}" != "$m" ] && f=hl_flow_batch_evolve
        echo "# $m $(cg $f "$build/bench-taylor_batch" 16 100 1 "$m" noref)"
    done
    if [ -f "$out/taylor_batch_heyoka" ]; then
        for m in heyoka-scalar heyoka-batch-4 heyoka-batch-8; do
            echo "# $m $(cg '*propagate_until_impl*' "$out/taylor_batch_heyoka" 16 100 1 "$m")"
        done
    fi
fi
