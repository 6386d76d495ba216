#!/bin/bash
# hamlie run with the adaptive Taylor integrator where Taylor coefficients
# vanish by symmetry (issue 13, defect 1: from q = 0 in a quartic well it
# took one unbounded step and reported H = 4.8e45 with exit 0), and the
# fixed-step runs that use it as their reference (--orders).
#
# Truths: energy conservation; final states from mpmath's own Taylor
# integrator (odefun) at 25 digits, computed once with
#   python3 -c "from mpmath import *; mp.dps = 25;
#     print(odefun(lambda t, z: [z[1], -z[0]**3], 0, [0, 1])(10))"
# (-z[0]**5 for the sextic; the 2-dof quartic from the origin moves on the
# line y = x/2 with u'' = -u^3, u'(0) = sqrt(5/4), x = u/sqrt(5/4)); and
# RK4's order, 4.
# usage (from the repo root): bash tests/cli/taylor-vanishing.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: taylor-vanishing.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh" # its py is replaced below: run's JSON has no symbols check
# py CODE: python with d = the last stdout as JSON and near(a, b, tol)
py() {
    if python3 - "$tmp/out" "$1" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "python check: $1"; sed 's/^/    /' "$tmp/py" >&2; fi
import json, sys
d = json.load(open(sys.argv[1]))
def near(a, b, tol):
    assert abs(a - b) < tol, (a, b, abs(a - b), tol)
exec(sys.argv[2])
PYEOF
}

Q4='p^2/2 + q^4/4'
Q6='p^2/2 + q^6/6'
Q4_2='(px^2+py^2)/2 + (x^4+y^4)/4 + x^2*y^2/2'

# ---- the reproductions of the issue ------------------------------------------
run 0 run -H "$Q4" --scheme lie --tol 1e-15 --dt 1 --t 10 --init q=0,p=1 --json
py 'near(d["H_final"], 0.5, 1e-12); assert d["taylor_steps"] > 10, d["taylor_steps"]
near(d["final_state"]["q"], -0.6399287095352511750718313, 1e-12)
near(d["final_state"]["p"], -0.9571579234851887488012049, 1e-12)'

run 0 run -H "$Q6" --scheme lie --tol 1e-12 --dt 1 --t 10 --init q=0,p=1 --json
py 'near(d["H_final"], 0.5, 1e-10); assert d["taylor_steps"] > 10, d["taylor_steps"]
near(d["final_state"]["q"], -1.148683594538233369517817, 1e-9)
near(d["final_state"]["p"], -0.4840042733356844047692585, 1e-9)'

run 0 run -H "$Q4_2" --scheme lie --tol 1e-15 --dt 1 --t 10 --init x=0,y=0,px=1,py=0.5 --json
py 'near(d["H_final"], 0.625, 1e-12); assert d["taylor_steps"] > 10, d["taylor_steps"]
z = d["final_state"]
near(z["x"], -1.036390487695418312974853, 1e-12)
near(z["y"], -0.5181952438477091564874267, 1e-12)
near(z["px"], -0.5281441132582558423205365, 1e-12)
near(z["py"], -0.2640720566291279211602682, 1e-12)'

# ---- the reference of fixed-step runs: RK4's observed order is 4 ------------
run 0 run -H "$Q4" --scheme rk4 --t 10 --init q=0,p=1 --orders 0.025,0.0125,0.00625 --json
py 'o = d["orders"]
assert all(abs(r["order"] - 4) < 0.1 and abs(r["order_final"] - 4) < 0.1 for r in o[1:]), o'

# ---- the equilibrium stays exactly where it is --------------------------------
run 0 run -H "$Q4" --scheme lie --tol 1e-15 --dt 1 --t 10 --init q=0,p=0 --json
py 'assert d["final_state"] == {"q": 0, "p": 0}, d["final_state"]; assert d["H_final"] == 0'

# ---- edges: loose tolerance, outputs farther apart than a period, t = 0 -------
run 0 run -H "$Q4" --scheme lie --tol 1e-3 --dt 1 --t 10 --init q=0,p=1 --json
py 'near(d["H_final"], 0.5, 1e-2)
near(d["final_state"]["q"], -0.6399287095352511750718313, 1e-2)'
run 0 run -H "$Q4" --scheme lie --tol 1e-15 --dt 100 --t 100 --init q=0,p=1 --json
py 'near(d["H_final"], 0.5, 1e-12)
near(d["final_state"]["q"], 0.2185510730820172342794210, 1e-11)
near(d["final_state"]["p"], 0.9994294736761303357068572, 1e-11)'
run 0 run -H "$Q4" --scheme lie --tol 1e-15 --dt 1 --t 0 --init q=0,p=1 --json
py 'assert d["final_state"] == {"q": 0, "p": 1} and d["taylor_steps"] == 0, d'

# a tolerance double cannot reach: refused before anything is written, and
# more digits are pointed to (the adaptive run and a fixed-step reference)
run 2 run -H "$Q4" --scheme lie --tol 1e-20 --dt 1 --t 10 --init q=0,p=1 --json
err_has "below double precision"
err_has "--digits 20"
if [ ! -s "$tmp/out" ]; then ok; else bad "--tol 1e-20 wrote to stdout"; fi
run 2 run -H "$Q4" --scheme rk4 --tol 1e-20 --dt 0.1 --t 1 --init q=0,p=1
if [ ! -s "$tmp/out" ]; then ok; else bad "rk4 --tol 1e-20 wrote to stdout"; fi
run 0 run -H "$Q4" --scheme lie --tol 1e-20 --digits 20 --dt 1 --t 1 --init q=0,p=1 --json

finish
