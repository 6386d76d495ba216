#!/bin/bash
# hamlie exact, and the catalog's 'exact' through run and errors: the closed
# form against flows solved by hand (sympy compares), the three checks
# reported true, every error field zero, a run at round-off against the
# Taylor reference; coupled pairs in closed form against mpmath's expm; H
# not quadratic, cubic normal modes and symbolic couplings refused (exit 2).
# usage (from the repo root): bash tests/cli/exact.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: exact.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

ANISO='(px^2+py^2)/2+(x^2+4*y^2)/2'

run 0 exact -H "$ANISO"
has_line '  Y = y*cos(2*D) + py*sin(2*D)/2'
has_line 'canonical: yes'
has_line 'two steps of D = one step of 2D: yes'
run 0 exact -H "$ANISO" --json
py 'm = d["map"]
assert same(m["X"], "x*cos(D) + px*sin(D)") and same(m["PY"], "py*cos(2*D) - 2*y*sin(2*D)")
assert d["equals_lie_series"] and d["canonical"] and d["two_steps_equal_one_of_2D"]'
# hyperbolic: cosh and sinh, whatever the printed form
run 0 exact -H '(p^2-x^2)/2' --json
py 'assert simplify((S(d["map"]["X"]) - S("x*cosh(D) + p*sinh(D)")).rewrite(sympy.exp)) == 0'
# uniform field, symbolic g
run 0 exact -H 'p^2/2 + g*q' --json
py 'assert same(d["map"]["Q"], "q + D*p - g*D**2/2") and same(d["map"]["P"], "p - g*D")'

run 2 exact -H 'p^2/2 - cos(q)'
err_has "not quadratic"
# coupled pairs whose normal-mode frequencies are roots of a cubic: refused
run 2 exact -H '(px^2+py^2+pz^2)/2 + (x^2+2*y^2+4*z^2)/2 + x*y + y*z + x*z'
err_has "irreducible polynomial of degree 3"
run 2 exact -H '(px^2+py^2)/2 + (x^2+y^2)/2 + k*x*y'
err_has "couples the pairs of x and y and has symbolic coefficients"
run 2 exact -H "$ANISO" --order 0
err_has "--order must be from 1 to 40"

# the same scheme in the catalog: no error field, and a run on the exact flow
run 0 errors -H "$ANISO" --scheme exact --order 6
has_line 'v_6 = 0'
run 0 run -H "$ANISO" --scheme exact --dt 0.5 --t 1000 --init x=1,y=0.3,px=0,py=0.2 --json
python3 -c 'import json, sys; d = json.load(open(sys.argv[1]))
assert d["max_error"] < 1e-11 and d["max_abs_dH"] < 1e-11, d' "$tmp/out" && ok ||
    bad "exact run not at round-off: $(cat "$tmp/out")"
run 0 schemes --json
python3 -c 'import json, sys; d = json.load(open(sys.argv[1]))
e = [s for s in d["schemes"] if s["name"] == "exact"][0]
assert e["exact"] and e["quadratic_only"] and e["symplectic"] and not e["implicit"]' "$tmp/out" &&
    ok || bad "schemes: exact not listed as such"

# issue 6: the seven steps of §3 for the oscillator end in the rotation
run 0 exact -H '(p^2+x^2)/2' --steps
has_line '  theta = atan2(x, p)'
has_line '  x = sqrt(2*I)*sin(theta)'
has_line '  X = x*cos(D) + p*sin(D)'
has_line 'check the action-angle map: yes'
has_line 'check the result equals the closed form (max diff 0): yes'
# symbolic mass and stiffness: the steps hold too
run 0 exact -H 'p^2/(2*m)+k*q^2/2' --steps
has_line 'check dK/dq = p, dK/dI = theta: yes'
# the uniform field (theta = -p/g, nu = 1) and the free particle (theta = q,
# nu = I/m): the seven steps end in the flow, and each check holds
run 0 exact -H 'p^2/2 + g*q' --steps
has_line '  theta = -p/g'
has_line '  Q = q + D*p - D^2*g/2'
has_line 'check the action-angle map: yes'
has_line 'check dK/dq = p, dK/dI = theta: yes'
run 0 exact -H 'p^2/(2*m) + 0*q' --steps
has_line '  nu = I/m'
has_line 'check the result equals the closed form (max diff 0): yes'
# not p^2/(2m) + V(q) with V of degree <= 2: refused
run 2 exact -H 'p^2/2 + q*p' --steps
err_has "--steps carries out"

# a user's action-angle map: verified, or rejected naming the condition (exit 1)
AA='theta = atan2(x, p); I = (x^2+p^2)/2; x = sqrt(2*I)*sin(theta); p = sqrt(2*I)*cos(theta)'
run 0 exact -H '(p^2+x^2)/2' --action-angle "$AA; nu = 1"
has_line '  X = sqrt(x^2 + p^2)*sin(atan2(x, p) + D)'
run 1 exact -H '(p^2+x^2)/2' --action-angle "$AA; nu = 2"
has_line 'action-angle map rejected: {theta, H} = nu(I) fails: the angle does not advance at the frequency nu(I)'
run 1 exact -H '(p^2+x^2)/2' --action-angle 'theta = x; I = p; x = theta; p = I; nu = 1'
has_line 'action-angle map rejected: {I, H} = 0 fails: I is not an integral of motion'
run 2 exact -H '(p^2+x^2)/2' --action-angle 'theta = x; I = p'
err_has "lacks"

# numeric exact scheme of the pendulum: period 4 K(sin^2(0.65)) (mpmath-free:
# the value 7.0192503118445466 from Arb's elliptic K, 25 digits)
run 0 exact -H 'p^2/2 - cos(q)' --init q=1.3,p=0
python3 -c 'import re, sys; t = open(sys.argv[1]).read()
T = float(re.search(r"period T = (\S+),", t).group(1)); assert abs(T - 7.019250311844546606) < 1e-14, T
d = float(re.search(r"integrator \(tol 1e-15\): (\S+)", t).group(1)); assert d < 1e-13, d' "$tmp/out" &&
    ok || bad "pendulum period or steps: $(cat "$tmp/out")"
run 2 exact -H 'p^2/2 - cos(q)' --init q=0,p=2
err_has "separatrix"

# issue 6: coupled pairs in closed form (linear_modes.c), frequencies
# sqrt((5 +- sqrt 13)/2): the three checks hold, and the printed map equals
# mpmath's expm(D A) z at a point
COUPLED='(px^2+py^2)/2+(x^2+4*y^2)/2 + x*y'
run 0 exact -H "$COUPLED"
has_line 'equals exp(D g) z to D^8 (v_2..v_8 vanish): yes'
has_line 'canonical: yes'
has_line 'two steps of D = one step of 2D: yes'
has_text 'sqrt(13)'
run 0 exact -H "$COUPLED + x - py/3" --json
py 'import mpmath
mpmath.mp.dps = 30
A = mpmath.matrix([[0, 0, 1, 0, 0], [0, 0, 0, 1, -mpmath.mpf(1)/3], [-1, -1, 0, 0, -1],
                   [-1, -4, 0, 0, 0], [0, 0, 0, 0, 0]])
pt = {"x": (3, 10), "y": (-7, 10), "px": (9, 20), "py": (11, 10), "D": (17, 10)}
f = {n: mpmath.mpf(a) / b for n, (a, b) in pt.items()}
E = mpmath.expm(A * f["D"])
w = E * mpmath.matrix([f["x"], f["y"], f["px"], f["py"], 1])
for i, k in enumerate(["X", "Y", "PX", "PY"]):
    v = S(d["map"][k]).subs({loc[n]: Rational(a, b) for n, (a, b) in pt.items()}).evalf(30)
    assert abs(v - w[i]) < 1e-20, (k, v, w[i])'
# rational frequencies 1 and 3: no square root at all
run 0 exact -H '(px^2+py^2)/2 + (5*x^2+5*y^2)/2 + 4*x*y'
has_text 'cos(3*D)'
if grep -q sqrt "$tmp/out"; then bad "sqrt printed for rational frequencies"; else ok; fi
# the catalog's exact on a coupled H: every error field zero, a run at round-off
run 0 errors -H "$COUPLED" --scheme exact --order 4
has_line 'v_4 = 0'
run 0 run -H "$COUPLED" --scheme exact --dt 0.5 --t 100 --init x=1,y=0.3,px=0,py=0.2 --json
python3 -c 'import json, sys; d = json.load(open(sys.argv[1]))
assert d["max_error"] < 1e-11 and d["max_abs_dH"] < 1e-11, d' "$tmp/out" && ok ||
    bad "coupled exact run not at round-off: $(cat "$tmp/out")"

# the normal modes of a coupled H, as printed above the map: the
# frequencies sqrt of the eigenvalues of the potential's Hessian [[1,1],[1,4]]
# ((5 -+ sqrt 13)/2), a denested root, and a hyperbolic mode
run 0 exact -H '(px^2+py^2)/2+(x^2+4*y^2)/2 + x*y'
has_line "normal modes: elliptic w = sqrt(5/2 - sqrt(13)/2); elliptic w = sqrt(5/2 + sqrt(13)/2)"
run 0 exact -H '(px^2+py^2)/2 + (x^2+2*y^2)/2 + x*y'
has_line "normal modes: elliptic w = (-1/2 + sqrt(5)/2); elliptic w = (1/2 + sqrt(5)/2)"
run 0 exact -H '(px^2+py^2)/2 - (x^2+y^2)/2 + 2*x*y'
has_line "normal modes: hyperbolic w = sqrt(3); elliptic w = 1"
run 0 exact -H '(px^2+py^2)/2+(x^2+4*y^2)/2'
if grep -q "normal modes" "$tmp/out"; then bad "normal modes printed for uncoupled pairs"; else ok; fi
finish
