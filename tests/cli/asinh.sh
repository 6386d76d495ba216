#!/bin/bash
# asinh, the function added by one rule (src/rules/asinh.c) to show what a
# new elementary function costs: read and differentiated (the Lie series
# against SymPy's own g^k z / k! with sympy.asinh, at points of both signs),
# integrated (a run's energy against the H written with log and sqrt, which
# the algebra uses for it), the numeric error analysis (dual numbers)
# against the symbolic v_k, and a Taylor run against mpmath's solution.
# usage (from the repo root): bash tests/cli/asinh.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: asinh.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

H='p^2/2 + asinh(q)'

# the Lie series to D^4 against SymPy, at q < 0 and q > 0
run 0 lie -H "$H" --order 4 --json
py '
q, p = S("q"), S("p")
H = p**2/2 + sympy.asinh(q)
g = lambda f: sympy.diff(f, q) * sympy.diff(H, p) - sympy.diff(f, p) * sympy.diff(H, q)
for item, z in zip(d["series"], (q, p)):
    f = z
    for k, c in enumerate(item["coefficients"]):
        want = f / sympy.factorial(k)
        for qv, pv in (("7/10", "-2/5"), ("-3/5", "3/10"), ("0", "1")):
            qv, pv = sympy.Rational(qv), sympy.Rational(pv)
            a = sympy.N(S(c).subs({q: qv, p: pv}), 30)
            b = sympy.N(want.subs({q: qv, p: pv}), 30)
            assert abs(a - b) < 1e-20 * (1 + abs(b)), (k, qv, pv, a, b)
        f = g(f)'

# the Taylor flow (the rule's recurrence, interpreted and compiled) against
# mpmath's ODE solver: q(3) from (q, p) = (0.5, 1)
run 0 run -H "$H" --scheme lie --tol 1e-14 --dt 0.5 --t 3 --init 'q=0.5,p=1' --json
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "Taylor run against mpmath"; cat "$tmp/py" >&2; }
import json, sys, mpmath
d = json.load(open(sys.argv[1]))
mpmath.mp.dps = 30
f = mpmath.odefun(lambda t, z: [z[1], -1/mpmath.sqrt(1 + z[0]**2)], 0, [mpmath.mpf("0.5"), mpmath.mpf(1)])
want = f(3)
got = d["final_state"]
assert abs(got["q"] - want[0]) < 1e-12 and abs(got["p"] - want[1]) < 1e-12, (got, want)
PYEOF

# numeric v_k (dual numbers through asinh) against the symbolic v_k
run 0 errors -H "$H" --scheme rk4 --order 5 --json
cp "$tmp/out" "$tmp/sym.json"
for at in 'q=-0.7,p=-0.4' 'q=1.6,p=0.9'; do
    run 0 errors -H "$H" --scheme rk4 --order 5 --numeric --at "$at" --json
    python3 "$(dirname "$0")/lib/numeric_vk.py" "$tmp/sym.json" "$tmp/out" >"$tmp/py" 2>&1 && ok ||
        { bad "numeric v_k at $at"; cat "$tmp/py" >&2; }
done

# arity: an error at the spot, exit 2
run 2 lie -H 'p^2 + asinh(q, p)' --order 2
err_has "'asinh' takes one argument"

finish
