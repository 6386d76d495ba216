#!/bin/bash
# hamlie section --chaos: Henon & Heiles' three sections (1964, figures 2-4,
# E = 1/12, 1/8, 1/6), each orbit classed by MEGNO <Y> over its span
# (chaotic when <Y> > 2.5), and the fraction of chaotic orbits.
#
# What to expect, from Henon & Heiles 1964 (their figure 6 as quoted in
# issue 15: the relative area of the section covered by invariant curves is
# ~1 at E = 1/12, ~0.55 at 1/8, ~0.1 at 1/6).  The fraction of chaotic
# ORBITS seeded along the line py = 0 is not the chaotic AREA (the line
# crosses the big islands around the stable periodic orbits, which makes
# it favour regular orbits), so the bounds are loose:
#  - E = 1/12: at most 10 % chaotic.  Not 0: seeds that land in the thin
#    stochastic layer around the separatrix of the unstable periodic orbit
#    are truly chaotic (with 30 seeds, y = -0.1207: <Y> = 12 at t = 1300,
#    30 at 3000, 44 at 1e4; H & H's figure at their resolution shows only
#    curves there);
#  - E = 1/8: strictly between 20 % and 80 % (islands in a chaotic sea);
#  - E = 1/6: at least 60 % (mostly chaos).
# Also: the class is <Y> > 2.5 in the CSV and the JSON alike, chaotic
# orbits' <Y> keeps growing (hamlie chaos to twice the span), the output is
# the same bytes with 1, 2 and 3 threads, Ctrl-C stops section and chaos
# with whole output and exit 130, and bad --threads.
# usage (from the repo root): bash tests/cli/section-chaos.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: section-chaos.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
SEC=(section -H "$HH" --surface x=0 --chaos --quiet)

check_py() { # what args..., the python on stdin
    local what=$1
    shift
    if $PY - "$@" >"$tmp/py" 2>&1; then ok; else bad "$what"; sed 's/^/    /' "$tmp/py" >&2; fi
    cat "$tmp/py"
}

# ---- the three energies ----------------------------------------------------
for E in 1/12 1/8 1/6; do
    tag=${E/\//-}
    run 0 "${SEC[@]}" --orbits 30 --crossings 200 --energy "$E" --out "$tmp/$tag.csv" --json
    cp "$tmp/out" "$tmp/$tag.json"
done
check_py "fractions of chaotic orbits" "$tmp" <<'PYEOF'
import csv, json, sys
tmp = sys.argv[1]
bounds = {"1-12": (0.0, 0.10), "1-8": (0.20, 0.80), "1-6": (0.60, 1.0)}
for tag, (lo, hi) in bounds.items():
    d = json.load(open("%s/%s.json" % (tmp, tag)))
    c = d["chaos"]
    f = c["chaotic_fraction"]
    print("E = %s: %d of %d orbits chaotic (fraction %.3f), bounds [%g, %g]"
          % (tag.replace("-", "/"), c["chaotic"], c["classified"], f, lo, hi))
    assert c["classified"] == 30 and c["threshold"] == 2.5 and c["spans_below_1000"] == 0, c
    assert lo <= f <= hi and (tag != "1-8" or lo < f < hi), f
    # the class is the threshold, in the JSON and in every CSV row
    cls = {}
    for i, s in enumerate(d["seeds"]):
        assert s["class"] == ("chaotic" if s["mean_Y"] > 2.5 else "regular"), s
        cls[i] = (s["mean_Y"], s["class"] == "chaotic")
    rows = list(csv.DictReader(open("%s/%s.csv" % (tmp, tag))))
    assert list(rows[0].keys())[-3:] == ["H", "mean_Y", "chaotic"], rows[0].keys()
    assert len(rows) == 30 * 200
    for r in rows:
        y, ch = cls[int(r["orbit"])]
        assert float(r["mean_Y"]) == y and r["chaotic"] == ("1" if ch else "0"), r
    # regular orbits: <Y> at most near 2 (tori -> 2, near a stable periodic orbit less)
    assert all(y < 2.5 for y, ch in cls.values() if not ch)
PYEOF

# chaotic orbits' <Y> grows with time (the linear growth of a chaotic
# orbit), regular ones stay below the threshold: hamlie chaos from two
# seeds of E = 1/6 to twice their span
read -r chaotic regular < <($PY - "$tmp/1-6.json" "$tmp/1-6.csv" <<'PYEOF'
import csv, json, sys
d = json.load(open(sys.argv[1]))
rows = list(csv.DictReader(open(sys.argv[2])))
span = {}
for r in rows:
    span[int(r["orbit"])] = float(r["t"])
def init(i):
    s = d["seeds"][i]
    return "x=0,y=%r,px=%r,py=%r" % (s["y"], s["px"], s["py"])
c = [i for i, s in enumerate(d["seeds"]) if s["class"] == "chaotic"][0]
g = [i for i, s in enumerate(d["seeds"]) if s["class"] == "regular"][0]
print("%s;%r;%r %s;%r;%r" % (init(c), 2 * span[c], d["seeds"][c]["mean_Y"],
                             init(g), 2 * span[g], d["seeds"][g]["mean_Y"]))
PYEOF
)
IFS=';' read -r ci ct cy <<<"$chaotic"
IFS=';' read -r gi gt gy <<<"$regular"
run 0 chaos -H "$HH" --init "$ci" --t "$ct" --json
cp "$tmp/out" "$tmp/c.json"
run 0 chaos -H "$HH" --init "$gi" --t "$gt" --json
check_py "chaotic <Y> grows, regular stays" "$tmp/c.json" "$tmp/out" "$cy" "$gy" <<'PYEOF'
import json, sys
c, g = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
cy, gy = float(sys.argv[3]), float(sys.argv[4])
print("E = 1/6: chaotic <Y> %.3g -> %.3g at twice the span; regular %.4g -> %.4g"
      % (cy, c["megno_mean"], gy, g["megno_mean"]))
assert c["megno_mean"] > 1.3 * cy and c["mlce"] > 0.01
assert g["megno_mean"] < 2.5
PYEOF

# ---- threads: the same bytes -------------------------------------------------
for n in 1 2 3; do
    run 0 "${SEC[@]}" --energy 1/8 --orbits 7 --crossings 60 --threads $n --out "$tmp/th.csv" \
        --plot "$tmp/fig" --json
    cp "$tmp/out" "$tmp/th$n.json"
    cp "$tmp/th.csv" "$tmp/th$n.csv"
done
cmp -s "$tmp/th1.csv" "$tmp/th2.csv" && cmp -s "$tmp/th1.csv" "$tmp/th3.csv" && ok ||
    bad "the CSV depends on the number of threads"
cmp -s "$tmp/th1.json" "$tmp/th2.json" && cmp -s "$tmp/th1.json" "$tmp/th3.json" && ok ||
    bad "the JSON depends on the number of threads"
[ -s "$tmp/fig/section.png" ] && ok || bad "no figure"
# without --chaos too, fixed-step scheme
for n in 1 2; do
    run 0 section -H "$HH" --energy 1/8 --surface x=0 --orbits 5 --crossings 40 --scheme \
        stormer-verlet-kdk --dt 0.05 --threads $n --out "$tmp/sv$n.csv"
done
cmp -s "$tmp/sv1.csv" "$tmp/sv2.csv" && ok || bad "stormer-verlet section depends on threads"
run 2 section -H "$HH" --energy 1/8 --surface x=0 --threads 0
err_has "--threads wants a whole number from 1 to 1024, not '0'"

# ---- Ctrl-C ----------------------------------------------------------------------
interrupted() { # WANT_RC SECONDS args... (as tests/cli/progress.sh)
    local want=$1 after=$2
    shift 2
    env --default-signal=INT "$HAMLIE" "$@" >"$tmp/out" 2>"$tmp/err" &
    local pid=$! i
    for i in $(seq 300); do grep -q "^hamlie [a-z]*: " "$tmp/err" && break; sleep 0.1; done
    sleep "$after"
    kill -INT "$pid" 2>/dev/null
    for i in $(seq 300); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null
    wait "$pid"
    local rc=$?
    if [ "$rc" -eq "$want" ]; then ok; else
        bad "hamlie $* interrupted: exit $rc, want $want"; sed 's/^/    /' "$tmp/err" >&2
    fi
}
interrupted 130 1 section -H "$HH" --energy 1/6 --surface x=0 --orbits 400 --crossings 3000 \
    --threads 2 --progress --out "$tmp/int.csv"
err_has "interrupted:"
ls "$tmp"/int.csv.tmp >/dev/null 2>&1 && bad "a .tmp left" || ok
if [ -e "$tmp/int.csv" ]; then # the orbits written are whole
    check_py "interrupted section: whole orbits" "$tmp/int.csv" <<'PYEOF'
import csv, sys, collections
n = collections.Counter(r["orbit"] for r in csv.DictReader(open(sys.argv[1])))
assert len(n) < 400 and all(v == 3000 for v in n.values()), n
PYEOF
else
    err_has "nothing written"
fi
interrupted 130 1 chaos -H "$HH" --init x=0,y=-0.1,px=0.56803755858823,py=0 --t 1e7 --progress
err_has "hamlie chaos: interrupted at t ="
[ ! -s "$tmp/out" ] && ok || bad "chaos printed after an interrupt"
interrupted 130 1 chaos -H "$HH" --init x=0,y=-0.1,px=0.56803755858823,py=0 --t 1e7 \
    --every 10 --progress
check_py "interrupted chaos --every: whole rows" "$tmp/out" <<'PYEOF'
import sys
lines = open(sys.argv[1]).read().split("\n")
assert lines[0].startswith("t,Y,mean_Y,fli,mlce") and lines[-1] == "", lines[:2]
rows = [l.split(",") for l in lines[1:-1]]
assert len(rows) >= 1 and all(len(r) == 9 for r in rows)
assert [float(r[0]) for r in rows] == [10.0 * (k + 1) for k in range(len(rows))]
PYEOF
finish
