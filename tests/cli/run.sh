#!/bin/bash
# hamlie run: the CSV against closed forms (Euler on the oscillator:
# x_n + i p_n = (1 - i dt)^n, so 2 H_n = (1 + dt^2)^n; the reference is
# cos t, -sin t), --every, --out/--json, the user's map and equations
# against the catalog's schemes, the adaptive integrator against cos/sin,
# observed orders, and the failures: exit 2, a clear message, and a partial
# CSV that is valid up to the failure.
# usage (from the repo root): bash tests/cli/run.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: run.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"  # its py is replaced below: CSV, not JSON
# py FILE CODE: python with rows = the CSV's rows as floats, head = its header
py() {
    if python3 - "$1" "$2" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "python check on $1: $2"; sed 's/^/    /' "$tmp/py" >&2; fi
import csv, json, math, sys
path, code = sys.argv[1], sys.argv[2]
text = open(path).read()
if text.lstrip().startswith("{"):
    d = json.loads(text)
else:
    assert text == "" or text.endswith("\n"), "last line not whole"
    lines = list(csv.reader(text.splitlines()))
    head, rows = lines[0], [[float(v) for v in r] for r in lines[1:]]
    assert all(len(r) == len(head) for r in rows), "ragged CSV"
exec(code)
PYEOF
}

OSC='(p^2+x^2)/2'
PEND='p^2/2 - cos(q)'

# ---- Euler on the oscillator: closed forms -------------------------------
run 0 run -H "$OSC" --scheme euler --dt 0.1 --t 20 --init x=1,p=0
cp "$tmp/out" "$tmp/euler.csv"
py "$tmp/euler.csv" '
assert head == ["t", "x", "p", "H", "sigma"], head
assert len(rows) == 201
for n, (t, x, p, H, s) in enumerate(rows):
    assert abs(t - n * 0.1) < 1e-12
    assert abs(2 * H / 1.01 ** n - 1) < 1e-12, (n, H)
    w = complex(1, -0.1) ** n
    assert abs(complex(x, p) - w) < 1e-12 * abs(w)
    ex = (x - math.cos(t)) ** 2 + (p + math.sin(t)) ** 2
    assert abs(s - ex) <= 1e-9 * ex + 1e-15, (n, s, ex)'

run 0 run -H "$OSC" --scheme euler --dt 0.1 --t 20 --init x=1,p=0 --every 7 --observe 'x/(p+3)' --observe 'x^2+p^2-2*H'
py "$tmp/out" '
assert head == ["t", "x", "p", "H", "sigma", "x/(p+3)", "x^2+p^2-2*H"], head
ks = [round(r[0] / 0.1) for r in rows]
assert ks == list(range(0, 197, 7)) + [200], ks
for t, x, p, H, s, a, b in rows:
    assert abs(a - x / (p + 3)) <= 1e-14 * max(1, abs(a)) and abs(b) < 1e-12 * H'

# ---- the user's map and equations = the catalog's schemes ----------------
run 0 run -H "$OSC" --map 'X = x + D*p; P = p - D*x' --dt 0.1 --t 20 --init x=1,p=0
if cmp -s "$tmp/out" "$tmp/euler.csv"; then ok; else bad "--map Euler differs from --scheme euler"; fi
run 0 run -H "$PEND" --scheme implicit-midpoint --dt 0.05 --t 5 --init q=1.3,p=0
cp "$tmp/out" "$tmp/mid.csv"
run 0 run -H "$PEND" --equations '(Q-q)/D = (p+P)/2; (P-p)/D = -sin((q+Q)/2)' --dt 0.05 --t 5 --init q=1.3,p=0
paste -d, "$tmp/out" "$tmp/mid.csv" >"$tmp/both.csv"
py "$tmp/both.csv" '
assert len(rows) == 101
for r in rows:
    assert all(abs(r[i] - r[5 + i]) < 1e-12 for i in range(4)), r'

# ---- --out and --json ----------------------------------------------------
run 0 run -H "$OSC" --scheme rk4 --dt 0.01 --t 10 --init x=1,p=0 --out "$tmp/rk4.csv" --json
[ -f "$tmp/rk4.csv" ] && [ ! -e "$tmp/rk4.csv.tmp" ] && ok || bad "--out did not leave rk4.csv alone"
py "$tmp/out" '
assert d["command"] == "run" and d["steps"] == 1000 and d["rows"] == 1001 and d["final_t"] == 10
x, p = d["final_state"]["x"], d["final_state"]["p"]
assert abs(x - math.cos(10)) < 1e-9 and abs(p + math.sin(10)) < 1e-9
assert abs(d["sigma_final"] - ((x - math.cos(10))**2 + (p + math.sin(10))**2)) < 1e-20
assert d["H0"] == 0.5 and d["max_abs_dH"] < 1e-9 and d["wall_time_s"] >= 0'
py "$tmp/rk4.csv" 'assert len(rows) == 1001 and rows[-1][0] == 10'
run 0 run -H "$OSC" --scheme rk4 --dt 0.01 --t 10 --init x=1,p=0 --json
py "$tmp/out" 'assert d["out"] is None and d["steps"] == 1000'

# ---- the adaptive Taylor integrator --------------------------------------
run 0 run -H "$OSC" --scheme lie --tol 1e-15 --t 100 --dt 0.5 --init x=1,p=0 --no-reference
py "$tmp/out" '
assert head == ["t", "x", "p", "H"] and len(rows) == 201
assert max(max(abs(x - math.cos(t)), abs(p + math.sin(t))) for t, x, p, H in rows) < 1e-12'
run 0 run -H "$OSC" --scheme lie --tol 1e-15 --t 100 --init x=1,p=0
py "$tmp/out" 'assert len(rows) == 1001'
# below |z| = 1 --tol is absolute (as heyoka's): a state of 1e-100 is said to
# be integrated to 1e-15, not to 1e-15 of its size (at t = 1000 it ended
# 1.4e83 times its amplitude away); a state of size 1, 0.01 or 0 is not
run 0 run -H "$OSC" --scheme lie --t 10 --init x=0,p=-1e-100 --json
err_has "note: |z| = 1e-100 at t = 0, and below 1 --tol 1e-15 is an absolute tolerance"
run 0 run -H "$OSC" --scheme rk4 --dt 0.1 --t 1 --init x=1e-9,p=0 --json
err_has "the reference (sigma) may have few correct digits"
for init in x=1,p=0 x=0.01,p=0 x=0,p=0; do
    run 0 run -H "$OSC" --scheme lie --t 1 --init "$init" --json
    if grep -q "note:" "$tmp/err"; then bad "a note on --tol at $init: $(cat "$tmp/err")"; else ok; fi
done
run 0 run -H "$OSC" --scheme rk4 --dt 0.1 --t 1 --init x=1e-9,p=0 --no-reference --json
if grep -q "note:" "$tmp/err"; then bad "a note on --tol without a reference"; else ok; fi
# --scheme lie with --dt alone: the truncated Lie series (order 4)
run 0 run -H "$PEND" --scheme lie --dt 0.1 --t 2 --init q=1.3,p=0 --orders 0.1,0.05,0.025 --json
py "$tmp/out" 'assert all(abs(o["order"] - 4) < 0.15 for o in d["orders"][1:]), d["orders"]'

# --digits: the adaptive run in Arb, against mpmath's cos/sin at 60 digits
run 0 run -H "$OSC" --scheme lie --digits 50 --t 10 --dt 2 --init x=1,p=0
if python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "--digits 50 vs mpmath"; cat "$tmp/py" >&2; fi
import sys, mpmath
mpmath.mp.dps = 60
lines = open(sys.argv[1]).read().splitlines()
assert lines[0] == "t,x,p,H" and len(lines) == 7
for l in lines[1:]:
    t, x, p, H = (mpmath.mpf(v) for v in l.split(","))
    assert abs(x - mpmath.cos(t)) < mpmath.mpf("1e-45") and abs(p + mpmath.sin(t)) < mpmath.mpf("1e-45"), l
    assert abs(H - mpmath.mpf(1) / 2) < mpmath.mpf("1e-45")
PYEOF
run 0 run -H '(px^2+py^2)/2 - 1/sqrt(x^2+y^2)' --scheme lie --digits 30 --t 1 --init x=0.5,y=0,px=0,py='sqrt(3)' --json
py "$tmp/out" 'assert d["rows"] == 1001 and abs(d["H0"] + 0.5) < 1e-16 and d["max_abs_dH"] < 1e-28'
run 2 run -H "$OSC" --scheme rk4 --digits 30 --dt 0.1 --t 1 --init x=1,p=0
err_has "--digits is for the adaptive integrator"

# ---- observed orders -------------------------------------------------------
run 0 run -H "$PEND" --scheme gauss2 --t 2 --init q=1.3,p=0 --orders 0.1,0.05,0.025 --json
py "$tmp/out" '
o = d["orders"]
assert [r["dt"] for r in o] == [0.1, 0.05, 0.025]
for a, b in zip(o, o[1:]):
    assert abs(b["order"] - math.log(a["max_error"] / b["max_error"]) / math.log(2)) < 1e-12
    assert abs(b["order"] - 4) < 0.15, o'
run 0 run -H "$PEND" --scheme stormer-verlet-kdk --t 2 --init q=1.3,p=0 --orders 0.05,0.025,0.0125
if grep -qE '^0.0125 +[0-9.e+-]+ +2\.0[0-9]* ' "$tmp/out" || grep -qE '^0.0125 +[0-9.e+-]+ +1\.9[0-9]* ' "$tmp/out"; then ok; else bad "verlet order table:"; cat "$tmp/out" >&2; fi

# ---- bad input ---------------------------------------------------------------
run 2 run -H "$OSC" --scheme euler --dt 0.1 --t 20 --init x=1
err_has "no initial value for 'p'"
run 2 run -H "$OSC" --scheme euler --dt 0 --t 20 --init x=1,p=0
err_has "positive"
[ -s "$tmp/out" ] && bad "output on a bad dt" || ok
run 2 run -H "$OSC" --scheme euler --dt -0.1 --t 20 --init x=1,p=0
err_has "positive"
run 2 run -H "$OSC" --scheme euler --dt 0.3 --t 20 --init x=1,p=0
err_has "t = 20 is not reachable with dt = 0.3: 66.67 steps"
run 2 run -H "$OSC" --scheme euler --dt 0.1 --t 20 --init x=1,p=0 --observe 'x/zz'
err_has "unknown symbol 'zz'"
err_has "    ^~"
run 2 run -H "$OSC" --scheme nosuch --dt 0.1 --t 20 --init x=1,p=0
run 2 run -H "$OSC" --dt 0.1 --t 20 --init x=1,p=0
err_has "give a scheme"

# a blow-up: Euler on the quartic oscillator (whose exact solution is bounded)
run 2 run -H 'p^2/2 + q^4/4' --scheme euler --dt 0.5 --t 100 --init q=2,p=0 --no-reference
err_has "blow-up"
err_has "step"
py "$tmp/out" '
assert head == ["t", "q", "p", "H"] and 1 < len(rows) < 200
assert all(math.isfinite(v) for r in rows for v in r)'
run 2 run -H 'p^2/2 + q^4/4' --scheme euler --dt 0.5 --t 100 --init q=2,p=0 --out "$tmp/blow.csv"
err_has "blow-up"
err_has "blow.csv.partial"
[ ! -e "$tmp/blow.csv" ] && [ ! -e "$tmp/blow.csv.tmp" ] && ok || bad "blow-up left blow.csv or .tmp"
py "$tmp/blow.csv.partial" '
assert head == ["t", "q", "p", "H", "sigma"] and 1 < len(rows) < 200
assert all(math.isfinite(v) for r in rows for v in r)'

# a Newton failure: gauss3 with a step far too large (Newton from the Euler
# prediction fails at the first step)
run 2 run -H "$PEND" --scheme gauss3 --dt 50 --t 1000 --init q=1.3,p=0
err_has "Newton did not converge"
py "$tmp/out" 'assert len(rows) == 1 and rows[0][:3] == [0, 1.3, 0]'

# output that cannot be written
run 2 run -H "$OSC" --scheme euler --dt 0.1 --t 1 --init x=1,p=0 --out "$tmp/no/such/dir.csv"
err_has "cannot write"
if [ -w /dev/full ]; then
    "$HAMLIE" run -H "$OSC" --scheme euler --dt 0.001 --t 100 --init x=1,p=0 >/dev/full 2>"$tmp/err"
    [ $? -eq 2 ] && ok || bad "writing to /dev/full did not exit 2"
    err_has "writing to standard output failed"
fi
run 0 help run
if grep -q -- "--orders" "$tmp/out"; then ok; else bad "hamlie help run"; fi

# --json alone on a long run: no rows are consumed, so the runner iterates
# the step fused with H in machine code between sparse rows (drive.c); the
# summary is that of the run that writes every row (rows counted the same)
run 0 run -H "$PEND" --scheme stormer-verlet --dt 0.01 --t 5000 --init q=1.3,p=0 --no-reference --json
cp "$tmp/out" "$tmp/fast.json"
run 0 run -H "$PEND" --scheme stormer-verlet --dt 0.01 --t 5000 --init q=1.3,p=0 --no-reference --json --out "$tmp/all.csv"
py "$tmp/out" "
f = json.load(open('$tmp/fast.json'))
assert f['rows'] == d['rows'] == 500001 and f['steps'] == d['steps'] == 500000
for k in ('q', 'p'):
    assert abs(f['final_state'][k] - d['final_state'][k]) < 1e-12, k
assert abs(f['max_abs_dH'] - d['max_abs_dH']) < 1e-15
"
finish
