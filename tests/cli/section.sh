#!/bin/bash
# hamlie section: Henon-Heiles surfaces of section x = 0, px > 0.
#  - E = 1/8: the seeds' solved px satisfies H = E (to 1e-15, against the
#    closed form sqrt(2E - py^2 - y^2 + 2y^3/3)); every crossing has x = 0,
#    px > 0, |H - E| < 1e-13;
#  - crossings against a 30-digit run: hamlie's Arb integrator (--digits 30)
#    from the same seed to the crossing time found in double lands on x = 0
#    to 1e-12 (so the time is right to 1e-12 / |px|), at the same state;
#  - schemes on the section (measured, printed): stormer-verlet-kdk keeps
#    |H - E| at O(dt^2) (ratio ~4 from dt 0.1 to 0.05); explicit Euler's H
#    grows crossing after crossing (the section spirals out);
#  - --init-file, the figure, and bad input with positions.
# usage (from the repo root): bash tests/cli/section.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: section.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
pyj() {
    if $PY -c "import json, math, sys; d = json.load(open('$tmp/out'))
$1" >"$tmp/py" 2>&1; then ok; else bad "python check: $1"; sed 's/^/    /' "$tmp/py" >&2; fi
}

run 0 section -H "$HH" --energy 1/8 --surface x=0 --direction up --orbits 6 --crossings 40 \
    --tol 1e-15 --out "$tmp/hh.csv" --plot "$tmp/fig" --json
pyj 'assert d["orbits"] == 6 and d["crossings"] == 240 and d["failed_orbits"] == 0, d
assert d["max_abs_H_minus_E"] < 1e-13, d["max_abs_H_minus_E"]
E = 0.125
for z in d["seeds"]:
    y, py, px = z["y"], z["py"], z["px"]
    assert z["x"] == 0 and px > 0
    H = (px*px + py*py)/2 + y*y/2 - y**3/3
    assert abs(H - E) < 1e-15, H - E
    assert abs(px - math.sqrt(2*E - py*py - y*y + 2*y**3/3)) < 1e-15'
[ -s "$tmp/fig/section.png" ] && ok || bad "no figure"
if $PY - "$tmp/hh.csv" <<'PYEOF'; then ok; else bad "crossings on x = 0 with px > 0 and H = E"; fi
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert list(rows[0].keys()) == ["orbit", "crossing", "t", "x", "y", "px", "py", "H"]
assert len(rows) == 240
for r in rows:
    assert abs(float(r["x"])) < 1e-15 and float(r["px"]) > 0, r
    assert abs(float(r["H"]) - 0.125) < 1e-13, r
PYEOF

# against 30 digits: orbit 2's seed, to its 10th crossing, in Arb
cp "$tmp/out" "$tmp/hh.json"
read -r init tc want < <($PY - "$tmp/hh.json" "$tmp/hh.csv" <<'PYEOF'
import csv, json, sys
d = json.load(open(sys.argv[1]))
z = d["seeds"][2]
row = [r for r in csv.DictReader(open(sys.argv[2])) if r["orbit"] == "2"][9]
init = ",".join("%s=%s" % (k, repr(z[k])) for k in ("x", "y", "px", "py"))
print(init, row["t"], ",".join(row[k] for k in ("x", "y", "px", "py")))
PYEOF
)
run 0 run -H "$HH" --scheme lie --digits 30 --init "$init" --t "$tc" --dt "$tc"
if $PY - "$tmp/out" "$want" <<'PYEOF'; then ok; else bad "crossing against the 30-digit run"; fi
import sys
from mpmath import mp, mpf
mp.dps = 30
last = open(sys.argv[1]).read().strip().splitlines()[-1].split(",")
x, y, px, py = (mpf(v) for v in last[1:5])
want = [float(v) for v in sys.argv[2].split(",")]
print("30 digits at the double's 10th crossing time: x = %s (time error ~ %.2g), state diff %.2g"
      % (mp.nstr(x, 5), float(abs(x / px)), max(abs(float(a) - b) for a, b in zip((x, y, px, py), want))))
assert abs(x / px) < 1e-12
assert max(abs(float(a) - b) for a, b in zip((x, y, px, py), want)) < 1e-12
PYEOF

# schemes on the section: measured
measure() { # scheme dt crossings -> max |H - E|, H(last) - H(first) of orbit 1
    "$HAMLIE" section -H "$HH" --energy 1/8 --surface x=0 --orbits 3 --crossings "$3" \
        --scheme "$1" --dt "$2" --out "$tmp/m.csv" >/dev/null 2>"$tmp/err" || echo "FAILED"
    $PY -c "
import csv
rows = [r for r in csv.DictReader(open('$tmp/m.csv'))]
o1 = [float(r['H']) for r in rows if r['orbit'] == '1']
print(max(abs(float(r['H']) - 0.125) for r in rows), o1[-1] - o1[0])"
}
read -r sv1 _ < <(measure stormer-verlet-kdk 0.1 100)
read -r sv2 _ < <(measure stormer-verlet-kdk 0.05 100)
read -r eu1 dr1 < <(measure euler 0.001 30)
read -r eu2 dr2 < <(measure euler 0.0005 30)
echo "HH E = 1/8 section, max |H - E| at the crossings: stormer-verlet-kdk $sv1 (dt 0.1), $sv2 (dt 0.05);" \
     "euler $eu1 (dt 1e-3), $eu2 (dt 5e-4), H gained over 30 crossings of orbit 1: $dr1, $dr2"
$PY -c "
sv1, sv2, eu1, dr1, dr2 = $sv1, $sv2, $eu1, $dr1, $dr2
assert 3.5 < sv1 / sv2 < 4.5 and sv1 < 1e-3, (sv1, sv2)
assert dr1 > 10 * sv1 and dr2 > 0 and 1.6 < dr1 / dr2 < 2.6, (dr1, dr2)
" && ok || bad "scheme sections: sv $sv1 $sv2, euler $dr1 $dr2"

# orbits that blow up (Euler escapes past E = 1/6): named, kept, drawn (the
# figure's range clipped to the bulk of the points), exit status 1
run 1 section -H "$HH" --energy 1/8 --surface x=0 --orbits 3 --crossings 200 --scheme euler \
    --dt 0.01 --out "$tmp/eu.csv" --plot "$tmp/eufig"
err_has "failed after"
err_has "blow-up"
[ -s "$tmp/eufig/section.png" ] && [ -s "$tmp/eu.csv" ] && ok || bad "no file or figure after failed orbits"

# --init-file
printf '# y, py on x = 0\ny,py\n0.1,0\n-0.2, 0.1\n\n' >"$tmp/pts.csv"
run 0 section -H "$HH" --energy 1/8 --surface x=0 --init-file "$tmp/pts.csv" --crossings 5 --json
pyj 'assert d["orbits"] == 2 and d["crossings"] == 10 and d["seeds"][1]["y"] == -0.2 and d["seeds"][1]["py"] == 0.1'
printf 'y,pz\n0.1,0\n' >"$tmp/bad.csv"
run 2 section -H "$HH" --energy 1/8 --surface x=0 --init-file "$tmp/bad.csv"
err_has "bad.csv:1:3: 'pz' is not a variable"
printf 'y,py\n0.1,0\n0.9,0\n' >"$tmp/bad.csv"
run 2 section -H "$HH" --energy 1/8 --surface x=0 --init-file "$tmp/bad.csv"
err_has "the point on line 3: H = E has no real solution for px"
printf 'y,py\n0.1,abc\n' >"$tmp/bad.csv"
run 2 section -H "$HH" --energy 1/8 --surface x=0 --init-file "$tmp/bad.csv"
err_has "bad.csv:2:5: expected a finite number for 'py'"
printf 'y\n0.1\n' >"$tmp/bad.csv"
run 2 section -H "$HH" --energy 1/8 --surface x=0 --init-file "$tmp/bad.csv"
err_has "no column for 'py'"

# bad input
run 2 section -H "$HH" --energy 1/8 --surface 'x+' --out "$tmp/never.csv"
err_has "in --surface"
err_has "  x+"
run 2 section -H "$HH" --energy 1/8 --surface 'x+y=0' --out "$tmp/never.csv"
err_has "a surface of section is 'coordinate = constant'"
run 2 section -H "$HH" --energy -1/100 --surface x=0 --out "$tmp/never.csv"
err_has "no allowed region around a minimum: at E = -0.01"
run 2 section -H '(px^2+py^2+x^2+y^2)/2' --energy -1 --surface x=0 --out "$tmp/never.csv"
err_has "no allowed region: E = -1 is below the minimum of H on the section"
run 2 section -H "$HH" --energy 1/8 --surface x=0 --direction upward --out "$tmp/never.csv"
err_has "--direction wants up, down or both, not 'upward'"
run 2 section -H "$HH" --energy 'E0' --surface x=0 --out "$tmp/never.csv"
err_has "in --energy: the energy must be a constant, not depend on 'E0'"
run 2 section -H "$HH" --energy 1/8 --surface x=0 --scheme euler --out "$tmp/never.csv"
err_has "needs its step: --dt"
[ ! -e "$tmp/never.csv" ] && ok || bad "a file written after an input error"
# a surface never crossed: a free particle leaves x = 0
printf 'y,py\n0,0.5\n' >"$tmp/free.csv"
run 2 section -H '(px^2+py^2)/2' --energy 1/2 --surface x=0 --init-file "$tmp/free.csv" --crossings 3 --t-max 50
err_has "0 of 3 crossings"
err_has "no orbit crossed the section"
finish
