#!/bin/bash
# Names (issue 13, defects 4, 8, 11): the order of the phase variables does
# not depend on how H is written; the step's name can be changed and is never
# taken for a parameter; the truncated Lie series of any order N is the
# scheme lieN, checked against its own definition (v_k = -g^k for k > N).
# usage (from the repo root): bash tests/cli/names.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: names.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

# same_output NAME ARGS...: the stdout of hamlie ARGS equals $tmp/want
same_as_want() {
    local what=$1
    if cmp -s "$tmp/out" "$tmp/want"; then ok; else
        bad "$what: output differs from the first writing of H:"
        diff "$tmp/want" "$tmp/out" | head -6 | sed 's/^/    /' >&2
    fi
}

# permutations FILE TERMS...: write several orderings of the terms (a sum),
# one per line, into FILE; a fixed seed so a failure repeats.  Six, and
# three under the sanitizers (the same code paths; 36 calls fewer, ~15 s)
WRITINGS=6
[ "$HL_SANITIZED" = 1 ] && WRITINGS=3
permutations() {
    local file=$1
    shift
    python3 - "$WRITINGS" "$@" >"$file" <<'PYEOF'
import random, sys
terms = sys.argv[2:]
rng = random.Random(13)
seen = []
for k in range(int(sys.argv[1])):
    t = terms[:] if k == 0 else (terms[::-1] if k == 1 else rng.sample(terms, len(terms)))
    print(" + ".join(t))
PYEOF
}

# every_writing_same FILE RUN_ARGS...: for each H in FILE, the run's CSV and
# generator/bracket outputs equal those of the first H (byte for byte).
every_writing_same() {
    local file=$1 first=1 H
    shift
    while IFS= read -r H; do
        for cmd in run generator bracket; do
            case $cmd in
            run) run 0 run -H "$H" "$@" ;;
            generator) run 0 generator -H "$H" ;;
            bracket) run 0 bracket -H "$H" "$BRACKET_A" H ;;
            esac
            if [ $first -eq 1 ]; then cp "$tmp/out" "$tmp/want.$cmd"; else
                cp "$tmp/want.$cmd" "$tmp/want"; same_as_want "$cmd with H = $H"
            fi
        done
        first=0
    done <"$file"
}

# ---- defect 8: the order of the phase variables ----------------------------
# Hénon–Heiles (2 dof, x:px, y:py): Itoh–Abe depends on the coordinate order,
# so any writing of H that changed it changes the trajectory.
permutations "$tmp/hh" 'px^2/2' 'py^2/2' 'x^2/2' 'y^2/2' 'x^2*y' '-y^3/3'
BRACKET_A='x*py - y*px + x^3'
every_writing_same "$tmp/hh" --scheme itoh-abe --dt 0.1 --t 2 --init x=0.1,y=0.2,px=0.3,py=-0.1
run 0 run -H "$(tail -1 "$tmp/hh")" --scheme itoh-abe --dt 0.1 --t 0 --init py=-0.1,px=0.3,y=0.2,x=0.1
has_line 't,x,y,px,py,H,sigma'

# 3 dof: x, y, z first in that order, whatever comes first in H.
permutations "$tmp/h3" 'pz^2/2' 'px^2/2' 'py^2/2' 'z^2' 'x^2/2' 'y^2*3/2' 'x*y*z' '-z^4/8'
BRACKET_A='z*px - x*pz + y'
every_writing_same "$tmp/h3" --scheme itoh-abe --dt 0.1 --t 1 --init x=0.3,y=-0.2,z=0.1,px=0,py=0.1,pz=-0.2
run 0 run -H "$(tail -1 "$tmp/h3")" --scheme euler --dt 0.1 --t 0 --init x=0.3,y=-0.2,z=0.1,px=0,py=0.1,pz=-0.2
has_line 't,x,y,z,px,py,pz,H,sigma'

# FPU-alpha chain q1..q10, fixed ends: indices sorted as numbers (q10 last).
fpu_terms() {
    for i in $(seq 1 10); do printf "p$i^2/2\n"; done
    printf "q1^2/2\nq10^2/2\n"
    for i in $(seq 1 9); do printf "(q$((i + 1))-q$i)^2/2 + (q$((i + 1))-q$i)^3/4\n"; done
}
mapfile -t FPU < <(fpu_terms)
permutations "$tmp/fpu" "${FPU[@]}"
BRACKET_A='q10*p1 + q2*p9'
init=$(for i in $(seq 1 10); do printf "q$i=0.$((i % 7)),p$i=-0.0$i,"; done)
every_writing_same "$tmp/fpu" --scheme itoh-abe --dt 0.05 --t 0.5 --init "${init%,}"
run 0 run -H "$(tail -1 "$tmp/fpu")" --scheme euler --dt 0.1 --t 0 --init "${init%,}"
has_line "t,$(seq -s, -f 'q%g' 1 10),$(seq -s, -f 'p%g' 1 10),H,sigma"

# Other names: sorted by name; momenta follow their coordinates.
permutations "$tmp/ab" 'pb^2/2' 'pa^2' 'a^2*b^2' 'b^4' 'a^2/2'
BRACKET_A='a*pb'
every_writing_same "$tmp/ab" --scheme itoh-abe --dt 0.1 --t 1 --init a=0.5,b=0.1,pa=0,pb=0.2
run 0 run -H "$(tail -1 "$tmp/ab")" --scheme euler --dt 0.1 --t 0 --init a=0.5,b=0.1,pa=0,pb=0.2
has_line 't,a,b,pa,pb,H,sigma'

# Given pairs keep their order.
run 0 run -H "$(head -1 "$tmp/hh")" --pairs y:py,x:px --scheme euler --dt 0.1 --t 0 --init x=1,y=0,px=0,py=0
has_line 't,y,x,py,px,H,sigma'

# ---- defect 11: the truncated Lie series lieN ------------------------------
# The scheme psi_D z = sum_{k<=N} D^k/k! g^k z differs from the exact flow
# exp(D g) z = sum_k D^k/k! g^k z by -sum_{k>N} D^k/k! g^k z, so (v_k being
# the coefficient fields of psi_D - exp(D g), as errors prints them)
# v_k = 0 for k <= N and v_k = -g^k z for k > N.  g^k z computed here by
# SymPy from g f = {f, H}.
PEND='p^2/2 - cos(q)'
lie_fields_check='
from sympy import diff, symbols, cos
q, p = symbols("q p")
H = p**2/2 - cos(q)
def g(f): return diff(f, q)*diff(H, p) - diff(f, p)*diff(H, q)
def gk(f, k):
    for _ in range(k): f = g(f)
    return f
fields = {x["k"]: x["v"] for x in d["fields"]}
assert sorted(fields) == list(range(2, n + 1)), sorted(fields)
for k, v in fields.items():
    for name, z in (("q", q), ("p", p)):
        want = 0 if k <= N else -gk(z, k)
        assert simplify(S(v[name]) - want) == 0, (k, name, v[name], want)
assert d["order"] == N, d["order"]
assert d["scheme"]["name"] == "lie%d" % N, d["scheme"]'
for N in 3 1 6; do
    n=$((N + 2))
    run 0 errors -H "$PEND" --scheme lie$N --order $n --json
    py "N = $N; n = $n
$lie_fields_check"
done
# lie1 is explicit Euler: the same fields
run 0 errors -H "$PEND" --scheme lie1 --order 4 --json
py 'import json; json.dump(d["fields"], open("'"$tmp"'/lie1.json", "w"))'
run 0 errors -H "$PEND" --scheme euler --order 4 --json
py 'import json; e = json.load(open("'"$tmp"'/lie1.json"))
assert all(same(a["v"][c], b["v"][c]) for a, b in zip(e, d["fields"]) for c in "qp"), (e, d["fields"])'

# observed order 6 of lie6 from three steps (the reference is the adaptive
# Taylor integrator at 1e-15; errors here are 1e-6 .. 1e-10)
run 0 run -H "$PEND" --scheme lie6 --dt 0.4 --t 4 --init q=1.3,p=0 --orders 0.4,0.2,0.1 --json
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "lie6 observed order"; cat "$tmp/py" >&2; }
import json, sys
d = json.load(open(sys.argv[1]))
orders = [o["order"] for o in d["orders"][1:]]
assert all(abs(o - 6) < 0.3 for o in orders), d["orders"]
PYEOF
# --scheme lie -n 6 --dt is the same scheme
run 0 run -H "$PEND" --scheme lie6 --dt 0.1 --t 1 --init q=1.3,p=0
cp "$tmp/out" "$tmp/want"
run 0 run -H "$PEND" --scheme lie -n 6 --dt 0.1 --t 1 --init q=1.3,p=0
same_as_want "--scheme lie -n 6 against --scheme lie6"

# the listing names the family once, with its range
run 0 schemes
if [ "$(grep -c '^lie' "$tmp/out")" -eq 1 ]; then ok; else bad "schemes lists lie more than once"; fi
has_text 'lie1 (explicit Euler)'
run 0 schemes --json
py2() { python3 -c "import json,sys; d=json.load(open('$tmp/out')); $1" && ok || bad "schemes --json: $1"; }
py2 'e=[s for s in d["schemes"] if s["name"]=="lieN"][0]; assert e["order_range"]==[1,20] and e["order"] is None, e'

# out of the range, or not a number: refused, with the range
# (run --scheme lie alone is the adaptive integrator, or lie -n N with --dt)
for bad_name in lie0 lie21 lie99 lieX lie; do
    run 2 errors -H "$PEND" --scheme $bad_name --order 3
    err_has "N = 1..20"
    [ $bad_name = lie ] && continue
    run 2 run -H "$PEND" --scheme $bad_name --dt 0.1 --t 1 --init q=1,p=0 --orders 0.1,0.05
    err_has "N = 1..20"
done
run 2 run -H "$PEND" --scheme lie6 -n 3 --dt 0.1 --t 1 --init q=1,p=0
err_has "--scheme lie6"

# ---- defect 4: the step's name ----------------------------------------------
# Textbooks name the Morse depth D.  With the step named D (the default) a D
# in H is refused, pointing at it; --step h frees the name.
MORSE='p^2/2 + D*(1-exp(-q))^2'
for cmd in lie generator check; do
    case $cmd in
    lie) run 2 lie -H "$MORSE" --order 2 ;;
    generator) run 2 generator -H "$MORSE" ;;
    check) run 2 check -H "$MORSE" --integral 'p' ;;
    esac
    err_has "'D' is the step's name"
    err_has "--step h"
    if grep -qxF '          ^' "$tmp/err"; then ok; else bad "$cmd: caret not under the D of H"; cat "$tmp/err" >&2; fi
    [ -s "$tmp/out" ] && bad "$cmd wrote output on an error" || ok
done
# nor in a function of the phase variables
run 2 check -H 'p^2/2 + q^2/2' --integral 'p*q + D'
err_has "'D' is the step's name"
run 2 lie -H "$PEND" --order 2 --of 'p + D*q'
err_has "'D' is the step's name"
run 2 bracket -H "$PEND" 'q*D' p
err_has "'D' is the step's name"

# --step h: D is a parameter.  exp(h g) z to h^2 against SymPy:
# q + h p - h^2/2 V'(q),  p - h V'(q) - h^2/2 p V''(q),  V = D (1 - e^-q)^2
run 0 lie -H "$MORSE" --step h --order 2 --json
py 'from sympy import exp, diff
q, p, h, D = (Symbol(n) for n in ("q", "p", "h", "D"))
assert sy["step"] == "h" and sy["parameters"] == ["D"], sy
V = D*(1 - exp(-q))**2
want = {"q": q + h*p - h**2/2*diff(V, q), "p": p - h*diff(V, q) - h**2/2*p*diff(V, q, 2)}
for s in d["series"]:
    assert simplify(S(s["series"]) - want[s["input"]]) == 0, (s, want[s["input"]])'
run 0 lie -H "$MORSE" --step h --order 2
has_text 'exp(h 𝔤) q = q + h*p'
has_text '+ O(h^3)'

# a user's map written with h, D a parameter: Euler, so v_k = -g^k z
run 0 errors -H "$MORSE" --step h --map 'Q = q + h*p; P = p - h*2*D*(1-exp(-q))*exp(-q)' --order 3 --json
py 'from sympy import exp, diff
q, p, D = Symbol("q"), Symbol("p"), Symbol("D")
H = p**2/2 + D*(1 - exp(-q))**2
def g(f): return diff(f, q)*diff(H, p) - diff(f, p)*diff(H, q)
for x in d["fields"]:
    k = x["k"]
    for name, z in (("q", q), ("p", p)):
        w = z
        for _ in range(k): w = g(w)
        assert simplify(S(x["v"][name]) + w) == 0, (k, name)
assert d["order"] == 1'
# user equations with h and --param D=2: the catalog's implicit midpoint
run 0 run -H "$MORSE" --step h --param D=2 --scheme implicit-midpoint --dt 0.1 --t 2 --init q=0.5,p=0
cp "$tmp/out" "$tmp/want"
run 0 run -H "$MORSE" --step h --param D=2 --equations '(Q-q)/h = (p+P)/2; (P-p)/h = -2*D*(1-exp(-(q+Q)/2))*exp(-(q+Q)/2)' --dt 0.1 --t 2 --init q=0.5,p=0
python3 - "$tmp/want" "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "--equations with h vs implicit-midpoint"; cat "$tmp/py" >&2; }
import sys
a = [l.split(",") for l in open(sys.argv[1]).read().split()[1:]]
b = [l.split(",") for l in open(sys.argv[2]).read().split()[1:]]
assert len(a) == len(b) == 21
assert all(abs(float(x) - float(y)) <= 1e-14 for r, s in zip(a, b) for x, y in zip(r[:3], s[:3])), (a[-1], b[-1])
PYEOF
# the name of the step changes no number
for s in rk4 gauss2 itoh-abe lie4 avf; do
    run 0 run -H "$PEND" --scheme $s --dt 0.1 --t 1 --init q=1.3,p=-0.2
    cp "$tmp/out" "$tmp/want"
    run 0 run -H "$PEND" --step dt --scheme $s --dt 0.1 --t 1 --init q=1.3,p=-0.2
    same_as_want "$s with --step dt"
done
run 1 canonical --step h --map 'X = x + h*p; P = p - h*x'
has_line '{X, P} = 1 + h^2    should be 1'
run 0 canonical --step h --map 'X = x*cos(h) + p*sin(h); P = p*cos(h) - x*sin(h)'
has_line 'canonical for every h'
run 0 run -H "$MORSE" --step h --param D=2 --scheme rk4 --dt 0.1 --t 0.2 --init q=0.5,p=0 --json
python3 -c "import json; d = json.load(open('$tmp/out')); assert d['symbols']['step'] == 'h', d['symbols']" && ok || bad "run --json: symbols.step"

run 0 exact -H '(p^2+x^2)/2' --step h
has_line 'two steps of h = one step of 2h: yes'
has_line '  P = -x*sin(h) + p*cos(h)'

# an action-angle map is of phase space alone
run 2 exact -H '(p^2+x^2)/2' --action-angle 'theta = atan(x/p) + D; I = (x^2+p^2)/2; x = sqrt(2*I)*sin(theta - D); p = sqrt(2*I)*cos(theta - D); nu = 1'
err_has "'D' is the step's name"

# what cannot be the step, or cannot use its name
run 2 lie -H "$PEND" --step sin --order 2
err_has "cannot be the step's name"
run 2 lie -H "$PEND" --step 'h 1' --order 2
err_has "must be a name"
run 2 lie -H "$MORSE" --step h --param h=2 --order 2
err_has "it is the step's name"
run 2 generator -H 'ph^2/2' --step h --pairs h:ph
err_has "it is the step's name"
run 2 errors -H "$PEND" --step h --map 'Q = q + D*p; P = p - D*sin(q)' --order 2
err_has "unknown symbol 'D'"
for cmd in schemes plot reproduce; do
    run 2 $cmd --step h
    err_has "no system options"
done

finish
