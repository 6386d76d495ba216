#!/bin/bash
# Issue 13, N3: a scheme that claims to preserve H (avf, itoh-abe, gonzalez)
# either returns steps that keep H to rounding, or stops with exit 2 and a
# message naming the step; never exit 0 with H changed.  Near Kepler's
# collision AVF's Gauss rule for int_0^1 grad H(z + s(Z - z)) ds was
# inaccurate and H went from -0.737 to 18.07 in one step, with exit 0.
# H0 is computed here from the initial point, not read from the program.
# usage (from the repo root): bash tests/cli/preserves-h.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: preserves-h.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

KEPLER='(px^2+py^2)/2 - 1/sqrt(x^2+y^2)'
NEAR='x=-0.85292,y=0.741467,px=0.285809,py=-0.46234'

# kept CASE X Y PX PY TOL: the last run's JSON has exit 0 (checked by run)
# and every |H - H0| <= TOL, H0 Kepler's energy at (X, Y, PX, PY)
kept() {
    if python3 - "$tmp/out" "$@" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "H not kept: $1"; sed 's/^/    /' "$tmp/py" >&2; fi
import json, math, sys
case, x, y, px, py, tol = sys.argv[2], *map(float, sys.argv[3:8])
d = json.load(open(sys.argv[1]))
H0 = (px * px + py * py) / 2 - 1 / math.hypot(x, y)
assert abs(d["H0"] - H0) <= 1e-15, (d["H0"], H0)
assert d["max_abs_dH"] <= tol, (case, d["max_abs_dH"])
assert abs(d["H_final"] - H0) <= tol, (case, d["H_final"], H0)
PYEOF
}

# near the collision: conserved to 1e-12, or refused (exit 2, nothing on
# stdout, the step named)
for scheme in avf itoh-abe gonzalez; do
    "$HAMLIE" run -H "$KEPLER" --scheme "$scheme" --dt 0.1 --t 2 --init "$NEAR" \
        --no-reference --json >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -eq 0 ]; then
        ok
        kept "$scheme near collision" -0.85292 0.741467 0.285809 -0.46234 1e-12
    elif [ "$rc" -eq 2 ] && [ ! -s "$tmp/out" ]; then
        ok
        err_has "step 9 (t = 0.8"
    else
        bad "$scheme near Kepler's collision: exit $rc (want 0 with H kept, or 2)"
        sed 's/^/    /' "$tmp/err" >&2
    fi
done
# AVF's refusal says why
run 2 run -H "$KEPLER" --scheme avf --dt 0.1 --t 2 --init "$NEAR" --no-reference --json
err_has "the scheme 'avf' preserves H, but this step changes it"

# the same orbit before it comes close: accepted, H kept to rounding
for scheme in avf itoh-abe; do
    run 0 run -H "$KEPLER" --scheme "$scheme" --dt 0.1 --t 0.5 --init "$NEAR" \
        --no-reference --json
    kept "$scheme before the collision" -0.85292 0.741467 0.285809 -0.46234 1e-13
done
# away from collisions (e = 0.5 from the pericentre, 0.5 from the origin)
for scheme in avf itoh-abe gonzalez; do
    run 0 run -H "$KEPLER" --scheme "$scheme" --dt 0.05 --t 10 \
        --init x=0.5,y=0,px=0,py=1.7320508075688772 --no-reference --json
    kept "$scheme e = 0.5" 0.5 0 0 1.7320508075688772 1e-13
done

finish
