#!/bin/bash
# The 1-dof exact flow (run --scheme exact, exact --init, --digits) on the
# orbits where it used to be silently wrong (issue 13, defect 2), against
# truths computed here by python3 + mpmath, not by hamlie:
#   the pendulum p^2/2 - cos q: a libration from the bottom (q = 0, p = 1.8,
#   q(4) = 0.9602: sin(q/2) = k sn(t | k^2), p = 2 k cn, k = p0/2), p < 0,
#   near the separatrix (q0 = 3.14, p0 = 1.99), a rotation (q = 2 am(k0 t |
#   1/k0^2), p = 2 k0 dn, T = 2 K(1/k0^2)/k0) also in Arb at 30 digits,
#   tiny amplitudes (q0 cos t), the equilibrium (stays; period 2 pi), and
#   the separatrix itself refused (exit 2, nothing on stdout);
#   quartic, Morse and double-well oscillators against the Taylor integrator
#   (run --scheme lie --tol 1e-15) at every output time; a Morse escape
#   and Morse at E = 1 refused, just below it the period 2 pi/sqrt(2(1-E)).
# usage (from the repo root): bash tests/cli/exact-orbits.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: exact-orbits.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PEND='p^2/2 - cos(q)'

# pend_check CSV TOL LABEL: every row of a pendulum run (t,q,p,...) against the closed
# form through its first row, within TOL (relative to the amplitude); queued,
# run by pend_check_all before finish
pend_check() {
    pend_n=$((pend_n + 1))
    cp "$1" "$tmp/pend$pend_n.csv"
    printf '%s\t%s\t%s\n' "$tmp/pend$pend_n.csv" "$2" "$3" >>"$tmp/pend.list"
}
pend_n=0
# pend_check_all: the queued runs in one python (mpmath's import, 0.8 s, was
# most of a check's cost)
pend_check_all() {
    local counts
    counts=$(python3 - "$tmp/pend.list" <<'PYEOF'
import csv, sys
from mpmath import mp, mpf, ellipfun, ellipk, ellipf, asin, atan2, floor, pi, sin, cos, sqrt
mp.dps = 40

def check(path, tol):
    rows = [[float(x) for x in r] for r in list(csv.reader(open(path)))[1:]]
    tol = float(tol)
    q0, p0 = mpf(rows[0][1]), mpf(rows[0][2])
    a = max(abs(q0), abs(p0))
    mp.dps = 40 + max(0, int(-2 * mp.log10(a)))  # E + 1 is a^2/2: no cancellation
    E = p0**2 / 2 - cos(q0)
    def state(t):
        if E < 1:  # libration: sin(q/2) = k sn(t + t0 | k^2), p = 2 k cn
            k = sqrt((1 + E) / 2); m = k * k
            u = ellipf(asin(min(mpf(1), sin(q0 / 2) / k)), m)
            t0 = u if p0 >= 0 else 2 * ellipk(m) - u
            return 2 * asin(k * ellipfun('sn', t + t0, m)), 2 * k * ellipfun('cn', t + t0, m)
        assert q0 == 0  # rotation from q = 0: q = 2 am(k0 t | 1/k0^2), p = 2 k0 dn
        k0 = sqrt((1 + E) / 2); m = 1 / k0**2; s = 1 if p0 > 0 else -1
        u = k0 * t; K = ellipk(m); n = floor(u / (2 * K)); r = u - 2 * n * K
        am = n * pi + atan2(ellipfun('sn', r, m), ellipfun('cn', r, m))
        return s * 2 * am, s * 2 * k0 * ellipfun('dn', u, m)
    worst = max(max(abs(q - r[1]), abs(p - r[2])) / a for r in rows for q, p in [state(mpf(r[0]))])
    assert worst < tol, (worst, tol)

passed = failed = 0
for line in open(sys.argv[1]).read().splitlines():
    path, tol, label = line.split("\t")
    mp.dps = 40
    try:
        check(path, tol)
        passed += 1
    except Exception as e:
        failed += 1
        print("FAIL: %s: %r" % (label, e), file=sys.stderr)
print(passed, failed)
PYEOF
)
    if [[ $counts =~ ^([0-9]+)\ ([0-9]+)$ ]] && [ $((BASH_REMATCH[1] + BASH_REMATCH[2])) -eq "$pend_n" ]; then
        pass=$((pass + BASH_REMATCH[1]))
        fail=$((fail + BASH_REMATCH[2]))
    else
        bad "the $pend_n pendulum checks did not run: '$counts'"
    fi
}

# the reproduction of the issue: q(4) = 0.9602, not 11.11
run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 4 --init q=0,p=1.8 --out "$tmp/lib.csv"
pend_check "$tmp/lib.csv" 1e-13 "libration from the bottom"
run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 20 --init q=0,p=-1.8 --out "$tmp/libn.csv"
pend_check "$tmp/libn.csv" 1e-13 "libration from the bottom, p < 0"
run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 40 --init q=0,p=1.99 --out "$tmp/sep1.csv"
pend_check "$tmp/sep1.csv" 1e-11 "libration near the separatrix, p0 = 1.99"
run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 40 --init q=3.14,p=0 --out "$tmp/sep2.csv"
pend_check "$tmp/sep2.csv" 1e-11 "libration near the separatrix, q0 = 3.14"
run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 40 --init q=0,p=2.5 --out "$tmp/rot.csv"
pend_check "$tmp/rot.csv" 1e-12 "rotation"
run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 40 --init q=0,p=-2.01 --out "$tmp/rotn.csv"
pend_check "$tmp/rotn.csv" 1e-12 "rotation near the separatrix, p < 0"
for q0 in 1e-8 1e-6 1e-300; do
    run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 20 --init q=$q0,p=0 --out "$tmp/tiny.csv"
    pend_check "$tmp/tiny.csv" 1e-13 "tiny amplitude q0 = $q0"
done

# periods: 4 K(k^2) for a libration, 2 K(1/k0^2)/k0 for a rotation, 2 pi at
# the equilibrium, which stays exactly where it is
period_is() { # the line "period T = ..." of exact --init against a python expression
    python3 -c "
import re, sys
from mpmath import mp, mpf, ellipk, sin, cos, sqrt, pi
mp.dps = 40
T = mpf(re.search(r'period T = (\S+),', open('$tmp/out').read()).group(1))
ref = $1
assert abs(T - ref) < $2 * ref, (T, ref)" && ok || bad "period: want $1"
}
run 0 exact -H "$PEND" --init q=3.14,p=0
period_is "4 * ellipk(sin(mpf(3.14) / 2)**2)" 1e-13
run 0 exact -H "$PEND" --init q=0,p=2.5
period_is "2 * ellipk(1 / mpf(1.25)**2) / mpf(1.25)" 1e-14
# 1e-8 from the separatrix on either side
run 0 exact -H "$PEND" --init q=0,p=1.99999999
period_is "4 * ellipk((mpf(1.99999999) / 2)**2)" 1e-14
run 0 exact -H "$PEND" --init q=0,p=2.00000001
period_is "2 * ellipk(1 / (mpf(2.00000001) / 2)**2) / (mpf(2.00000001) / 2)" 1e-14
run 0 exact -H "$PEND" --init q=0,p=0
period_is "2 * pi" 1e-15
has_text "Q = 0 P = 0"
# in Arb: the rotation's period to 28 digits
run 0 exact -H "$PEND" --init q=0,p=2.5 --digits 30
python3 -c "
import re
from mpmath import mp, mpf, ellipk
mp.dps = 40
T = mpf(re.search(r'in Arb at 30 digits: period T = (\S+)', open('$tmp/out').read()).group(1))
ref = 2 * ellipk(1 / mpf('1.25')**2) / mpf('1.25')
assert abs(T - ref) < mpf('1e-28') * ref, (T, ref)" && ok || bad "rotation period in Arb"

# the separatrix and an escape: refused, nothing written
run 2 exact -H "$PEND" --init q=0,p=2
err_has "separatrix"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
run 2 exact -H 'p^2/2 + (1-exp(-q))^2' --init q=0,p=1.5
err_has "unbounded orbit"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
# Morse at E = 1 to rounding (p = sqrt 2): the period diverges there too
run 2 exact -H 'p^2/2 + (1-exp(-q))^2' --init q=0,p=1.4142135623730951
err_has "separatrix"
# just below, E = 1 - 1.75e-8: the period 2 pi / sqrt(2 (1 - E)), 33587
run 0 exact -H 'p^2/2 + (1-exp(-q))^2' --init q=0,p=1.41421355
period_is "2 * pi / sqrt(2 * (1 - mpf(1.41421355)**2 / 2))" 1e-12

# other systems against the Taylor integrator in Arb (30 digits) at every
# output time: the double one at tol 1e-15 drifts by 1e-14 over t = 20 here
same_as_lie() { # H init tol
    run 0 run -H "$1" --scheme exact --dt 0.5 --t 20 --init "$2" --no-reference --out "$tmp/ex.csv"
    run 0 run -H "$1" --scheme lie --digits 30 --dt 0.5 --t 20 --init "$2" --no-reference --out "$tmp/lie.csv"
    python3 - "$tmp/ex.csv" "$tmp/lie.csv" "$3" <<'PYEOF' && ok || bad "$1 from $2 against the Taylor integrator"
import csv, sys
a, b = ([[float(x) for x in r[:3]] for r in list(csv.reader(open(f)))[1:]] for f in sys.argv[1:3])
assert len(a) == len(b) == 41
d = max(abs(x - y) for r, s in zip(a, b) for x, y in zip(r, s))
assert d < float(sys.argv[3]), d
PYEOF
}
same_as_lie 'p^2/2 + q^4/4' q=0.1,p=1 1e-13
same_as_lie 'p^2/2 + q^4/4' q=-1.2,p=0 1e-13
same_as_lie 'p^2/2 + (1-exp(-q))^2' q=0,p=-1.2 1e-13
same_as_lie 'p^2/2 + q^4/4 - q^2/2' q=1,p=0.1 1e-13
same_as_lie 'p^2/2 + q^4/4 - q^2/2' q=-0.5,p=0 1e-13
same_as_lie 'p^2/2 + q^4/4 - q^2/2' q=0.2,p=-0.8 1e-13
pend_check_all
finish
