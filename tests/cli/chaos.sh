#!/bin/bash
# hamlie chaos: the inverted oscillator p^2/2 - q^2/2 from delta0 = (1, 0),
# where |delta|^2 = cosh 2t and r = tanh 2t: the CSV of --every against
# mpmath (mLCE = log(cosh 2t)/(2t), Y = (2/t) int s tanh 2s, <Y> by the
# swapped double integral); the pendulum's <Y> near 2 (--json); a chaotic
# Henon-Heiles orbit (E = 1/6) against a regular one (E = 1/12); bad input:
# no --init, an unknown variable, a zero tangent vector, a parameter
# without value, --every with --json, a blow-up (nothing on stdout).
# usage (from the repo root): bash tests/cli/chaos.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: chaos.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'

run 0 chaos -H 'p^2/2 - q^2/2' --init q=0.5,p=-0.25 --delta q=1,p=0 --t 8 --every 2 --tol 1e-14
has_line "t,Y,mean_Y,fli,mlce,q,p"
if $PY - "$tmp/out" <<'PYEOF'; then ok; else bad "inverted oscillator CSV against mpmath"; fi
import csv, sys, mpmath as m
m.mp.dps = 30
rows = list(csv.DictReader(open(sys.argv[1])))
assert [float(r["t"]) for r in rows] == [2, 4, 6, 8], rows
for r in rows:
    t = m.mpf(r["t"])
    mlce = m.log(m.cosh(2 * t)) / (2 * t)
    Y = 2 / t * m.quad(lambda s: s * m.tanh(2 * s), [0, t])
    mY = m.quad(lambda u: 2 * u * m.tanh(2 * u) * m.log(t / u), [0, t]) / t
    for key, want in (("mlce", mlce), ("Y", Y), ("mean_Y", mY), ("fli", mlce * t)):
        got = float(r[key])
        assert abs(got - want) <= 1e-11 * abs(want), (key, t, got, want)
PYEOF

run 0 chaos -H 'p^2/2 - cos(q)' --init q=1.3,p=0 --t 1000 --json
py 'assert d["command"] == "chaos" and abs(d["megno_mean"] - 2) < 0.05, d'
py 'assert abs(d["mlce"]) < 0.01 and d["t"] == 1000, d'

run 0 chaos -H "$HH" --init x=0,y=-0.1,px=0.56803755858823,py=0 --t 2000 --json
cp "$tmp/out" "$tmp/chaotic.json"
run 0 chaos -H "$HH" --init x=0,y=0.1,px=0.39665266081716,py=0 --t 2000 --json
if $PY -c "
import json
c = json.load(open('$tmp/chaotic.json')); r = json.load(open('$tmp/out'))
assert c['megno_mean'] > 50 and c['mlce'] > 0.05, c
assert abs(r['megno_mean'] - 2) < 0.02 and r['mlce'] < 0.01, r
"; then ok; else bad "Henon-Heiles: chaotic E = 1/6 vs regular E = 1/12"; fi

# text output: the five lines
run 0 chaos -H 'p^2/2 - q^2/2' --init q=0,p=0 --delta q=1,p=1 --t 10
has_line "MEGNO Y = 10"
has_line "MEGNO mean <Y> = 5"
has_line "maximal Lyapunov exponent ~ 1"

# rows at 0.3, 0.6 and 0.9, though 3 * 0.3 < 0.9 in double
run 0 chaos -H 'p^2/2 - q^2/2' --init q=0,p=0 --t 0.9 --every 0.3
[ "$(wc -l < "$tmp/out")" -eq 4 ] && ok || bad "rows at 0.3, 0.6, 0.9: $(cat "$tmp/out")"
run 2 chaos -H 'p^2/2 - q^2/2' --init q=0,p=0 --t 1e3 --every 1e-5
err_has "more than"

run 2 chaos -H 'p^2/2 - cos(q)' --t 10
err_has "missing --init"
run 2 chaos -H 'p^2/2 - cos(q)' --init q=1,z=0 --t 10
err_has "'z' is not a variable"
run 2 chaos -H 'p^2/2 - cos(q)' --init q=1,p=0 --delta q=0,p=0 --t 10
err_has "tangent vector is 0"
run 2 chaos -H 'p^2/2 - k*cos(q)' --init q=1,p=0 --t 10
err_has "parameter 'k' needs a value"
run 2 chaos -H 'p^2/2 - cos(q)' --init q=1,p=0 --t 0
err_has "--t must be positive"
run 2 chaos -H 'p^2/2 - cos(q)' --init q=1,p=0 --t 1 --every 0.5 --json
err_has "not with --json"
run 2 chaos -H 'p^2/2 - q^4/4' --init 'q=1,p=sqrt(1/2)' --t 10 --every 0.1
err_has "at t = 1.41"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
finish
