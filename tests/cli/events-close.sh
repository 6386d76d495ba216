#!/bin/bash
# run --event: two crossings far closer than a Taylor step are both found
# (the roots are isolated on g's own series over the step).  The oscillator
# (p^2 + x^2)/2 from x = 0, p = 1 is x = sin t; the surface x = 1 - eps is
# crossed at pi/2 + 2 pi k -+ acos(1 - eps), 2 sqrt(2 eps) apart (2.8e-2
# down to 2.8e-6 here, against steps of ~0.8).  Each crossing time is
# checked against that closed form to the root's conditioning:
# |dt| sin(acos(1 - eps)) < 1e-13.  The surface is affine (the fast path:
# g's series along the step is exact) and, written as x^3 = (1 - eps)^3,
# not (the tape's Taylor mode: g's series is truncated at the step's order,
# so pairs between which g departs from 0 by less than about the
# integrator's tolerance can still be missed: 3e-12 at eps = 1e-12 is
# below that line and not tested).
# usage (from the repo root): bash tests/cli/events-close.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: events-close.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PY=/usr/bin/python3

for eps in 1e-4 1e-8 1e-12; do
    surfaces=("x = 1 - $eps")
    [ "$eps" != 1e-12 ] && surfaces+=("x^3 = (1 - $eps)^3")
    for surface in "${surfaces[@]}"; do
        for dir in up down both; do
            run 0 run -H '(p^2+x^2)/2' --scheme lie --tol 1e-13 --init x=0,p=1 --t 40 \
                --event "$surface" --direction $dir --json
            if $PY - "$tmp/out" "$eps" "$dir" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "close crossings: $surface $dir"; cat "$tmp/py" >&2; fi
import json, math, sys
d = json.load(open(sys.argv[1]))
eps, dirn = float(sys.argv[2]), sys.argv[3]
a = 1 - eps
w = math.acos(a)
want = sorted(math.pi / 2 + 2 * math.pi * k + s * w for k in range(8) for s in (-1, 1)
              if (dirn == "both" or (s < 0) == (dirn == "up")) and math.pi / 2 + 2 * math.pi * k + s * w < 40)
got = [c["t"] for c in d["event"]["table"]]
assert len(got) == len(want), (len(got), len(want))
worst = max(abs(g - t) for g, t in zip(got, want)) * math.sin(w)
assert worst < 1e-13, worst
PYEOF
        done
    done
done
# An orbit that lies in the surface (the pendulum at rest at q = 0, the
# section q = 0): g is 0 along every step, no sign changes, no crossing.
# The root isolation once bisected such a step 2^40 ways (a sweep with
# --event q=0 on that grid point never ended); now it is told at once.
# at_rest ARGS...: hamlie ARGS on it, under 10 CPU seconds
at_rest() {
    timeout 60 bash -c 'ulimit -t 10; exec "$@"' _ "$HAMLIE" "$@" -H 'p^2/2 - cos(q)' --scheme lie \
        --dt 0.1 --t 30 --event q=0 >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ $rc -eq 0 ]; then ok; else bad "at rest on the surface: hamlie $1 exited $rc"; fi
}
at_rest run --init q=0,p=0 --json
if $PY -c 'import json, sys; assert json.load(open(sys.argv[1]))["event"]["table"] == []' "$tmp/out"; then
    ok
else bad "at rest: crossings in the run"; fi
at_rest sweep --grid q=0,p=0 --out "$tmp/rest.csv"
if [ "$(cat "$tmp/rest-cross.csv")" = "member,t,q,p" ]; then ok; else bad "at rest: crossings in the sweep"; fi
finish
