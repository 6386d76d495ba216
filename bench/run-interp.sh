#!/bin/bash
# The double Taylor interpreter of several builds side by side (issue 14's
# "no speed regression"): bench/taylor_interp.c built against each, run
# interleaved ROUNDS times, each run the best of 1000 rounds of 100 calls
# (short rounds: on a loaded machine some run without interruption); prints
# per system and build the median and the minimum ns per call.
#   bench/run-interp.sh ROUNDS BIN...
# A build of another commit (the old interpreter a4ae1ce, say):
#   git worktree add /tmp/old a4ae1ce && cmake -S /tmp/old -B /tmp/old/build \
#     -DCMAKE_BUILD_TYPE=RelWithDebInfo && cmake --build /tmp/old/build --target hamlie_static
#   cc -O2 bench/taylor_interp.c -I /tmp/old/include /tmp/old/build/libhamlie.a \
#     -lflint-arb -lflint -lmpfr -lgmp -lgccjit -lm -ldl -o /tmp/interp-old
# The scalar loop of a build: a wrapper that sets HAMLIE_NO_AVX2=1.
# The loop of a processor without AVX2 and FMA (most without AVX2), glibc's
# libm included (its fma is then a slow emulation; sin, cos the SSE2 ones):
#   HAMLIE_NO_AVX2=1 HAMLIE_NO_FMA=1 \
#   GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2_Usable,-FMA_Usable,-AVX2,-FMA,-FMA4 \
#   bench/run-interp.sh --so ...
# (a build that reads neither variable, as a4ae1ce, still gets that libm).
#
# Steadier on a loaded machine: the builds' shared libraries in ONE process,
# taking turns round by round (a change of load or clock hits all alike):
#   bench/run-interp.sh --so ROUNDS BENCH LIB.so...
# BENCH is this tree's build/bench-taylor_interp; a LIB is a build's
# build/libhamlie.so (named by the folder above build/) or a copy of it
# (named by its file); ROUNDS of 100 calls each, min and median printed.
set -e
if [ "$1" = "--so" ]; then
    R=$2 BENCH=$3
    shift 3
    exec "$BENCH" "$R" 100 0 "$@"
fi
R=$1
shift
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for r in $(seq "$R"); do
    for b in "$@"; do
        "$b" 1000 100 | awk -v b="$(basename "$b")" '{print b, $1, $2}' >>"$out"
    done
done
/usr/bin/python3 - "$out" <<'PY'
import collections, statistics, sys
d = collections.defaultdict(list)
for line in open(sys.argv[1]):
    b, s, v = line.split()
    d[(s, b)].append(float(v))
for (s, b), v in sorted(d.items()):
    print("%-13s %-16s median %7.1f  min %7.1f ns/call  n=%d" % (s, b, statistics.median(v), min(v), len(v)))
PY
