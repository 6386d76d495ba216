#!/bin/bash
# hamlie run --event: crossings of a surface.
#  - pendulum q = 0 from (1.3, 0): at T/4 + k T/2, T = 4 K(sin^2(0.65)) by
#    mpmath at 30 digits, to 1e-12; H at each crossing = 1 - cos(1.3);
#  - oscillator x = 0 upwards: 3 pi/2 + 2 pi k, p = 1, in the CSV file;
#  - a fixed-step run says its interpolant (Hermite, order 4); --event-stop;
#  - bad input: a surface that is not a formula, an unknown symbol, a
#    direction typo, --digits, an unwritable file: clear errors, nothing
#    written.
# usage (from the repo root): bash tests/cli/events.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: events.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3
PEND='p^2/2 - cos(q)'
OSC='(p^2+x^2)/2'
# pyj CODE: python asserts on d, the last stdout as JSON
pyj() {
    if $PY -c "import json, math, sys; d = json.load(open('$tmp/out'))
$1" >"$tmp/py" 2>&1; then ok; else bad "python check: $1"; sed 's/^/    /' "$tmp/py" >&2; fi
}

run 0 run -H "$PEND" --scheme lie --tol 1e-15 --t 300 --init q=1.3,p=0 --event q --json
if $PY - "$tmp/out" <<'PYEOF'; then ok; else bad "pendulum crossings against 4 K(sin^2(0.65))"; fi
import json, sys, mpmath
mpmath.mp.dps = 30
d = json.load(open(sys.argv[1]))
ev = d["event"]
assert ev["located_on"] == "taylor-polynomial" and ev["direction"] == "both", ev
T = 4 * mpmath.ellipk(mpmath.sin(mpmath.mpf('1.3') / 2) ** 2)
rows = ev["table"]
want = int((300 - T / 4) / (T / 2)) + 1
assert len(rows) == want == ev["crossings"], (len(rows), want)
H0 = -mpmath.cos(mpmath.mpf('1.3'))
worst = max(abs(mpmath.mpf(r["t"]) - (T / 4 + k * T / 2)) for k, r in enumerate(rows))
dH = max(abs(r["H"] - H0) for r in rows)
print("pendulum: %d crossings to t = 300, max |t - t_k| = %.3g, max |H - H0| = %.3g" % (len(rows), worst, dH))
assert worst < 1e-12, worst
assert dH < 1e-14, dH
assert all(abs(r["state"]["q"]) < 1e-15 for r in rows)
PYEOF

run 0 run -H "$OSC" --scheme lie --t 40 --init x=1,p=0 --event x --direction up --out "$tmp/osc.csv"
has_text "located on the Taylor integrator's step polynomials"
if $PY - "$tmp/osc.csv.events.csv" <<'PYEOF'; then ok; else bad "oscillator crossings"; fi
import csv, sys, math
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys()) == ["crossing", "t", "x", "p", "H"], rows[0].keys()
assert len(rows) == 6, len(rows)
for k, r in enumerate(rows):
    assert int(r["crossing"]) == k
    assert abs(float(r["t"]) - (1.5 + 2 * k) * math.pi) < 1e-12, r
    assert abs(float(r["p"]) - 1) < 1e-14 and abs(float(r["x"])) < 1e-15, r
PYEOF

# fixed step: the Hermite interpolant, said; --event-stop
run 0 run -H "$OSC" --scheme stormer-verlet-kdk --dt 0.01 --t 40 --init x=1,p=0 --event x=0 \
    --event-stop 3 --json
pyj 'e = d["event"]; assert e["located_on"] == "hermite-cubic" and e["interpolant_local_order"] == 4 and e["crossings"] == 3 and e["stopped"]'
pyj 'import math; t = [r["t"] for r in d["event"]["table"]]; assert all(abs(t[k] - (0.5 + k) * math.pi) < 1e-4 for k in range(3)), t'
pyj 'assert d["final_t"] < 3 * 3.1416 and d["steps"] < 1000'

# bad input
run 2 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event 'x+' --events-out "$tmp/e.csv"
err_has "in --event: expected an expression"
err_has "  x+"
[ ! -e "$tmp/e.csv" ] && ok || bad "a crossings file after a parse error"
run 2 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event 'x = y' --events-out "$tmp/e.csv"
err_has "unknown symbol 'y'"
run 2 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event x --direction upp --events-out "$tmp/e.csv"
err_has "--direction wants up, down or both, not 'upp'"
run 2 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event x --digits 30 --events-out "$tmp/e.csv"
err_has "not located by the Arb integrator"
run 2 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event x
err_has "where do the crossings go?"
run 2 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event x --events-out "$tmp/no/such/dir/e.csv" --out "$tmp/traj.csv"
err_has "cannot write"
run 2 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event 1 --events-out "$tmp/e.csv"
err_has "never crossed"
# a surface never crossed is no error for a run: zero crossings, said
run 0 run -H "$OSC" --scheme lie --t 10 --init x=1,p=0 --event 'x - 5' --events-out "$tmp/e.csv" --out "$tmp/t.csv"
has_text "0 crossings of x - 5"
[ "$(wc -l <"$tmp/e.csv")" -eq 1 ] && ok || bad "the empty crossings table has its header only"
finish
