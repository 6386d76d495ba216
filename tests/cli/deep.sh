#!/bin/bash
# Deep and large formulas (issue 13, defect 5) at the default 8 MiB stack:
# what is computable gives the right result, what is not is refused with
# exit 2 and a message; never a signal.  Truths: a run of 2k minuses is the
# identity, a sum of n copies of x is n*x, brackets of the identity map.
# usage (from the repo root): bash tests/cli/deep.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: deep.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
ulimit -s 8192

minuses() { python3 -c "print('-' * $1, end='')"; }
copies() { python3 -c "print('$2'.join(['$1'] * $3), end='')"; }

# ---- a long run of unary minuses is +x or -x ---------------------------------
run 0 generator -H "$(minuses 65000)x + p^2" --json
py 'g = d["generator"]; assert same(g["x"], "2*p") and same(g["p"], "-1"), g'
run 0 generator -H "$(minuses 65001)x + p^2" --json
py 'g = d["generator"]; assert same(g["x"], "2*p") and same(g["p"], "1"), g'

# ---- flat sums: 60,000 terms, and 25,000 mixed powers ------------------------
run 0 generator -H "$(copies x + 60000) + p^2" --json
py 'g = d["generator"]; assert same(g["p"], "-60000"), g'
H=$(python3 -c "print('+'.join(f'x^{i % 4}' for i in range(25000)), end='')")
run 0 generator -H "$H - p^2" --json
# 6250 copies of each of 1, x, x^2, x^3: dH/dx = 6250 (1 + 2 x + 3 x^2)
py 'g = d["generator"]; assert same(g["p"], "-6250*(1 + 2*x + 3*x**2)") and same(g["x"], "-2*p"), g'

# ---- a 60,000-term sum compiled for a run: (60000 x)^2/7.2e9 = x^2/2 --------
run 0 run -H "p^2/2 + ($(copies x + 60000))^2/7200000000" --scheme lie --tol 1e-12 --t 1 \
    --init x=1,p=0
python3 - "$tmp/out" <<'PYEOF' && ok || bad "run of the 60,000-term oscillator: not (cos 1, -sin 1)"
import csv, math, sys
rows = list(csv.reader(open(sys.argv[1])))
t, x, p = (float(v) for v in rows[-1][:3])
assert t == 1 and abs(x - math.cos(1)) < 1e-10 and abs(p + math.sin(1)) < 1e-10, rows[-1]
PYEOF

# ---- canonical --map with 40,000 minuses or terms ---------------------------
run 0 canonical --map "X = $(minuses 40000)x; P = p"
has_line 'canonical for every D'
run 1 canonical --map "X = $(minuses 40001)x; P = p"
run 0 canonical --map "X = $(copies x + 40000) - 39999*x; P = p"
has_line 'canonical for every D'

# ---- nesting: one limit, one message, with its position ----------------------
run 2 generator -H "$(python3 -c "print('(' * 201 + 'x' + ')' * 201, end='')") + p^2"
err_has 'formula nested too deeply (limit 200) at position 201'
run 2 canonical --map "X = x; P = $(python3 -c "print('sin(' * 201 + 'p' + ')' * 201, end='')")"
err_has 'formula nested too deeply (limit 200)'
run 0 generator -H "$(python3 -c "print('(' * 199 + 'x' + ')' * 199, end='')") + p^2"
has_line '𝔤 = 2*p ∂/∂x − ∂/∂p'

# ---- a large result prints (without recursion): 123,410 terms --------------
# dH/dpx of (x+y+px+py+1)^N at x=1, y=2, px=3, py=-1 is N*6^(N-1), evaluated
# term by term in exact integers (too long for sympify or Python's parser);
# its binomial(N+3, 4) terms.  N = 40, and 24 (17,550 terms) under the
# sanitizers, where 40 costs 15 CPU seconds of CI's twenty minutes
N=40
ldd "$HAMLIE" 2>/dev/null | grep -q libasan && N=24
run 0 generator -H "(x+y+px+py+1)^$N" --json
py "
import re
from math import comb
N = $N
def value(poly, at):
    assert '(' not in poly
    total = 0
    for sign, term in re.findall(r'(^-?|[+-] )([^ ]+)', poly):
        v = -1 if sign.strip() == '-' else 1
        for f in re.split(r'(?<!\*)\*(?!\*)', term):
            base, _, k = f.partition('**')
            v *= (int(base) if base.isdigit() else at[base]) ** int(k or 1)
        total += v
    return total
at = {'x': 1, 'y': 2, 'px': 3, 'py': -1}
g = d['generator']
assert len(re.findall(r' [+-] ', g['x'])) + 1 == comb(N + 3, 4)
assert value(g['x'], at) == N * 6**(N - 1) and value(g['px'], at) == -N * 6**(N - 1)
"

# ---- a result too large to print is said to be so ----------------------------
# a power tower: its Lie series written out is 14 million terms and operators,
# three times the limit (a tower of 20, 62 million, cost 4 CPU s a format
# here, three times that under the sanitizers)
TOWER="$(python3 -c "print('x^-' * 16 + '(p^2+x^2)', end='')")"
for fmt in "" --latex --json; do
    run 2 lie -H "$TOWER" --order 3 $fmt
    err_has 'hamlie: error: result too large to print: '
    [ -s "$tmp/out" ] && bad "lie $fmt: output written before the refusal" || ok
done
run 0 lie -H "$(python3 -c "print('x^-' * 3 + '(p^2+x^2)', end='')")" --order 2

finish
