#!/bin/bash
# Large printed results (issue 17, part 5: the printers were rewritten for
# speed, and must print the same mathematics).  Hénon–Heiles to order 12 and
# Kepler to order 8: the text, JSON series and JSON coefficients of `hamlie
# lie` are read back by SymPy and must agree with each other, and the
# coefficients with g^k z / k! computed by SymPy itself (polynomials: exact
# expand; Kepler: at random rational points to 60 digits).
# usage (from the repo root): bash tests/cli/print-big.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: print-big.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
if ! "$PY" -c 'import sympy, mpmath' 2>/dev/null; then
    echo "SKIP: python3 with sympy and mpmath not found"
    exit 0
fi

# check NAME H ORDER KIND K_PEER: the text and JSON outputs of hamlie lie,
# against each other and (to order K_PEER) against SymPy's Lie series.
check() {
    local name=$1 H=$2 order=$3 kind=$4 peer=$5
    run 0 lie -H "$H" --order "$order" --json
    cp "$tmp/out" "$tmp/$name.json"
    run 0 lie -H "$H" --order "$order"
    cp "$tmp/out" "$tmp/$name.txt"
    # the sanitizer build prints the same (harness.sh): SymPy's reading, 15 s, is the normal build's
    [ "$HL_SANITIZED" = 1 ] && return
    if "$PY" - "$tmp/$name.json" "$tmp/$name.txt" "$H" "$kind" "$peer" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "$name: printed forms disagree"; sed 's/^/    /' "$tmp/py" >&2; fi
import json, random, sys
import sympy as sp
from mpmath import mp, mpf
d = json.load(open(sys.argv[1]))
text = open(sys.argv[2], encoding="utf-8").read().splitlines()
H_text, kind, peer = sys.argv[3], sys.argv[4], int(sys.argv[5])
sy = d["symbols"]
qs, ps = sy["coordinates"], sy["momenta"]
loc = {n: sp.Symbol(n) for n in qs + ps + [sy["step"]]}
S = lambda s: sp.sympify(s.replace("^", "**"), locals=loc)
D = loc[sy["step"]]
Q, P = [loc[n] for n in qs], [loc[n] for n in ps]
H = S(H_text)
mp.dps = 60
rng = random.Random(7)
points = [{v: sp.Rational(rng.randint(3, 40), rng.randint(3, 40)) * rng.choice([-1, 1])
           for v in Q + P + [D]} for _ in range(3)]

def equal(a, b):
    if kind == "poly":
        return sp.expand(a - b) == 0
    for pt in points:
        x, y = sp.N(a.subs(pt), 60), sp.N(b.subs(pt), 60)
        if abs(x - y) > sp.Float(10, 60) ** -45 * (1 + abs(x)):
            return False
    return True

order = d["order"]
assert len(d["series"]) == len(text) == len(Q) + len(P), (len(d["series"]), len(text))
for item, line in zip(d["series"], text):
    z = loc[item["input"]]
    coeffs = [S(c) for c in item["coefficients"]]
    series = S(item["series"])
    # the JSON series is the sum of its coefficients
    assert equal(series, sum(c * D**k for k, c in enumerate(coeffs))), item["input"]
    # the text line says the same
    head, rest = line.split(" = ", 1)
    assert head.endswith(" " + item["input"]), head
    tail = " + O(%s^%d)" % (sy["step"], order + 1)
    assert rest.endswith(tail), rest[-30:]
    assert equal(S(rest[: -len(tail)]), series), item["input"] + " (text)"
    # SymPy's own g^k z / k!, g(f) = {f, H}
    term = z
    for k in range(peer + 1):
        assert equal(coeffs[k], term / sp.factorial(k)), "%s: D^%d" % (item["input"], k)
        term = sum(sp.diff(term, q) * sp.diff(H, p) - sp.diff(term, p) * sp.diff(H, q)
                   for q, p in zip(Q, P))
        term = sp.expand(term) if kind == "poly" else sp.cancel(term)
print("ok")
PYEOF
}

check henon-heiles '(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3' 12 poly 12
check kepler '(px^2+py^2)/2-1/sqrt(x^2+y^2)' 8 sqrt 4

# LaTeX of the same series: one line per coordinate, every D power present
run 0 lie -H '(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3' --order 12 --latex
if [ "$(grep -c 'D^{12}' "$tmp/out")" -eq 4 ] && [ "$(wc -l <"$tmp/out")" -eq 4 ]; then ok; else
    bad "latex: want 4 lines each with D^{12}"; head -c 400 "$tmp/out" >&2
fi

finish
