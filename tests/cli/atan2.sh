#!/bin/bash
# atan2(y, x) in formulas, as a user meets it: read, printed back for SymPy
# and LaTeX, differentiated (the Lie series against SymPy's own, evaluated
# by mpmath in every quadrant of atan2's arguments), the numeric error
# analysis (dual-number series, analysis/numeric.c) against the symbolic
# v_k evaluated by mpmath at points where atan2's arguments lie in the
# fourth and the second quadrant; wrong arities refused with the position.
# usage (from the repo root): bash tests/cli/atan2.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: atan2.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

H='p*atan2(q, 2 + p) + q^2/2'

# the Lie series to D^3, SymPy's g^k z / k! with sympy.atan2, compared at
# points with 2 + p > 0 and < 0, q > 0 and < 0 (all four quadrants of atan2)
run 0 lie -H "$H" --order 3 --json
py '
q, p = S("q"), S("p")
H = S("p*atan2(q, 2 + p) + q**2/2")
assert S(d["H"]) == H, d["H"]
g = lambda f: sympy.diff(f, q) * sympy.diff(H, p) - sympy.diff(f, p) * sympy.diff(H, q)
for item, z in zip(d["series"], (q, p)):
    f = z
    for k, c in enumerate(item["coefficients"]):
        want = f / sympy.factorial(k)
        for qv, pv in (("7/10", "-2/5"), ("-3/5", "3/10"), ("1/2", "-13/5"), ("-4/5", "-31/10")):
            qv, pv = sympy.Rational(qv), sympy.Rational(pv)
            a = sympy.N(S(c).subs({q: qv, p: pv}), 30)
            b = sympy.N(want.subs({q: qv, p: pv}), 30)
            assert abs(a - b) < 1e-20 * (1 + abs(b)), (k, qv, pv, a, b)
        f = g(f)'

# LaTeX and the formula as sympify reads it
run 0 generator -H "$H" --latex
has_text '\operatorname{atan2}\left(q, p + 2\right)'
run 0 generator -H "$H" --json
py 'assert S(d["H"]).has(sympy.atan2)'

# numeric v_k (dual-number series through atan2) against the symbolic v_k
# at a point; Itoh-Abe's differences H(Q, p) - H(q, p) keep atan2 in the
# equations the numeric analysis evaluates
run 0 errors -H "$H" --scheme itoh-abe --order 3 --json
cp "$tmp/out" "$tmp/sym.json"
for at in 'q=-0.7,p=-0.4' 'q=0.6,p=-2.9'; do
    run 0 errors -H "$H" --scheme itoh-abe --order 3 --numeric --at "$at" --json
    python3 "$(dirname "$0")/lib/numeric_vk.py" "$tmp/sym.json" "$tmp/out" >"$tmp/py" 2>&1 && ok ||
        { bad "numeric v_k at $at"; cat "$tmp/py" >&2; }
done

# arities: an error at the spot, exit 2
run 2 lie -H 'atan2(q) + p^2' --order 2
err_has "expected ',': 'atan2' takes two arguments"
run 2 lie -H 'p^2 + sin(q, p)' --order 2
err_has "'sin' takes one argument"
run 2 lie -H 'p^2 + atan2(q, )' --order 2
err_has "expected an expression after ','"
run 2 lie -H 'p^2 + atan2(0, 0)*q' --order 2
err_has 'atan2(0, 0)'

finish
