#!/usr/bin/env bash
# Lie series benchmark (issue 3): hamlie against SymPy on the same machine.
# Usage: bench/run-lie.sh [build-dir]     (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
[ -x "$build/bench-lie_series" ] || cmake --build "$build" --target bench-lie_series >/dev/null

ours=$("$build/bench-lie_series" 5)
theirs=$(python3 bench/lie_sympy.py)
python3 - "$ours" "$theirs" <<'PY'
import sys
ours = {l.split()[0]: l.split() for l in sys.argv[1].splitlines()}
theirs = {l.split()[0]: l.split() for l in sys.argv[2].splitlines()}
print(f"{'system':14} {'order':>5} {'hamlie s':>10} {'sympy s':>10} {'ratio':>8} {'terms':>8}")
for name, (n, order, t, terms) in ours.items():
    ts = float(theirs[name][2])
    print(f"{name:14} {order:>5} {float(t):10.4f} {ts:10.3f} {ts/float(t):7.0f}x {terms:>8}")
PY
