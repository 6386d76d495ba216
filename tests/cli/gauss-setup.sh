#!/bin/bash
# Gauss-Legendre set-up on Kepler (issue 13, defect 7): the stage equations
# of an implicit Runge-Kutta scheme must not be put over a common
# denominator (in 3-D gauss3 took over a minute and gauss2 250 MB).  Each
# run has a time limit, and its result is checked against an independent
# route: the adaptive Taylor integrator at --tol 1e-15, at two step sizes
# whose errors must fall by 2^order (gauss2: 16, gauss3: 64) -- the
# scheme's order seen from outside, not read from the catalog.
# usage (from the repo root): bash tests/cli/gauss-setup.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: gauss-setup.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
LIMIT=20 # seconds a call may take (generous for the sanitizer build)
K2='(px^2+py^2)/2 - 1/sqrt(x^2+y^2)'
K3='(px^2+py^2+pz^2)/2 - 1/sqrt(x^2+y^2+z^2)'
I2='x=1,y=0.1,px=-0.1,py=1'
I3='x=1,y=0,z=0.2,px=-0.1,py=1,pz=0.1'

# timed NAME args...: run hamlie under the time limit, stdout to $tmp/NAME
timed() {
    local name=$1
    shift
    timeout "$LIMIT" "$HAMLIE" "$@" >"$tmp/$name" 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -eq 0 ]; then ok; else
        bad "hamlie $* exited $rc (124: over ${LIMIT} s)"; sed 's/^/    /' "$tmp/err" >&2
    fi
}

# one step of each Gauss rule, 2-D and 3-D: the set-up alone must be quick
for s in gauss2 gauss3; do
    timed one2 run -H "$K2" --scheme $s --dt 0.01 --t 0.01 --init "$I2"
    timed one3 run -H "$K3" --scheme $s --dt 0.01 --t 0.01 --init "$I3"
done

# order_ratio ORDER NVAR H INIT DT1 DT2 SCHEME: the error of the NVAR phase
# variables at t = 1 against the Taylor integrator falls by 2^ORDER (within
# 30 %) when the step is halved
order_ratio() {
    local want=$1 nvar=$2 H=$3 init=$4 dt1=$5 dt2=$6 s=$7
    timed ref run -H "$H" --scheme lie --tol 1e-15 --dt 1 --t 1 --init "$init"
    timed a run -H "$H" --scheme "$s" --dt "$dt1" --t 1 --init "$init"
    timed b run -H "$H" --scheme "$s" --dt "$dt2" --t 1 --init "$init"
    if python3 - "$tmp" "$nvar" "$want" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "$s on $H: error ratio"; sed 's/^/    /' "$tmp/py" >&2; fi
import sys
tmp, nvar, want = sys.argv[1], int(sys.argv[2]), 2 ** int(sys.argv[3])
def at_one(name):  # the phase variables of the last row, t = 1
    row = [float(v) for v in open(f"{tmp}/{name}").read().split("\n")[-2].split(",")]
    assert row[0] == 1.0, row
    return row[1:1 + nvar]
ref = at_one("ref")
def err(name):
    return max(abs(a - b) for a, b in zip(at_one(name), ref))
ea, eb = err("a"), err("b")
print(ea, eb, ea / eb, want)
assert eb > 1e-13, "the finer error is at rounding: take larger steps"
assert 0.7 * want < ea / eb < 1.3 * want, (ea, eb, ea / eb, want)
PYEOF
}

# ---- stages coupled through a linear part: the map itself -----------------
# On x^2/2 + y^4/4 + x y/4 the stage equations of the x pair are affine in
# several stages.  They were solved by substitution, one stage at a time:
# gauss2 then erred by 1e-12 and gauss3 refused to compile ("a constant
# subexpression cannot be decided").  Ten steps of each against the same
# Gauss-Legendre map written here from its Butcher tableau and solved by
# fixed-point iteration at 40 digits (mpmath): equal to rounding.
QW='(px^2+py^2)/2 + x^2/2 + y^4/4 + x*y/4'
for s in gauss2 gauss3; do
    timed gl run -H "$QW" --scheme $s --dt 0.1 --t 1 --init x=1,y=0,px=0,py=1/2 --no-reference --json
    if python3 - "$tmp/gl" "${s#gauss}" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "$s on $QW: not the Gauss-Legendre map"; sed 's/^/    /' "$tmp/py" >&2; fi
import json, sys
from mpmath import mp, mpf, sqrt
mp.dps = 40
def f(z):
    x, y, px, py = z
    return [px, py, -(x + y / 4), -(y ** 3 + x / 4)]
if sys.argv[2] == "2":
    r = sqrt(3) / 6
    A = [[mpf(1) / 4, mpf(1) / 4 - r], [mpf(1) / 4 + r, mpf(1) / 4]]
    b = [mpf(1) / 2] * 2
else:
    r = sqrt(15)
    A = [[mpf(5) / 36, mpf(2) / 9 - r / 15, mpf(5) / 36 - r / 30],
         [mpf(5) / 36 + r / 24, mpf(2) / 9, mpf(5) / 36 - r / 24],
         [mpf(5) / 36 + r / 30, mpf(2) / 9 + r / 15, mpf(5) / 36]]
    b = [mpf(5) / 18, mpf(4) / 9, mpf(5) / 18]
def step(z, h):
    s = len(b)
    K = [f(z)] * s
    for _ in range(200):
        K = [f([z[c] + h * sum(A[i][j] * K[j][c] for j in range(s)) for c in range(4)])
             for i in range(s)]
    return [z[c] + h * sum(b[i] * K[i][c] for i in range(s)) for c in range(4)]
z = [mpf(1), mpf(0), mpf(0), mpf(1) / 2]
for _ in range(10):
    z = step(z, mpf(1) / 10)
d = json.load(open(sys.argv[1]))["final_state"]
got = [d["x"], d["y"], d["px"], d["py"]]
err = max(abs(g - w) for g, w in zip(got, z))
print(got, [float(w) for w in z], float(err))
assert err < 1e-14, float(err)
PYEOF
done

order_ratio 4 4 "$K2" "$I2" 0.1 0.05 gauss2
order_ratio 6 4 "$K2" "$I2" 0.1 0.05 gauss3
order_ratio 4 6 "$K3" "$I3" 0.1 0.05 gauss2
order_ratio 6 6 "$K3" "$I3" 0.1 0.05 gauss3
finish
