#!/bin/bash
# hamlie exact --action-angle and --steps in all four quadrants (issue 13,
# defect 3): the printed exact scheme, read back by SymPy and evaluated by
# mpmath at points in every quadrant and on the axes (turning points p = 0,
# the cut x = 0, p < 0 of atan2(x, p)), against the rotation solved by hand,
# X = x cos wD + p/(m w) sin wD, P = p cos wD - m w x sin wD.  The paper's
# angle atan(x/p) is right for p > 0 only: the check must refuse it (exit 1)
# and name a point where the inverse fails.
# usage (from the repo root): bash tests/cli/exact-quadrants.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: exact-quadrants.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

# rotation HEADER M K Q P: the two lines after HEADER in the last output are
# the scheme's images of (Q, P); compare them with the flow of
# H = P^2/(2M) + K Q^2/2 at points in every quadrant and on the axes
rotation() {
    if python3 - "$tmp/out" "$@" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "rotation $*"; sed 's/^/    /' "$tmp/py" >&2; fi
import sys, sympy, mpmath
out, header, m, k, qn, pn = sys.argv[1:7]
lines = open(out).read().splitlines()
i = lines.index(header)
q, p, D = sympy.symbols(f"{qn} {pn} D")
img = []
for line in lines[i + 1:i + 3]:
    lhs, rhs = line.split(" = ", 1)
    img.append(sympy.lambdify((q, p, D), sympy.sympify(rhs.replace("^", "**"),
                              locals={qn: q, pn: p, "D": D}), "mpmath"))
m, k = mpmath.mpf(m), mpmath.mpf(k)
w = mpmath.sqrt(k / m)
pts = [(0.7, 0.4), (-0.6, 0.9), (-0.8, -0.5), (0.3, -1.1),  # the four quadrants
       (0.0, 1.0), (0.0, -0.7), (0.9, 0.0), (-0.8, 0.0)]    # the axes
worst = 0
for x0, p0 in pts:
    for d in (0.5, 2.0, -3.1):
        x0, p0, d = mpmath.mpf(x0), mpmath.mpf(p0), mpmath.mpf(d)
        X = x0 * mpmath.cos(w * d) + p0 / (m * w) * mpmath.sin(w * d)
        P = p0 * mpmath.cos(w * d) - m * w * x0 * mpmath.sin(w * d)
        err = max(abs(img[0](x0, p0, d) - X), abs(img[1](x0, p0, d) - P))
        assert err < 1e-12, f"at ({x0}, {p0}), D = {d}: {err}"
        worst = max(worst, err)
print("max deviation", worst)
PYEOF
}

OSC='(p^2+x^2)/2'
MAP2='I = (x^2+p^2)/2; x = sqrt(2*I)*sin(theta); p = sqrt(2*I)*cos(theta); nu = 1'
AAHEAD='exact scheme Q = q(theta + nu D, I), P = p(theta + nu D, I):'

# the paper's angle atan(x/p) is the inverse for p > 0 only: refused
run 1 exact -H "$OSC" --action-angle "theta = atan(x/p); $MAP2"
has_text 'action-angle map rejected: the inverse fails'
# atan2(x, p): verified in every quadrant, and the scheme is the rotation
run 0 exact -H "$OSC" --action-angle "theta = atan2(x, p); $MAP2"
has_text 'action-angle map verified'
rotation "$AAHEAD" 1 1 x p
# frequency 2 and another pair of names
run 0 exact -H '(p^2+4*q^2)/2' --action-angle \
    'theta = atan2(2*q, p); I = (p^2+4*q^2)/4; q = sqrt(I)*sin(theta); p = 2*sqrt(I)*cos(theta); nu = 2'
rotation "$AAHEAD" 1 4 q p
run 1 exact -H '(p^2+4*q^2)/2' --action-angle \
    'theta = atan(2*q/p); I = (p^2+4*q^2)/4; q = sqrt(I)*sin(theta); p = 2*sqrt(I)*cos(theta); nu = 2'
has_text 'the inverse fails'

# --steps: the angle of step 4 is atan2, so the result line is the flow
# everywhere, for m = k = 1 and for other masses and stiffnesses
STEPHEAD='result: Q = r(theta(q, gamma) + nu D, gamma), P = s(...):'
run 0 exact -H "$OSC" --steps
has_line '  theta = atan2(x, p)'
has_line 'check the action-angle map: yes'
rotation "$STEPHEAD" 1 1 x p
run 0 exact -H 'p^2/4 + 3*q^2/2' --steps
has_line 'check the action-angle map: yes'
rotation "$STEPHEAD" 2 3 q p

finish
