#!/bin/bash
# Issue 13, defect 9: command lines that used to run silently with a
# default or a wrong value, or report a bad input as a blow-up.  Each must
# now be refused: exit 2, a message that names the option or the value
# (with its position in --init), and nothing on stdout or in --out.
# usage (from the repo root): bash tests/cli/silent.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: silent.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

OSC='(p^2+q^2)/2'
KEPLER='(px^2+py^2)/2 - 1/sqrt(x^2+y^2)'

# refused: exit 2, stdout empty, stderr has TEXT
refused() {
    local text=$1
    shift
    run 2 "$@"
    if [ -s "$tmp/out" ]; then bad "stdout not empty for: hamlie $*"; sed 's/^/    /' "$tmp/out" | head -3 >&2; else ok; fi
    err_has "$text"
}

# ---- -n: the order of the truncated Lie series (0 used to mean 4) ---------
refused "--order" run -H "$OSC" --scheme lie -n 0 --dt 0.1 --t 1 --init q=1,p=0
refused "--order" run -H "$OSC" --scheme lie --order -3 --dt 0.1 --t 1 --init q=1,p=0
# an order for a scheme that has none was ignored
refused "--order" run -H "$OSC" --scheme rk4 -n 3 --dt 0.1 --t 1 --init q=1,p=0
# -n 1 is Euler's map on the oscillator: x_1 = 1, p_1 = -dt (closed form)
run 0 run -H "$OSC" --scheme lie -n 1 --dt 0.1 --t 0.1 --init q=1,p=0 --no-reference
has_line "0.1,1,-0.10000000000000001,0.505"

# ---- an option given twice with different values ---------------------------
refused "--scheme" run -H "$OSC" --scheme rk4 --scheme euler --dt 0.1 --t 1 --init q=1,p=0
refused "--dt" run -H "$OSC" --scheme rk4 --dt 0.1 --dt=0.2 --t 1 --init q=1,p=0
refused "-H" run -H "$OSC" -H 'p^2/2' --scheme rk4 --dt 0.1 --t 1 --init q=1,p=0
refused "--order" lie -H "$OSC" -n 2 --order 3
refused "--pairs" generator -H "$OSC" --pairs q:p --pairs p:q
refused "--out" plot a.csv --out d1 --out d2
# the same value twice says the same thing: accepted
run 0 run -H "$OSC" --scheme rk4 --scheme rk4 --dt 0.5 --t 1 --init q=1,p=0
# repeatable options stay repeatable
run 0 run -H "$OSC" --scheme rk4 --dt 0.5 --t 1 --init q=1,p=0 --observe q --observe p
has_line "t,q,p,H,sigma,q,p"

# ---- a fixed-step scheme without --dt (was t/1000 silently) ----------------
refused "--dt" run -H "$OSC" --scheme rk4 --t 1 --init q=1,p=0
refused "--dt" run -H "$OSC" --scheme exact --t 1 --init q=1,p=0 --json
refused "--dt" run -H "$OSC" --map 'Q = q + D*p; P = p - D*q' --t 1 --init q=1,p=0

# ---- invalid initial points --------------------------------------------------
for init in q=nan,p=0 q=inf,p=0 q=abc,p=0 q=1e400,p=0 x=1,p=0 q=1 q=1,q=2,p=0; do
    refused "in --init" run -H "$OSC" --scheme rk4 --dt 0.1 --t 1 --init "$init"
done
# the value's position: a caret under 'abc' (characters 7-9 of "q=1,p=abc")
run 2 run -H "$OSC" --scheme rk4 --dt 0.1 --t 1 --init q=1,p=abc
if grep -qxF '        ^~~' "$tmp/err"; then ok; else bad "no caret under 'abc'"; cat "$tmp/err" >&2; fi
# a point outside H's domain (Kepler at the origin) was "blow-up at step 0"
# after the CSV header: the point is named, nothing written
refused "initial point" run -H "$KEPLER" --scheme rk4 --dt 0.1 --t 1 --init x=0,y=0,px=0,py=1
if grep -q "blow-up" "$tmp/err"; then bad "still reported as a blow-up"; else ok; fi
rm -f "$tmp/k.csv"*
refused "initial point" run -H "$KEPLER" --scheme rk4 --dt 0.1 --t 1 --init x=0,y=0,px=0,py=1 --out "$tmp/k.csv"
if ls "$tmp"/k.csv* >/dev/null 2>&1; then bad "--out left a file: $(ls "$tmp"/k.csv*)"; else ok; fi
refused "initial point" run -H 'p^2/2 + log(q)' --scheme lie --tol 1e-10 --t 1 --init q=-1,p=1
refused "initial point" run -H 'p^2/2 + log(q)' --scheme lie --digits 30 --t 1 --init q=-1,p=1
refused "initial point" run -H 'p^2/2 + log(q)' --scheme rk4 --orders 0.1,0.05 --t 1 --init q=-1,p=1
# observers may have poles (x/p at p = 0): not checked
run 0 run -H "$OSC" --scheme rk4 --dt 0.5 --t 1 --init q=1,p=0 --observe "q/p"

# ---- a value that underflows in double (was read as 0) ----------------------
refused "underflows" run -H "$OSC" --scheme rk4 --dt 0.1 --t 1 --init q=1e-400,p=0
refused "underflows" run -H "$OSC" --scheme rk4 --dt 0.1 --t 1 --init 'q=10^(-400),p=0'
refused "underflows" run -H "$OSC" --scheme rk4 --dt 0.1 --t 1 --init q=1,p=-3e-320
refused "underflows" exact -H 'p^2/2 - cos(q)' --init q=1e-400,p=0
# an exact 0 and a value whose ball holds 0 (sin(pi) = 1.2e-16 in double) are fine
run 0 run -H "$OSC" --scheme rk4 --dt 0.5 --t 1 --init 'q=1,p=sin(pi)'
run 0 run -H "$OSC" --scheme rk4 --dt 0.5 --t 1 --init 'q=1,p=1-1'
# with --digits it is a valid number, kept: q(t) = 1e-400 cos t
run 0 run -H "$OSC" --scheme lie --digits 30 --dt 0.5 --t 1 --init q=1e-400,p=0
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "--digits 1e-400"; cat "$tmp/py" >&2; }
import sys, mpmath
mpmath.mp.dps = 40
rows = [l.split(",") for l in open(sys.argv[1]).read().splitlines()[1:]]
for r in rows:
    t, q = mpmath.mpf(r[0]), mpmath.mpf(r[1])
    want = mpmath.mpf("1e-400") * mpmath.cos(t)
    assert abs(q - want) <= mpmath.mpf("1e-425"), (r, want)
PYEOF

# ---- --digits with --out: the summary line, as without --digits -------------
# and plot of that CSV: the energy error from the texts, not from doubles.
# An eccentric Kepler orbit at 25 digits drifts by ~2e-25 in H ~ -0.455,
# below a double's resolution (5.6e-17 there): read as doubles it was a
# flat 0.
rm -rf "$tmp/k25.csv" "$tmp/fig"
run 0 run -H "$KEPLER" --scheme lie --digits 25 --dt 10 --t 300 --init x=1,y=0,px=0,py=0.3 --out "$tmp/k25.csv"
has_text "30 steps to t = 300, max |H - H0| = "
has_text "wrote 31 rows to $tmp/k25.csv"
cp "$tmp/out" "$tmp/summary"
run 0 plot "$tmp/k25.csv" --out "$tmp/fig" --json
python3 - "$tmp/out" "$tmp/k25.csv" "$tmp/summary" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "plot of a --digits CSV"; cat "$tmp/py" >&2; }
import json, re, sys, mpmath
mpmath.mp.dps = 50
d = json.load(open(sys.argv[1]))
lines = open(sys.argv[2]).read().splitlines()
iH = lines[0].split(",").index("H")
H = [mpmath.mpf(l.split(",")[iH]) for l in lines[1:]]
want = max(abs(h - H[0]) for h in H)
got = d["runs"][0]["max_abs_dH"]
assert want > 1e-26, want                      # the drift is there in the text
assert abs(got - want) <= 1e-9 * want, (got, want)
# the run's own max |H - H0| (in Arb, before printing) agrees to the
# printing's resolution: 25 digits of H ~ 0.455
run = float(re.search(r"max \|H - H0\| = ([0-9.e+-]+)", open(sys.argv[3]).read()).group(1))
assert abs(run - float(want)) <= 1e-25, (run, want)
PYEOF
# a double CSV: |H - H0| from the doubles, as before (Euler: 2 H_n = (1 + dt^2)^n)
run 0 run -H "$OSC" --scheme euler --dt 0.1 --t 1 --init q=1,p=0 --out "$tmp/e.csv"
run 0 plot "$tmp/e.csv" --out "$tmp/fig" --json
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "plot of a double CSV"; cat "$tmp/py" >&2; }
import json, sys
got = json.load(open(sys.argv[1]))["runs"][0]["max_abs_dH"]
want = (1.01 ** 10 - 1) / 2
assert abs(got - want) <= 1e-15, (got, want)
PYEOF


# ---- a constant on a discontinuity: said so, not "not finite" ------------
# sin(pi) is 0 only in exact arithmetic; atan2 jumps there (pi or -pi)
refused "discontinuity" run -H 'p^2/2 + atan2(sin(pi),-1)*q^2' --scheme rk4 --dt 0.1 --t 1 --init q=1,p=0
# exactly on the cut's upper side the constant is pi (H = pi at q=1, p=0)
run 0 run -H 'p^2/2 + atan2(0,-1)*q^2' --scheme rk4 --dt 0.1 --t 0.1 --init q=1,p=0 --no-reference
has_line "0,1,0,3.1415926535897931"
finish

