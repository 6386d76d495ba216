#!/bin/bash
# hamlie errors --scheme exact for an H whose exact scheme is numeric (the
# 1-dof orbit table of exact.h): analysed at a point from the scheme's own
# series; no error field above round-off, K not computed; the flow of a
# wrong H would be seen (exact/t-series); bad points and a missing
# --numeric are clear errors (exit 2, nothing on stdout).
# usage (from the repo root): bash tests/cli/errors-exact.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: errors-exact.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PEND='p^2/2 - cos(q)'

# the pendulum at the turning point and mid-orbit, text and JSON
run 0 errors -H "$PEND" --scheme exact --numeric --at q=1.3,p=0 --order 8
has_line "order: at least 8 (no v_k above round-off up to k = 8)"
has_line "K(D): not computed (it needs the scheme at other points than z)"
run 0 errors -H "$PEND" --scheme exact --numeric --at q=0.9,p=0.64 --order 20 --json
py "
assert d['mode'] == 'numeric' and d['scheme']['name'] == 'exact'
assert d['exact_to_order_computed'] is True and d['order'] == 20 and d['leading'] is None
assert all(not f['nonzero'] and f['norm'] <= f['threshold'] for f in d['fields'])
assert all(v is None for k in d['K_coefficients'] for v in k.values())
# the flow's own coefficients: [D^1] = (p, -sin q)
import math
f1 = d['flow_coefficients'][1]
assert abs(f1['q'] - 0.64) < 1e-15 and abs(f1['p'] + math.sin(0.9)) < 1e-15
"
# Morse and the quartic oscillator
run 0 errors -H 'p^2/2 + (1 - exp(-q))^2' --scheme exact --numeric --at q=0.5,p=0.3 --order 12
has_line "order: at least 12 (no v_k above round-off up to k = 12)"
run 0 errors -H 'p^2/2 + q^4/4' --scheme exact --numeric --at q=0.2,p=0.9 --order 12
has_line "order: at least 12 (no v_k above round-off up to k = 12)"

# errors: no --numeric, a separatrix point, a rotation
run 2 errors -H "$PEND" --scheme exact
err_has "the exact scheme of this H is numeric"
err_has "--numeric --at 'q=...,p=...'"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
run 2 errors -H "$PEND" --scheme exact --numeric --at q=0,p=2
err_has "the exact scheme"
run 2 errors -H "$PEND" --scheme exact --numeric --at q=0,p=3
err_has "the exact scheme"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
finish
