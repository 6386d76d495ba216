#!/bin/bash
# The command lines of issue 4 (schemes, errors), checked for exit code, key output lines, and
# (through --json and sympy) the mathematics: every expected value is a closed
# form or computed independently in sympy, never copied from hamlie's output.
# usage (from the repo root): bash tests/cli/analysis.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: analysis.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

# every expression in a JSON output must sympify
ALL_PARSE='
for k, v in d.items():
    if k in ("command", "symbols", "scheme") or k.endswith("input"):
        continue
    for s in every_string(v):
        S(s)
'

# sympy helpers for the error fields: v_k(z_i) = k! ([D^k] psi_i - [D^k] flow_i)
VK='
D = loc["D"]
def coeff(e, k):
    return sympy.series(e, D, 0, k + 1).removeO().coeff(D, k)
def check_fields(psi, flow, names):
    for f in d["fields"]:
        k = f["k"]
        for i, n in enumerate(names):
            want = factorial(k) * (coeff(psi[i], k) - coeff(flow[i], k))
            assert simplify(S(f["v"][n]) - want) == 0, (k, n, f["v"][n], want)
x, p = loc.get("x"), loc.get("p")
'
OSC='(p^2+x^2)/2'
ROT='flow = [x*cos(D) + p*sin(D), p*cos(D) - x*sin(D)]'

# ---- schemes --------------------------------------------------------------------
run 0 schemes
has_text 'rk4'
has_text 'implicit-midpoint'
run 0 schemes --latex
has_text '\begin{tabular}'
"$HAMLIE" schemes --json >"$tmp/out" 2>"$tmp/err" && ok || bad "schemes --json"
if python3 - "$tmp/out" <<'PYEOF'; then ok; else bad "schemes JSON"; fi
import json, sys
d = json.load(open(sys.argv[1]))
s = {e["name"]: e for e in d["schemes"]}
assert s["rk4"]["order"] == 4 and not s["rk4"]["implicit"] and not s["rk4"]["symplectic"]
assert s["implicit-midpoint"]["symplectic"] and s["implicit-midpoint"]["implicit"]
assert s["exact-rotation"]["order"] is None and s["exact-rotation"]["exact"]
assert s["avf"]["preserves_H"]
PYEOF
run 2 schemes -H 'p^2'

# ---- errors: explicit Euler on the oscillator --------------------------------------
run 0 errors -H "$OSC" --scheme euler --order 7
has_line 'v_k computed two ways: agree'
has_line 'order: 1 (leading error v_2)'
has_text 'a scaling'
run 0 errors -H "$OSC" --scheme euler --order 7 --json
py "$ALL_PARSE"
py "$VK
$ROT
# Euler = sqrt(1+D^2) times the rotation by atan(D)
r = sqrt(1 + D**2); a = sympy.atan(D)
check_fields([r*(x*cos(a) + p*sin(a)), r*(p*cos(a) - x*sin(a))], flow, ['x', 'p'])
assert d['order'] == 1 and d['two_ways_agree']
assert d['leading']['kind'] == 'scaling' and S(d['leading']['scale']['x']) == 1
assert simplify(S(d['K']['x']) - (p + D*x)) == 0 and simplify(S(d['K']['p']) - (-x + D*p)) == 0"

# ---- the paper's discrete gradient as a map --------------------------------------
DG='X = (4*x+4*D*p-D^2*x)/(4+D^2); P = (4*p-4*D*x-D^2*p)/(4+D^2)'
run 0 errors -H "$OSC" --map "$DG" --order 7
has_line 'order: 2 (leading error v_3)'
has_text 'a pure time translation'
run 0 errors -H "$OSC" --map "$DG" --order 7 --json
py "$VK
$ROT
t = 2*sympy.atan(D/2)
check_fields([x*cos(t) + p*sin(t), p*cos(t) - x*sin(t)], flow, ['x', 'p'])
L = d['leading']
assert d['order'] == 2 and L['kind'] == 'time_shift' and S(L['lambda']) == Rational(-1, 2)
assert simplify(S(L['h']) + (x**2 + p**2)/4) == 0
# K in closed form, derived by hand: psi_{-D} o d/dD psi_D = 4/(4+D^2) (p, -x)
assert simplify(S(d['K']['x']) - 4*p/(4 + D**2)) == 0"

# part 4: tan(tau/2) = M12/(1 + M11) = (4D/(4+D^2))/(8/(4+D^2)) = D/2 (by hand);
# two steps: D'/2 = tan(2 atan(D/2)) = D/(1 - D^2/4)
py "$VK
t = d['time']
assert t['pure_time_translation'] and t['fails_at'] is None
assert simplify(S(t['tau']) - 2*sympy.atan(D/2)) == 0
assert simplify(S(t['double_step']) - 8*D/(4 - D**2)) == 0
ser = sympy.series(2*sympy.atan(D/2), D, 0, 8).removeO()
assert sympy.expand(S(t['tau_series']) - ser) == 0
assert sympy.expand(S(t['W_series']) - (ser - D)) == 0"
run 0 errors -H "$OSC" --map "$DG" --order 7
has_line '  closed form: tan(tau/2) = M12/(1 + M11) = D/2, tau = 2*atan(D/2)'
run 0 errors -H "$OSC" --scheme euler --order 4 --json
py "assert d['time'] is None"
run 0 errors -H "$OSC" --scheme rk4 --order 6
has_text 'time reparametrisation: none (the D^6 term'

# ---- the same as implicit equations (implicit midpoint) -----------------------------
run 0 errors -H "$OSC" --equations '(X-x)/D = (P+p)/2; (P-p)/D = -(X+x)/2' --order 7 --json
py "$VK
$ROT
t = 2*sympy.atan(D/2)
check_fields([x*cos(t) + p*sin(t), p*cos(t) - x*sin(t)], flow, ['x', 'p'])
assert d['order'] == 2 and not d['scheme']['explicit']
t = d['time']
assert t['closed_form_from_series'] and simplify(S(t['tau']) - 2*sympy.atan(D/2)) == 0
assert simplify(S(t['double_step']) - 8*D/(4 - D**2)) == 0"

# ---- implicit midpoint on the pendulum: sympy solves the scheme by iteration ---------
run 0 errors -H 'p^2/2 - cos(q)' --scheme implicit-midpoint --order 6
has_line 'order: 2 (leading error v_3)'
run 0 errors -H 'p^2/2 - cos(q)' --scheme implicit-midpoint --order 6 --json
py "$VK
q = loc['q']
n = 7
tr = lambda e: sympy.series(e, D, 0, n).removeO()
Q, P = q, p
for it in range(n):
    Q, P = tr(q + D*(p + P)/2), tr(p - D*sin((q + Q)/2))
g = lambda f: p*sympy.diff(f, q) - sin(q)*sympy.diff(f, p)
def lie(z):
    t, s = z, z
    for k in range(1, n):
        t = g(t); s += D**k/factorial(k)*t
    return s
check_fields([Q, P], [lie(q), lie(p)], ['q', 'p'])
assert d['order'] == 2 and d['leading']['hamiltonian']"

# ---- RK4 on Henon-Heiles -----------------------------------------------------------
HH='(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3'
run 0 errors -H "$HH" --scheme rk4 --order 6
has_line 'order: 4 (leading error v_5)'
run 0 errors -H "$HH" --scheme rk4 --order 6 --json
py "$VK
y, px, py_ = loc['y'], loc['px'], loc['py']
zs = [x, y, px, py_]
H = (px**2 + py_**2)/2 + (x**2 + y**2)/2 + x**2*y - y**3/3
F = lambda z: [sympy.diff(H, px).subs(dict(zip(zs, z)), simultaneous=True),
               sympy.diff(H, py_).subs(dict(zip(zs, z)), simultaneous=True),
               -sympy.diff(H, x).subs(dict(zip(zs, z)), simultaneous=True),
               -sympy.diff(H, y).subs(dict(zip(zs, z)), simultaneous=True)]
k1 = F(zs); k2 = F([zs[i] + D/2*k1[i] for i in range(4)])
k3 = F([zs[i] + D/2*k2[i] for i in range(4)]); k4 = F([zs[i] + D*k3[i] for i in range(4)])
psi = [sympy.expand(zs[i] + D/6*(k1[i] + 2*k2[i] + 2*k3[i] + k4[i])) for i in range(4)]
g = lambda f: sum(sympy.diff(f, zs[i])*F(zs)[i] for i in range(4))
def lie(z):
    t, s = z, z
    for k in range(1, 7):
        t = sympy.expand(g(t)); s += D**k/factorial(k)*t
    return s
check_fields(psi, [lie(z) for z in zs], ['x', 'y', 'px', 'py'])
assert d['order'] == 4"

# ---- --correct 4: Euler with v_2..v_4 subtracted is RK4 on the oscillator -------------
run 0 errors -H "$OSC" --scheme euler --order 7 --correct 4
has_text 'corrected scheme (v_2..v_4 subtracted)'
has_line 'order: 4 (leading error v_5)'
run 0 errors -H "$OSC" --scheme euler --order 7 --correct 4 --json
py "$VK
c = d['corrected']
T4 = 1 - D**2/2 + D**4/24; S3 = D - D**3/6
assert simplify(S(c['map']['x']) - (T4*x + S3*p)) == 0
assert simplify(S(c['map']['p']) - (T4*p - S3*x)) == 0
assert c['order'] == 4 and c['two_ways_agree']"
# the Cayley rotation minus its D^3 error is still off at D^4 (v_4 = 2 z, from
# cos(D - D^3/12) = cos D + D^4/12 + ...): order 3, not 4
run 0 errors -H "$OSC" --scheme implicit-midpoint --order 5 --correct 3
has_line 'order: 3 (leading error v_4)'
has_text 'psi_D(z) - sum_{k=2}^{3}'

# ---- part 5: invariants of the leading field (hand: Euler's v_2 = x d/dx + p d/dp has
# the Darboux polynomials x, p; the discrete gradient's v_3 = -g/2 keeps x^2 + p^2)
run 0 errors -H "$OSC" --scheme euler --order 3 --json
py "$VK
inv = d['invariants']
assert inv['polynomial'] == []
r = [S(s) for s in inv['rational']]
assert len(r) == 1 and (simplify(r[0] - x/p) == 0 or simplify(r[0] - p/x) == 0)"
run 0 errors -H "$OSC" --map "$DG" --order 3 --json
py "$VK
inv = d['invariants']
assert len(inv['polynomial']) == 1
c = simplify(S(inv['polynomial'][0]) / (x**2 + p**2))
assert c.is_number and c != 0"
run 0 errors -H 'p^2/2 - cos(q)' --scheme implicit-midpoint --order 3
has_text 'not a polynomial field'
run 2 errors -H "$OSC" --scheme euler --invariants-degree -1

# ---- part 6: modified Hamiltonian of velocity Verlet, H = p^2/2 + U, U = q^4/4 - q^2/2:
# by the symmetric BCH with Poisson brackets (see src/analysis/test/t-modified.c)
# H~ = H + D^2 (p^2 U''/12 - U'^2/24) + O(D^4); sympy re-derives the brackets here
run 0 errors -H 'p^2/2 + q^4/4 - q^2/2' --scheme stormer-verlet-kdk --order 4 --json
py "$VK
q = loc['q']
U = q**4/4 - q**2/2; T = p**2/2
br = lambda f, g: sympy.diff(f, q)*sympy.diff(g, p) - sympy.diff(f, p)*sympy.diff(g, q)
h3 = -br(U, br(U, T))/24 - br(T, br(U, T))/12
hs = d['modified']['hamiltonians']
assert simplify(S(hs[1])) == 0
assert sympy.expand(S(hs[2]) - h3) == 0
assert sympy.expand(h3 - (p**2*(3*q**2 - 1)/12 - (q**3 - q)**2/24)) == 0"
run 0 errors -H 'p^2/2 - cos(q)' --scheme avf --order 3 --json
py "$VK
q = loc['q']
f = sympy.Matrix([p, -sin(q)]); z = sympy.Matrix([q, p])
Jf = f.jacobian(z)
f3 = Jf*Jf*f/12          # no f''(f,f) term for the average vector field
m = d['modified']['fields'][2]
assert simplify(S(m['q']) - f3[0]) == 0 and simplify(S(m['p']) - f3[1]) == 0"

# ---- the exact rotation --------------------------------------------------------------
run 0 errors -H "$OSC" --scheme exact-rotation --order 7
has_line 'no error up to order 7 (exact to the order computed)'

# ---- bad input: exit 2 with a message ------------------------------------------------
run 2 errors -H "$OSC" --scheme no-such-scheme
grep -q "unknown scheme" "$tmp/err" && ok || bad "unknown scheme message"
run 2 errors -H "$OSC" --map 'X = x + 2*D*p; P = p - D*x'
grep -q "not consistent" "$tmp/err" && ok || bad "inconsistent message"
run 2 errors -H "$OSC" --equations '(X-x)/D = (P+p)/2'
grep -q "wrong number of equations" "$tmp/err" && ok || bad "equation count message"
run 2 errors -H "$OSC" --equations 'X^2 + 1 = D; P = p - D*x'
grep -q "not the identity at D = 0" "$tmp/err" && ok || bad "no solution at D = 0 message"
run 2 errors -H "$OSC"
run 2 errors -H "$OSC" --scheme euler --map 'X = x; P = p'
run 2 errors -H "$OSC" --scheme euler --order 1
run 2 errors -H "$OSC" --scheme euler --order 4 --correct 5
run 2 errors --scheme euler
run 0 errors --help
has_text 'usage: hamlie errors'

finish
