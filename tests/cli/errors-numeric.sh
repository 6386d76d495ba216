#!/bin/bash
# hamlie errors --numeric --at: the error fields v_k(z) and K(D)'s
# coefficients at a point, by Taylor mode in double precision, checked
# against the symbolic analysis of the same command (sympy evaluates its
# formulas at the point), a hand derivation, the textbook orders, and bad
# input (exit 2, nothing on stdout, a message naming the problem).
# usage (from the repo root): bash tests/cli/errors-numeric.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: errors-numeric.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PEND='p^2/2 - cos(q)'
HH='(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3'

# compare NAME args...: numeric and symbolic JSON of the same analysis agree
# at the point to 1e-12 relative (plus round-off k! 1e-14 for zero fields).
compare() {
    local at=$1
    shift
    "$HAMLIE" errors "$@" --invariants-degree 0 --json >"$tmp/sym" 2>"$tmp/err" || { bad "symbolic $*"; return; }
    run 0 errors "$@" --numeric --at "$at" --json
    compared=$((compared + 1)) # py runs at finish: a file of its own for each
    cp "$tmp/sym" "$tmp/sym$compared.json"
    py "
import math
s = json.load(open('$tmp/sym$compared.json'))
pt = {Symbol(k): v for k, v in d['at'].items()}
ev = lambda f: float(S(f).subs(pt).evalf(30))
for fs, fn in zip(s['fields'], d['fields']):
    k = fs['k']; assert fn['k'] == k
    vs = {n: ev(f) for n, f in fs['v'].items()}
    big = max(abs(x) for x in vs.values())
    for n, x in vs.items():
        assert abs(fn['v'][n] - x) <= 1e-12 * big + 1e-14 * math.factorial(k) * 10, (k, n, fn['v'][n], x)
for k, (ks, kn) in enumerate(zip(s['K_coefficients'], d['K_coefficients'])):
    for n, f in ks.items():
        x = ev(f)
        assert abs(kn[n] - x) <= 1e-12 * max(1, abs(x)) * (k + 1), ('K', k, n, kn[n], x)
assert len(d['K_coefficients']) == len(s['K_coefficients'])
assert d['order'] == s['order'], (d['order'], s['order'])
"
}

compared=0
compare 'q=1.3,p=0.2' -H "$PEND" --scheme rk4 --order 6
compare 'q=-0.4,p=0.9' -H "$PEND" --scheme gauss2 --order 5
compare 'x=0.1,y=-0.3,px=0.25,py=0.4' -H "$HH" --scheme implicit-midpoint --order 4
compare 'x=0.2,y=0.1,px=-0.3,py=0.5' -H "$HH" --order 4 \
    --equations '(X-x)/D = (PX+px)/2; (Y-y)/D = (PY+py)/2; (PX-px)/D = -(x+X)/2 - (x+X)*(y+Y)/2; (PY-py)/D = -(y+Y)/2 - (x+X)^2/4 + (y+Y)^2/4'
compare 'q=0.7,p=-0.1' -H "$PEND" --map 'Q = q + D*p; P = p - D*sin(Q)' --order 5

# by hand: explicit Euler on the oscillator, psi = (q + D p, p - D q); the
# flow has g z = (p, -q), g^2 z = -z, g^3 z = (-p, q), and psi has no D^k term for
# k >= 2, so v_k = -g^k z: v_2 = (q, p), v_3 = (p, -q)
run 0 errors -H '(p^2+q^2)/2' --scheme euler --order 3 --numeric --at 'q=0.3,p=0.7' --json
py "
v2 = d['fields'][0]['v']; v3 = d['fields'][1]['v']
assert abs(v2['q'] - 0.3) < 1e-15 and abs(v2['p'] - 0.7) < 1e-15, v2
assert abs(v3['q'] - 0.7) < 1e-15 and abs(v3['p'] + 0.3) < 1e-15, v3
assert d['order'] == 1 and d['leading'] == 2
"

# textbook orders at a point
for so in euler:1 symplectic-euler-a:1 stormer-verlet-kdk:2 implicit-midpoint:2 rk4:4 gauss2:4 gauss3:6 avf:2 yoshida4:4; do
    run 0 errors -H "$HH" --scheme "${so%%:*}" --order 8 --numeric --at 'x=0.1,y=-0.2,px=0.3,py=0.25'
    has_text "order: ${so##*:} (leading error v_$(( ${so##*:} + 1 ))"
done

# bad input
bad_input() {
    local piece=$1
    shift
    "$HAMLIE" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -eq 2 ] && [ ! -s "$tmp/out" ] && grep -qF -- "$piece" "$tmp/err"; then ok; else
        bad "hamlie $*: exit $rc (want 2), stdout $(wc -c <"$tmp/out") bytes, stderr:"
        sed 's/^/    /' "$tmp/err" >&2
    fi
}
bad_input "--numeric needs the point" errors -H "$PEND" --scheme rk4 --numeric
bad_input "no value for 'p'" errors -H "$PEND" --scheme rk4 --numeric --at 'q=1.3'
bad_input "not a number: 'abc'" errors -H "$PEND" --scheme rk4 --numeric --at 'q=abc,p=0'
bad_input "not a number: ''" errors -H "$PEND" --scheme rk4 --numeric --at 'q=,p=0'
bad_input "'z' is not a phase variable" errors -H "$PEND" --scheme rk4 --numeric --at 'q=1,p=0,z=2'
bad_input "given twice" errors -H "$PEND" --scheme rk4 --numeric --at 'q=1,p=0,q=2'
bad_input "add --numeric" errors -H "$PEND" --scheme rk4 --at 'q=1,p=0'
bad_input "--order must be between 2 and 60" errors -H "$PEND" --scheme rk4 --numeric --at 'q=1,p=0' --order 61
bad_input "not a number" errors -H "$PEND" --scheme rk4 --numeric --at 'q=1e999,p=0'

finish
