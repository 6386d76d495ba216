#!/bin/bash
# hamlie sweep with lie members in SIMD lanes (HAMLIE_SWEEP_BATCH=1) and
# one at a time (=0): the same CSV bytes, with 1 and 2 threads, for a
# sweep whose batches hold members that end ok, blow up (H = p^2/2 - q^4
# from q = 50 and 1.2, escaping at about 0.93/q0 < 2) and start outside
# H's domain (a q^4 + 1/q term: q = 0), with a fixed-step scheme and the
# chaos indicators beside them; the statuses as expected (exit 1, the
# failures named; euler's runaway from q = 50 may end at t = 2, its chaos
# indicators failing).  The lanes are compiled here (HAMLIE_JIT_VERBOSE says
# so when libgccjit is there): a quartic at tol 1e-9, a small program.
# Then fixed-step members in lanes (hl_run_fixed_batch's compiled loop)
# beside lie ones: stormer-verlet-kdk, rk4 and euler in the well of
# H = p^2/2 + q^2/2 - q^4/4 (bounded for |q| < 1 below the barrier H =
# 1/4) and from q = 1.5 and -2 (outside it: q runs off to infinity in
# finite time, every scheme blows up, lie's steps underflow), and euler at
# dt 0.25, whose energy grows out of the well from |q| near 0.9: the same
# bytes with lanes off (1 thread) and on (1 and 2 threads; reasons included).
# usage (from the repo root): bash tests/cli/sweep_lanes.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: sweep_lanes.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3

H='p^2/2 - q^4 + 1e-3/q^2'
args=(sweep -H "$H" --grid 'q=0.3,50,0,0.25,1.2,0.2,-0.3,0.35,0.15,p=0,0.1' --scheme lie,euler
    --dt 0.25,0.5 --t 2 --tol 1e-9 --chaos)
for mode in 0 1; do
    for threads in 1 2; do
        HAMLIE_SWEEP_BATCH=$mode HAMLIE_JIT_VERBOSE=1 run 1 "${args[@]}" --threads $threads \
            --out "$tmp/m$mode-t$threads.csv"
        cp "$tmp/err" "$tmp/err-m$mode-t$threads"
    done
done
for f in m0-t2 m1-t1 m1-t2; do
    cmp -s "$tmp/m0-t1.csv" "$tmp/$f.csv" && ok || bad "lanes: $f.csv differs from m0-t1.csv"
done
if grep -q "jit: the batch recursion" "$tmp/err-m0-t1"; then bad "lanes off, yet compiled"; else ok; fi
# the lanes compiled, or found in the cache, when libgccjit is there
if grep -q "jit:" "$tmp/err-m1-t1" && ! grep -q "jit: the batch recursion" "$tmp/err-m1-t1"; then
    bad "lanes on, no batch recursion:"; sed 's/^/    /' "$tmp/err-m1-t1" >&2
else ok; fi
grep -q "failed" "$tmp/err-m1-t2" && ok || bad "no failure named on stderr"
if $PY - "$tmp/m1-t1.csv" >"$tmp/py" 2>&1 <<'PYEOF'; then ok; else bad "statuses"; sed 's/^/    /' "$tmp/py" >&2; fi
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 18 * 2 * 2, len(rows)
for r in rows:
    q0 = float(r["q0"])
    if q0 == 0:  # outside the domain from the start
        assert r["status"] != "ok" and "domain" in r["reason"], r
    elif q0 in (50, 1.2):  # escape before t = 2: lie stops, euler may only run away
        assert r["status"] != "ok" and (r["scheme"] != "lie" or float(r["t"]) < 2), r
    else:
        assert r["status"] == "ok" and r["t"] == "2" and r["megno"] != "nan", r
PYEOF

# ---- fixed-step members in lanes ---------------------------------------------
H='p^2/2 + q^2/2 - q^4/4'
args=(sweep -H "$H" --grid 'q=-0.9:0.9:6,1.5,-2,p=0,0.1' --scheme lie,stormer-verlet-kdk,rk4,euler
    --dt 0.002,0.25 --t 10 --tol 1e-9)
for mt in 0-1 1-1 1-2; do # lanes off with 1 thread; on with 1 and 2
    mode=${mt%-*} threads=${mt#*-}
    HAMLIE_SWEEP_BATCH=$mode HAMLIE_JIT_VERBOSE=1 run 1 "${args[@]}" --threads $threads \
        --out "$tmp/f$mode-t$threads.csv"
    cp "$tmp/err" "$tmp/err-f$mode-t$threads"
done
for f in f1-t1 f1-t2; do
    cmp -s "$tmp/f0-t1.csv" "$tmp/$f.csv" && ok || bad "fixed lanes: $f.csv differs from f0-t1.csv"
done
if grep -q "jit: the lanes' loop" "$tmp/err-f0-t1"; then bad "fixed lanes off, yet compiled"; else ok; fi
# the fixed-step lanes' loop compiled, or found in the cache, when libgccjit is there
if grep -q "jit:" "$tmp/err-f1-t1" && ! grep -q "jit: the lanes' loop" "$tmp/err-f1-t1"; then
    bad "fixed lanes on, no lanes' loop:"; sed 's/^/    /' "$tmp/err-f1-t1" >&2
else ok; fi
if $PY - "$tmp/f1-t2.csv" >"$tmp/py" 2>&1 <<'PYEOF'; then ok; else bad "fixed statuses"; sed 's/^/    /' "$tmp/py" >&2; fi
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 16 * 4 * 2, len(rows)
euler_out = 0
for r in rows:
    q0, fixed = float(r["q0"]), r["scheme"] != "lie"
    if q0 in (1.5, -2):  # runs off to infinity at t < 2
        assert r["status"] != "ok" and float(r["t"]) < 5, r
        assert not fixed or r["reason"].startswith("blow-up"), r
    elif r["scheme"] == "euler" and r["dt"] == "0.25" and r["status"] != "ok":
        assert abs(q0) > 0.5 and r["reason"].startswith("blow-up"), r
        euler_out += 1
    else:
        assert r["status"] == "ok" and r["t"] == "10", r
assert euler_out > 0
PYEOF
finish
