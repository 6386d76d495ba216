#!/bin/bash
# hamlie errors --scheme exact for an H whose exact scheme is numeric (the
# 1-dof orbit table of exact.h): analysed at a point from the scheme's own
# series (the table's piece re-expanded at the point's time); no error
# field above round-off up to order 8, K not computed; orders beyond 8 (the
# pieces' truncation shows there), a missing --numeric and a separatrix
# point are clear errors (exit 2, nothing on stdout).  That the
# check can fail: a wrong step (the flow of 1.001 H) is seen at k = 2 in
# exact/t-series.
# usage (from the repo root): bash tests/cli/errors-exact.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: errors-exact.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PEND='p^2/2 - cos(q)'

# the pendulum at the turning point and mid-orbit, text and JSON
run 0 errors -H "$PEND" --scheme exact --at q=1.3,p=0 --order 8 --numeric
has_line "scheme: exact"
has_line "order: at least 8 (no v_k above round-off up to k = 8)"
has_line "K(D): not computed (it needs the scheme at other points than z)"
run 0 errors -H "$PEND" --scheme exact --numeric --at q=1.3,p=0 --order 8 --json
py "
assert d['mode'] == 'numeric' and d['scheme']['name'] == 'exact'
assert d['exact_to_order_computed'] is True and d['order'] == 8 and d['leading'] is None
"
run 0 errors -H "$PEND" --scheme exact --numeric --at q=0.9,p=0.64 --order 8 --json
py "
assert d['exact_to_order_computed'] is True and d['order'] == 8 and d['leading'] is None
assert len(d['fields']) == 7
assert all(not f['nonzero'] and f['norm'] <= 1e-3 * f['threshold'] for f in d['fields'])
assert all(v is None for k in d['K_coefficients'] for v in k.values())
# the flow's own coefficients, by hand: [D^1] = (p, -sin q), [D^2] = (-sin q, -p cos q)/2
import math
f1, f2 = d['flow_coefficients'][1], d['flow_coefficients'][2]
assert abs(f1['q'] - 0.64) < 1e-15 and abs(f1['p'] + math.sin(0.9)) < 1e-15
assert abs(f2['q'] + math.sin(0.9) / 2) < 1e-15 and abs(f2['p'] + 0.64 * math.cos(0.9) / 2) < 1e-15
"
# the default order (4), Morse and the quartic oscillator
run 0 errors -H "$PEND" --scheme exact --numeric --at q=-0.4,p=1.1
has_line "order: at least 4 (no v_k above round-off up to k = 4)"
run 0 errors -H 'p^2/2 + (1 - exp(-q))^2' --scheme exact --numeric --at q=0.5,p=0.3 --order 8
has_line "order: at least 8 (no v_k above round-off up to k = 8)"
run 0 errors -H 'p^2/2 + q^4/4' --scheme exact --numeric --at q=0.2,p=0.9 --order 8
has_line "order: at least 8 (no v_k above round-off up to k = 8)"
# q = 0 of the quartic: the flow's [D^2], [D^3] vanish there (parity), the
# table's are round-off; not an error (the thresholds follow the
# neighbouring orders, numerr.h)
run 0 errors -H 'p^2/2 + q^4/4' --scheme exact --numeric --at q=0,p=1 --order 8
has_line "order: at least 8 (no v_k above round-off up to k = 8)"

# errors: no --numeric, an order beyond the table's accuracy, a separatrix
# point; a rotation is analysed (an exact scheme: no error to order 8)
run 2 errors -H "$PEND" --scheme exact
err_has "the exact scheme of this H is numeric"
err_has "--numeric --at 'q=...,p=...'"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
run 2 errors -H "$PEND" --scheme exact --numeric --at q=1.3,p=0 --order 9
err_has "--order at most 8, not 9"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
run 2 errors -H "$PEND" --scheme exact --numeric --at q=0,p=2
err_has "the exact scheme: separatrix"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
run 0 errors -H "$PEND" --scheme exact --numeric --at q=0,p=3 --order 8 --json
py "
assert d['exact_to_order_computed'] is True and d['order'] == 8 and d['leading'] is None
"
finish
