#!/bin/bash
# Issue 13, defect 10: exact --json with --steps, --action-angle and --init
# (refused before).  Every formula is a string sympy reads; they are
# checked against closed forms by SymPy, the numbers against mpmath.
# usage (from the repo root): bash tests/cli/exact-json.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: exact-json.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

# the harness's S() knows the system's symbols; the step formulas also use
# those of "formula_symbols" (I, theta, eps: plain symbols, not sympy's I)
PRE='
for n in d.get("formula_symbols", []):
    loc[n] = Symbol(n)   # as the strings spell them: Symbol("I"), not the imaginary unit
import random, mpmath
random.seed(13)
def at(e, **v):
    return complex(S(e).subs({loc[k]: x for k, x in v.items()}).evalf(30))
'

# ---- --steps: the oscillator, m = k = 1 ----------------------------------------
run 0 exact -H '(p^2+q^2)/2' --steps --json
py "$PRE"'
assert d["mode"] == "steps" and d["all_checks_hold"] is True
st = {s["step"]: s["formulas"] for s in d["steps"]}
assert sorted(st) == [1, 2, 3, 4, 5, 6, 7] and d["form"] == {"kind": "oscillator", "m": "1", "k": "1"}
I, q, p, D, eps = (loc[n] for n in ("I", "q", "p", "D", "eps"))
H = S(d["H"])
assert same(S(st[1]["I"]), H)                                     # the action is H
assert simplify(S(st[3]["K"]).diff(q) - S(st[2]["p"])) == 0       # K = int p dq
# dK/dI = theta on the branch eps = 1 (p > 0); SymPy cannot simplify atan - atan2
# without that sign, so compared at points with q^2 < 2I
dKdI = (S(st[3]["K"]).diff(I) - S(st[4]["theta"]).subs(p, S(st[2]["p"]))).subs(eps, 1)
for qv, Iv in ((sympy.Rational(3, 10), 1), (sympy.Rational(-6, 5), sympy.Rational(4, 5)), (sympy.Rational(1, 20), sympy.Rational(5, 2))):
    assert abs(complex(dKdI.subs({q: qv, I: Iv}).evalf(30))) < 1e-25, (qv, Iv)
assert S(st[6]["nu"]) == 1
# the closed form is the flow exp(D g): x cos D + p sin D
assert same(d["closed_form"]["Q"], "q*cos(D) + p*sin(D)")
assert same(d["closed_form"]["P"], "-q*sin(D) + p*cos(D)")
# the result of the seven steps equals it where its branch holds (p > 0)
for _ in range(20):
    v = dict(q=random.uniform(-2, 2), p=random.uniform(-2, 2), D=random.uniform(-3, 3))
    for k in ("Q", "P"):
        assert abs(at(d["result"][k], **v) - at(d["closed_form"][k], **v)) < 1e-12, (k, v)
# the inverse (step 5) at I = H and theta = step 4 gives the point back
for _ in range(10):
    v = dict(q=random.uniform(-2, 2), p=random.uniform(0.1, 2))
    th = S(st[4]["theta"]).subs({q: v["q"], p: v["p"]})
    Iv = H.subs({q: v["q"], p: v["p"]})
    assert abs(complex(S(st[5]["q"]).subs({loc["theta"]: th, I: Iv}).evalf()) - v["q"]) < 1e-12
    assert abs(complex(S(st[5]["p"]).subs({loc["theta"]: th, I: Iv}).evalf()) - v["p"]) < 1e-12
c = d["checks"]
assert c["dK_dq_is_p_and_dK_dI_is_theta"] and c["action_angle_map"] and c["equals_closed_form"]
'

# ---- --steps with m = 3, k = 5: w = sqrt(k/m) ------------------------------------
run 0 exact -H 'p^2/6 + 5*q^2/2' --steps --json
py '
assert d["form"] == {"kind": "oscillator", "m": "3", "k": "5"}, d["form"]
w = sqrt(Rational(5, 3))
q, p, D = loc["q"], loc["p"], loc["D"]
assert simplify(S(d["closed_form"]["Q"]) - (q*cos(w*D) + p/(3*w)*sin(w*D))) == 0
assert simplify(S(d["closed_form"]["P"]) - (-3*w*q*sin(w*D) + p*cos(w*D))) == 0
'

# ---- --steps, a uniform field g = 3: Q = q + p D - 3 D^2/2, P = p - 3 D -------------
run 0 exact -H 'p^2/2 + 3*q' --steps --json
py '
assert d["form"]["kind"] == "uniform field" and S(d["form"]["g"]) == 3 and S(d["form"]["m"]) == 1
assert same(d["closed_form"]["Q"], "q + p*D - 3*D**2/2")
assert same(d["closed_form"]["P"], "p - 3*D")
assert d["all_checks_hold"] is True
'

# ---- --action-angle: a user's map, verified and rejected ---------------------------
AA='theta = atan2(q, p); I = (p^2+q^2)/2; q = sqrt(2*I)*sin(theta); p = sqrt(2*I)*cos(theta)'
run 0 exact -H '(p^2+q^2)/2' --action-angle "$AA; nu = 1" --json
py "$PRE"'
assert d["mode"] == "action_angle" and d["verified"] is True and d["rejected_because"] is None
for _ in range(20):
    v = dict(q=random.uniform(-2, 2), p=random.uniform(-2, 2), D=random.uniform(-3, 3))
    assert abs(at(d["scheme"]["Q"], **v) - (v["q"]*mpmath.cos(v["D"]) + v["p"]*mpmath.sin(v["D"]))) < 1e-12
    assert abs(at(d["scheme"]["P"], **v) - (-v["q"]*mpmath.sin(v["D"]) + v["p"]*mpmath.cos(v["D"]))) < 1e-12
'
run 1 exact -H '(p^2+q^2)/2' --action-angle "$AA; nu = 2" --json
py 'assert d["verified"] is False and "nu" in d["rejected_because"] and d["all_checks_hold"] is False'
# the paper's atan(q/p) is the angle for p > 0 only: rejected, and said why in the JSON
run 1 exact -H '(p^2+q^2)/2' --action-angle "${AA/atan2(q, p)/atan(q/p)}; nu = 1" --json
py 'assert d["verified"] is False and "inverse" in d["rejected_because"] and d["all_checks_hold"] is False'

# ---- --init: the pendulum's orbit against Jacobi's sn (mpmath) ----------------------
# from rest at q0: sin(q/2) = k sn(K - t | m), m = k^2 = sin(q0/2)^2, T = 4 K(m)
JACOBI='
mpmath.mp.dps = 40
m = mpmath.sin(mpmath.mpf(1) / 2) ** 2
K = mpmath.ellipk(m)
qt = lambda t: 2 * mpmath.asin(mpmath.sqrt(m) * mpmath.ellipfun("sn", K - t, m=m))
T, q4, p4 = 4 * K, qt(4), mpmath.diff(qt, 4)
'
run 0 exact -H 'p^2/2 - cos(q)' --init q=1,p=0 --json
py "$PRE$JACOBI"'
assert d["mode"] == "init" and d["orbit"]["quadratic"] is False
assert abs(d["orbit"]["period"] - T) < 1e-12, (d["orbit"]["period"], T)
assert abs(d["orbit"]["frequency"] - 2 * mpmath.pi / T) < 1e-12
e = d["exact_steps"]
assert e["dt"] == 0.5 and e["count"] == 8
assert abs(e["final_state"]["Q"] - q4) < 1e-12 and abs(e["final_state"]["P"] - p4) < 1e-12, (e, q4, p4)
assert e["max_difference_from_taylor"] < 1e-11
'
run 0 exact -H 'p^2/2 - cos(q)' --init q=1,p=0 --digits 25 --json
py "$PRE$JACOBI"'
a = d["arb"]
assert a["digits"] == 25
assert abs(mpmath.mpf(a["period"]) - T) < mpmath.mpf("1e-23"), (a["period"], T)
assert abs(mpmath.mpf(a["final_state"]["Q"]) - q4) < mpmath.mpf("1e-22")
assert abs(mpmath.mpf(a["final_state"]["P"]) - p4) < mpmath.mpf("1e-22")
'
# a quadratic H: no orbit by quadrature (the period is not computed: null)
run 0 exact -H '(p^2+q^2)/2' --init q=1,p=0 --json
py 'assert d["orbit"]["quadratic"] is True and d["orbit"]["period"] is None
assert abs(d["exact_steps"]["final_state"]["Q"] - __import__("math").cos(4)) < 1e-13'

finish
