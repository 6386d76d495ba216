#!/bin/bash
# hamlie sweep: many runs at once.
#  - a member's row against the same single `hamlie run` (its last CSV row:
#    final state and H, bit for bit as printed);
#  - the pendulum with stormer-verlet-kdk across a grid inside the
#    separatrix: max |H - H0| scales with dt^2 (log2 of the ratio from dt to
#    dt/2 is 2 +- 0.05 for every point) and the observed order (--order,
#    against the reference) is 2 +- 0.05;
#  - the same file with --threads 1 and 2 (cmp), random points reproducible
#    (a point depends on the seed and its index only), --init-file;
#  - kill -INT mid-sweep: exit 130, no output, the journal kept; --resume
#    gives the same file as an uninterrupted run (cmp); the same after
#    kill -KILL (a torn journal);
#  - a blowing-up member (H = p^2/2 - q^4 from q = 50): recorded with its
#    reason, named on stderr, the others done, exit 1;
#  - bad input: a grid with no points, an unknown variable, a step that does
#    not divide t, an unwritable --out -> exit 2, the position, no file.
# usage (from the repo root): bash tests/cli/sweep.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: sweep.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3
PEND='p^2/2 - cos(q)'

pycheck() { # pycheck WHAT CODE ARGS...: python asserts
    local what=$1 code=$2
    shift 2
    if $PY -c "$code" "$@" >"$tmp/py" 2>&1; then ok; else bad "$what"; sed 's/^/    /' "$tmp/py" >&2; fi
}

# ---- a row against the same single run ----------------------------------------
run 0 sweep -H "$PEND" --grid 'q=-1:1:3,p=0.25:0.75:2' --scheme stormer-verlet-kdk,rk4 \
    --dt 0.1,0.05 --t 7 --out "$tmp/row.csv" --threads 2
read -r q0 p0 scheme dt want < <($PY - "$tmp/row.csv" <<'PYEOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 6 * 2 * 2, len(rows)
r = rows[4 * 4 + 2 + 1]  # point 4, rk4, dt 0.05
assert r["member"] == "19" and r["point"] == "4" and r["scheme"] == "rk4" and r["dt"] == "0.05", r
print(r["q0"], r["p0"], r["scheme"], r["dt"], ",".join([r["t"], r["q"], r["p"]]))
PYEOF
)
run 0 run -H "$PEND" --scheme "$scheme" --dt "$dt" --t 7 --init "q=$q0,p=$p0" --no-reference
got=$(tail -1 "$tmp/out" | cut -d, -f1-3)
[ "$got" = "$want" ] && ok || bad "member 19 '$want' against hamlie run '$got'"

# ---- max_dH ~ dt^2 and the observed order across a grid -------------------------
run 0 sweep -H "$PEND" --grid 'q=-1.5:1.5:7,p=-1:1:5' --scheme stormer-verlet-kdk \
    --dt 0.1,0.05 --t 20 --order --out "$tmp/order.csv"
pycheck "stormer-verlet's max_dH ratio and order on the grid" '
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 35 * 2
for a, b in zip(rows[0::2], rows[1::2]):
    assert a["point"] == b["point"] and a["dt"] == "0.1" and b["dt"] == "0.05"
    assert a["status"] == "ok" and b["status"] == "ok", (a, b)
    if a["q0"] == "0" and a["p0"] == "0":  # the equilibrium: no error at all
        assert float(a["max_dH"]) == 0 and float(b["max_dH"]) == 0
        continue
    k = math.log2(float(a["max_dH"]) / float(b["max_dH"]))
    assert abs(k - 2) < 0.05, (a["q0"], a["p0"], k)
    for r in (a, b):
        assert abs(float(r["order"]) - 2) < 0.05, (r["q0"], r["p0"], r["order"])
' "$tmp/order.csv"

# ---- threads, random points, --init-file ---------------------------------------
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
common=(-H "$HH" --random 'x=0,y=-0.3:0.3,px=-0.3:0.3,py=0.1' --seed 7 --scheme rk4,lie
        --dt 0.5 --t 10 --tol 1e-12 --chaos --reference)
run 0 sweep "${common[@]}" --count 12 --threads 1 --out "$tmp/t1.csv"
run 0 sweep "${common[@]}" --count 12 --threads 2 --out "$tmp/t2.csv"
cmp -s "$tmp/t1.csv" "$tmp/t2.csv" && ok || bad "--threads 1 and 2 differ"
run 0 sweep "${common[@]}" --count 5 --threads 2 --out "$tmp/t5.csv"
pycheck "random points: the first 5 of 12 are the 5 of --count 5; inside the bounds" '
import csv, math, sys
a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
assert len(a) == 24 and len(b) == 10
cols = ["x0", "y0", "px0", "py0", "megno", "x", "y"]
for ra, rb in zip(a[:10], b):
    assert [ra[c] for c in cols] == [rb[c] for c in cols], (ra, rb)
for r in a:
    assert r["x0"] == "0" and r["py0"] == "0.10000000000000001"
    assert -0.3 <= float(r["y0"]) < 0.3 and -0.3 <= float(r["px0"]) < 0.3
    assert math.isfinite(float(r["megno"]))
' "$tmp/t1.csv" "$tmp/t5.csv"
# 40 parameter values: more than a thread keeps built (16), rebuilt as they come
pa=(-H 'p^2/2 - k*cos(q)' --param 'k=0.1:2:40' --grid 'q=0:1:3,p=0' --scheme rk4,lie --dt 0.1
    --t 2)
run 0 sweep "${pa[@]}" --threads 1 --out "$tmp/pa1.csv"
run 0 sweep "${pa[@]}" --threads 2 --out "$tmp/pa2.csv"
cmp -s "$tmp/pa1.csv" "$tmp/pa2.csv" && ok || bad "40 paramsets: --threads 1 and 2 differ"
want=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i }
                $c["member"] == "157" { print $c["k"] "," $c["q0"] "," $c["q"] "," $c["p"] }' "$tmp/pa1.csv")
IFS=, read -r k q0 q p <<<"$want"
# (to 1e-13, not bit for bit: run's progress callback restarts the adaptive
# integrator at its rows, run.h; the sweep's members have no callback)
run 0 run -H 'p^2/2 - k*cos(q)' --param "k=$k" --scheme lie --tol 1e-15 --dt 0.1 --t 2 \
    --init "q=$q0,p=0"
got=$(tail -1 "$tmp/out" | cut -d, -f2,3)
pycheck "member 157 (k = $k, lie) '$q,$p' against hamlie run '$got'" '
import sys
a = [float(x) for x in sys.argv[1].split(",")]
b = [float(x) for x in sys.argv[2].split(",")]
assert all(abs(x - y) < 1e-13 for x, y in zip(a, b)) and len(a) == len(b) == 2
' "$q,$p" "$got"
printf '# two orbits\ny,px,x,py\n0.1,0.2,0,0.1\n-0.1,0,0,0.3\n' >"$tmp/pts.csv"
run 0 sweep -H "$HH" --init-file "$tmp/pts.csv" --scheme stormer-verlet-kdk --dt 0.1 --t 1
pycheck "--init-file points" '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [(r["x0"], r["y0"], r["px0"], r["py0"]) for r in rows] == [
    ("0", "0.10000000000000001", "0.20000000000000001", "0.10000000000000001"),
    ("0", "-0.10000000000000001", "0", "0.29999999999999999")], rows
' "$tmp/out"

# ---- kill -INT / -KILL mid-sweep, then --resume -----------------------------------
# (about 2 s of CPU; fewer than 200000 steps a run: no compiling to wait for)
slow=(-H "$PEND" --grid 'q=-2:2:20,p=-1:1:6' --scheme rk4,stormer-verlet-kdk --dt 0.0005
      --t 90 --threads 2 --quiet)
run 0 sweep "${slow[@]}" --out "$tmp/whole.csv"
# interrupted SIGNAL: started in the background, signalled once its journal
# holds some results; its exit status in $rc
interrupted() {
    env --default-signal=INT "$HAMLIE" sweep "${slow[@]}" --out "$tmp/cut.csv" \
        >"$tmp/out" 2>"$tmp/err" &
    local pid=$!
    for i in $(seq 600); do
        [ "$(stat -c %s "$tmp/cut.csv.journal" 2>/dev/null || echo 0)" -gt 2000 ] && break
        sleep 0.05
    done
    kill "-$1" "$pid"
    { wait "$pid"; } 2>/dev/null
    rc=$?
}
for sig in INT KILL; do
    rm -f "$tmp/cut.csv" "$tmp/cut.csv.journal"
    interrupted $sig
    want=$([ $sig = INT ] && echo 130 || echo 137)
    [ "$rc" -eq "$want" ] && ok || bad "SIGINT: exit $rc, want $want"
    [ ! -e "$tmp/cut.csv" ] && [ -s "$tmp/cut.csv.journal" ] && ok ||
        bad "after SIG$sig: a file written or no journal"
    [ $sig = INT ] && { grep -q -- "--resume" "$tmp/err" && ok || bad "no --resume hint"; }
    run 2 sweep "${slow[@]}" --out "$tmp/cut.csv"   # the journal is not overwritten
    err_has "--resume"
    run 0 sweep "${slow[@]}" --out "$tmp/cut.csv" --resume
    cmp -s "$tmp/cut.csv" "$tmp/whole.csv" && ok || bad "resumed after SIG$sig differs"
    [ ! -e "$tmp/cut.csv.journal" ] && ok || bad "journal left after a complete sweep"
done
rm -f "$tmp/cut.csv"
interrupted INT # a journal left, then another sweep resumed from it
run 2 sweep -H "$PEND" --grid 'q=0,p=0' --scheme rk4 --dt 0.1 --t 2 --out "$tmp/cut.csv" --resume
err_has "another sweep"
[ ! -e "$tmp/cut.csv" ] && [ -s "$tmp/cut.csv.journal" ] && ok || bad "the other journal touched"
rm -f "$tmp/cut.csv.journal"

# ---- a blow-up is a row -----------------------------------------------------------
run 1 sweep -H 'p^2/2 - q^4' --grid 'q=0.05,50,0.02,p=0' --scheme euler --dt 0.1 --t 10 \
    --out "$tmp/blow.csv"
err_has "member 1 (point 1, euler, dt 0.1) failed: blow-up"
pycheck "blow-up recorded, the others done" '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["status"] for r in rows] == ["ok", "domain error", "ok"], rows
assert "blow-up" in rows[1]["reason"] and rows[0]["t"] == "10" and rows[2]["t"] == "10"
' "$tmp/blow.csv"

# ---- bad input: exit 2, the position, no file --------------------------------------
bad_input() { # bad_input TEXT ARGS...: exit 2, TEXT on stderr, no --out file
    local text=$1
    shift
    rm -f "$tmp/bad.csv"
    run 2 sweep -H "$PEND" --scheme rk4 --t 1 --out "$tmp/bad.csv" "$@"
    err_has "$text"
    [ ! -e "$tmp/bad.csv" ] && [ ! -e "$tmp/bad.csv.journal" ] && ok || bad "a file left by $*"
}
bad_input "a range of 0 points" --grid 'q=1:0:0,p=0' --dt 0.1
grep -qF '       ^' "$tmp/err" && ok || bad "no caret under the range's count"
bad_input "'x' is not a variable" --grid 'q=0,x=1' --dt 0.1
bad_input "not reachable" --grid 'q=0,p=0' --dt 0.1,0.3
bad_input "(it depends on 'p')" --grid 'q=pi/p,p=0' --dt 0.1
# values may be constant formulas, as run's initial values: q = pi is the top
run 0 sweep -H "$PEND" --grid 'q=pi,p=-pi/2:0:2' --scheme rk4 --t 1 --dt 0.5 --out "$tmp/pi.csv"
pycheck "constant formulas in a grid" '
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [float(r["q0"]) for r in rows] == [math.pi] * 2, rows
assert [float(r["p0"]) for r in rows] == [-math.pi / 2, 0.0], rows
' "$tmp/pi.csv"
bad_input "exactly one of" --dt 0.1
bad_input "2 values expected, 1 given" --init-file <(printf 'q,p\n1,2\n3\n') --dt 0.1
err_has ":3:1:"
run 2 sweep -H "$PEND" --scheme rk4 --t 1 --dt 0.1 --grid 'q=0,p=0' --out /nonexistent/dir/x.csv
err_has "/nonexistent/dir/x.csv"
run 2 sweep -H "$PEND" --scheme nosuch --t 1 --dt 0.1 --grid 'q=0,p=0'
err_has "schemes: unknown scheme 'nosuch'"

bad_input "a grid in two variables" --grid 'q=0:1:3,p=1' --dt 0.5 --plot "$tmp/nomaps"
[ ! -e "$tmp/nomaps" ] && ok || bad "--plot of a 1-D grid left a folder"

# ---- --plot: a map per scheme and step ---------------------------------------------
if "$HAMLIE" sweep -H "$PEND" --grid 'q=-1:1:9,p=-1:1:9' --scheme euler,rk4 --dt 0.1 --t 2 \
    --chaos --tol 1e-10 --plot "$tmp/maps" --out "$tmp/maps.csv" 2>"$tmp/err"; then
    [ -s "$tmp/maps/max_dH-euler-dt0.1.png" ] && [ -s "$tmp/maps/megno-rk4-dt0.1.png" ] && ok ||
        bad "maps missing: $(ls "$tmp/maps" 2>&1)"
elif grep -q "PLplot" "$tmp/err"; then
    echo "(PLplot missing: no maps drawn)"
else
    bad "--plot failed"; sed 's/^/    /' "$tmp/err" >&2
fi
finish
