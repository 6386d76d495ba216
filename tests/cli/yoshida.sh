#!/bin/bash
# Yoshida's order-4 composition of Stormer-Verlet on non-separable H (zoo
# defects N1, N2 of issue 13).  Each kick of such an H is implicit; its
# value, affine in the unknown, must stay an expression over the earlier
# stages, not be put in canonical form at each stage: on a magnetic H the
# set-up took more than 30 s and 1.6 GB, and on p^2/2 + q*p it was refused
# ("a constant subexpression is not finite").  Both H are quadratic: the
# truth is exp(t A) z0 (mpmath), and the error at t = 1 must fall by
# 2^4 (within 30 %) when the step is halved.
# Its symbolic analysis on polynomial wells (defect 6): the closed-form
# map swells (degree 5^6 in q for q^6/6), so it must be left out before it
# is expanded, and the order found, 4 (Yoshida 1990), within the limit.
# usage (from the repo root): bash tests/cli/yoshida.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: yoshida.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
LIMIT=20 # seconds a call may take (generous for the sanitizer build)

# order4 NAME H PARAMS INIT A Z0: yoshida4 at D = 0.1 and 0.05 to t = 1,
# each under the time limit, against exp(A) Z0 (A, Z0: python lists)
order4() {
    local name=$1 H=$2 params=$3 init=$4 A=$5 z0=$6 dt
    for dt in 0.1 0.05; do
        timeout "$LIMIT" "$HAMLIE" run -H "$H" $params --scheme yoshida4 --dt $dt --t 1 \
            --init "$init" >"$tmp/$dt" 2>"$tmp/err"
        local rc=$?
        if [ "$rc" -eq 0 ]; then ok; else
            bad "$name: yoshida4 --dt $dt exited $rc (124: over ${LIMIT} s)"
            sed 's/^/    /' "$tmp/err" >&2
            return
        fi
    done
    if python3 - "$tmp/0.1" "$tmp/0.05" "$A" "$z0" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else
import sys, mpmath
mpmath.mp.dps = 30
exact = mpmath.expm(mpmath.matrix(eval(sys.argv[3]))) * mpmath.matrix(eval(sys.argv[4]))
def error(path):
    last = open(path).read().split("\n")[-2].split(",")
    assert abs(float(last[0]) - 1) < 1e-12, last
    return max(abs(float(last[1 + i]) - exact[i]) for i in range(len(exact)))
e1, e2 = error(sys.argv[1]), error(sys.argv[2])
print(e1, e2, e1 / e2)
assert 16 / 1.3 < e1 / e2 < 16 * 1.3 and e1 < 1e-3, (e1, e2)
PYEOF
        bad "$name: yoshida4's error does not fall as D^4:"; sed 's/^/    /' "$tmp/py" >&2
    fi
}

# a charge in a uniform magnetic field b = 2 (symmetric gauge):
# x' = px + y, y' = py - x, px' = py - x, py' = -(px + y)
order4 magnetic '((px + b*y/2)^2 + (py - b*x/2)^2)/2' '--param b=2' \
    x=-0.465819,y=0.702289,px=0.743419,py=-0.153093 \
    '[[0,1,1,0],[-1,0,0,1],[-1,0,0,1],[0,-1,-1,0]]' \
    '[-0.465819,0.702289,0.743419,-0.153093]'
# H = p^2/2 + q p: q' = p + q, p' = -p
order4 'p^2/2 + q*p' 'p^2/2 + q*p' '' q=0.3,p=0.2 '[[1,1],[0,-1]]' '[0.3,0.2]'

# errors_order4 H: hamlie errors to order 5 under the time limit, order 4
errors_order4() {
    timeout "$LIMIT" "$HAMLIE" errors -H "$1" --scheme yoshida4 --order 5 --json \
        >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -eq 0 ]; then ok; else
        bad "errors -H '$1' --scheme yoshida4 exited $rc (124: over ${LIMIT} s)"
        sed 's/^/    /' "$tmp/err" >&2
        return
    fi
    py "assert d['order'] == 4 and d['leading']['k'] == 5, d['order']"
}
errors_order4 'p^2/2 + q^6/6'
errors_order4 'p^2/2 + q^4/4'
errors_order4 '(px^2+py^2)/2 + (x^4+y^4)/4 + x^2*y^2/2'
finish
