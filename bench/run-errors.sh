#!/usr/bin/env bash
# Error-analysis benchmark (issue 4): RK4 on Hénon–Heiles and the implicit
# midpoint rule on the pendulum, v_2..v_8, hamlie against SymPy.
# Usage: bench/run-errors.sh [build-dir] [--check]   (default: build)
#   hamlie core:    bench-errors_analysis: expansion + v_k by the direct route
#                   (what SymPy does), and with the K(D) cross-check (best of 5)
#   hamlie command: the whole `hamlie errors ... --order 8` (wall time, one run)
#   --check: v_3 and v_5 of both cases compared (sympy.simplify(a - b) == 0)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
HH='(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3'
PD='p^2/2 - cos(q)'
[ -x "$build/bench-errors_analysis" ] || cmake --build "$build" --target bench-errors_analysis >/dev/null
[ -x "$build/hamlie" ] || cmake --build "$build" --target hamlie_cli >/dev/null

if [ "${2:-}" = "--check" ]; then
    tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
    python3 bench/errors_sympy.py --check --order=5 >"$tmp/sympy"
    "$build/hamlie" errors -H "$HH" --scheme rk4 --order 5 --json >"$tmp/rk4"
    "$build/hamlie" errors -H "$PD" --scheme implicit-midpoint --order 5 --json >"$tmp/mid"
    python3 - "$tmp" <<'PY'
import json, sys
import sympy as sp
d = sys.argv[1]
sy = {c["case"]: c for c in map(json.loads, open(d + "/sympy").read().splitlines())}
ham = {"rk4-henon-heiles": json.load(open(d + "/rk4")), "midpoint-pendulum": json.load(open(d + "/mid"))}
bad = 0
for case, h in ham.items():
    names = h["symbols"]["coordinates"] + h["symbols"]["momenta"]
    hv = {f["k"]: f["v"] for f in h["fields"]}
    for k in (3, 5):
        for i, z in enumerate(names):
            a, b = sp.sympify(sy[case][f"v{k}"][i]), sp.sympify(hv[k][z])
            ok = sp.simplify(a - b) == 0
            bad |= not ok
            print(f"{case:18} v_{k}({z:2}) {'same' if ok else 'DIFFER'}  sympy: {a}")
sys.exit(bad)
PY
    exit
fi

ours=$("$build/bench-errors_analysis" 5)
t0=$(date +%s.%N); "$build/hamlie" errors -H "$HH" --scheme rk4 --order 8 >/dev/null; t1=$(date +%s.%N)
"$build/hamlie" errors -H "$PD" --scheme implicit-midpoint --order 8 >/dev/null; t2=$(date +%s.%N)
cmd="rk4-henon-heiles $(echo "$t1 - $t0" | bc)
midpoint-pendulum $(echo "$t2 - $t1" | bc)"
theirs=$(python3 bench/errors_sympy.py)
python3 - "$ours" "$cmd" "$theirs" <<'PY'
import sys
rows = [{l.split()[0]: l.split() for l in a.splitlines()} for a in sys.argv[1:]]
ours, cmd, theirs = rows
print(f"{'case':18} {'order':>5} {'direct s':>9} {'+K s':>8} {'command s':>10} {'sympy s':>8}"
      f" {'ratio':>7} {'ratio+K':>8}")
def ratio(ts, t):
    return f"{float(ts)/float(t):6.0f}x" if ts != "timeout" else "  >600s"
for name, (n, order, t, tk) in ours.items():
    ts = theirs[name][2]
    print(f"{name:18} {order:>5} {float(t):9.4f} {float(tk):8.4f} {float(cmd[name][1]):10.3f}"
          f" {ts:>8} {ratio(ts, t):>7} {ratio(ts, tk):>8}")
PY
