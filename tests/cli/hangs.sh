#!/bin/bash
# Inputs that used to run for minutes (issue 13, the zoo's and the fuzzer's
# hangs).  Each must end within a few CPU seconds, refused: exit 2, a
# message that names the cause, nothing on stdout.
# usage (from the repo root): bash tests/cli/hangs.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: hangs.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
LIMIT=5 # CPU seconds; a hang is killed (exit 137 or 152)
ldd "$HAMLIE" 2>/dev/null | grep -q libasan && LIMIT=20

# refused TEXT args...: exit 2 under the limit, stdout empty, TEXT in stderr
refused() {
    local text=$1
    shift
    timeout $((6 * LIMIT)) bash -c 'ulimit -t "$1"; shift; exec "$@"' _ "$LIMIT" "$HAMLIE" "$@" \
        >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -eq 2 ]; then ok; else
        bad "hamlie $* exited $rc, want 2 (137, 152: over $LIMIT s of CPU)"; sed 's/^/    /' "$tmp/err" >&2
    fi
    if [ -s "$tmp/out" ]; then bad "stdout not empty for: hamlie $*"; else ok; fi
    err_has "$text"
}

OSC='(p^2+omega^2*x^2)/2'
# ---- exact powers whose value would have millions of bits -------------------
# 9.888...^9999.9 = (98888...9/10^33)^(99999/10): about 11 million bits
# (the fuzzer's input, also in fuzz/corpus/param)
refused "too large" generator -H "$OSC" --param 'omega=9^9.888888888888888888888888888888889^9999.9'
refused "too large" generator -H "$OSC" --param 'omega=9.888888888888888888888888888888889^99999'
refused "too large" generator -H '(p^2+x^2)/2 + x*9.888888888888888888888888888888889^9999.9'
refused "too large" generator -H '(p^2+x^2)/2 + x*(10^40+1/3)^99999'
refused "too large" generator -H '(p^2+x^2)/2 + x*(10/3)^(1/99999)'
refused "too large" generator -H 'x^(9^9^9)*p'
# --init is read in floating point: 10^9950 is refused as not finite
refused "not finite" run -H "$OSC" --param omega=1 --scheme rk4 --dt 0.1 --t 1 --json \
    --init 'x=9.888888888888888888888888888888889^9999.9,p=0'
refused "too large" canonical --map 'Q=q*(10^40+1/3)^99999; P=p' --pairs q:p
# below the limit they are exact: 2^1000 * 2^(-999) = 2, (3/2)^(1/2)^2 = 3/2
run 0 generator -H "(p^2+x^2*2^1000*2^(-999))/2"
has_text "2*x"
run 0 generator -H "(p^2+x^2*((3/2)^(1/2))^2)/2"
has_text "3*x/2"

# ---- the zoo's N7: an orbit that meets an essential singularity -------------
# dp/dt = -10 from p = 0.01: p = 0 (where sin(1/p) has an essential
# singularity) at t = 0.001; the steps shrink like p^2 there, so t creeps
# towards 0.001 and the step never underflowed
refused "no progress" run -H '10*q + sin(1/p)' --pairs q:p --scheme lie --tol 1e-12 --t 1 --json \
    --init q=0,p=0.01
# with 1/p the steps shrink like p, and the coefficients grow like p^-(k+1):
# at the order of tol 1e-12 (22, flow/rule.c) they overflow before the step
# underflows (at Jorba & Zou's 15 the step underflowed first)
refused "Taylor coefficients overflow" run -H '10*q + 1/p' --pairs q:p --scheme lie --tol 1e-12 --t 1 --json \
    --init q=0,p=0.01

# ---- the zoo's: gauss3 on a quadratic H that couples its pairs --------------
# its stage equations are linear: eliminated one unknown at a time, where
# each divisor's dependence on the 12 unknowns was a walk per divisor and
# unknown, and each value substituted alone (3.6 CPU s with 2 degrees of
# freedom, over a minute with 3; then 0.5 s).  The answer: Gauss-Legendre
# keeps a quadratic H to rounding, and its sixth order puts the state
# within 1e-10 of the exact flow exp(t A) z0 at dt = 0.1
quick=$((LIMIT * 2 / 5))
if timeout $((6 * quick)) bash -c 'ulimit -t "$1"; shift; exec "$@"' _ "$quick" "$HAMLIE" \
    run -H '(px^2+py^2)/2 + (x^2+y^2)/2 + k*x*y' --param k=1/4 --scheme gauss3 --dt 0.1 --t 1 \
    --init x=-0.522001,y=-0.948792,px=0.209525,py=0.730887 --no-reference --json \
    >"$tmp/out" 2>"$tmp/err"; then ok; else bad "gauss3 on a coupled oscillator: over $quick CPU s"; fi
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "gauss3 on a coupled oscillator"; cat "$tmp/py" >&2; }
import json, sys, mpmath
d = json.load(open(sys.argv[1]))
mpmath.mp.dps = 30
A = mpmath.matrix([[0, 0, 1, 0], [0, 0, 0, 1], [-1, -0.25, 0, 0], [-0.25, -1, 0, 0]])
z0 = mpmath.matrix([-0.522001, -0.948792, 0.209525, 0.730887])
z = mpmath.expm(A) * z0
f = d["final_state"]
got = [f["x"], f["y"], f["px"], f["py"]]
assert max(abs(got[i] - z[i]) for i in range(4)) < 1e-10, (got, z)
assert d["max_abs_dH"] < 1e-14, d["max_abs_dH"]
PYEOF
# The elimination itself was the cost: each stage solved by substitution
# doubled the values (3 pairs: 10 s, 4 pairs: minutes).  Stages coupled to
# each other are now Newton's: a chain of 4 pairs under the same limit,
# its H kept to rounding over 100 steps.
if timeout $((6 * quick)) bash -c 'ulimit -t "$1"; shift; exec "$@"' _ "$quick" "$HAMLIE" \
    run -H '(px^2+py^2+pz^2+pw^2)/2 + (x^2+y^2+z^2+w^2)/2 + k*(x*y+y*z+z*w)' --param k=1/4 \
    --scheme gauss3 --dt 0.1 --t 10 --init x=1,y=0,z=0,w=0,px=0,py=0,pz=0,pw=0 --no-reference \
    --json >"$tmp/out" 2>"$tmp/err"; then ok; else bad "gauss3 on a chain of 4 pairs: over $quick CPU s"; fi
pyjson 'assert d["max_abs_dH"] < 1e-14, d["max_abs_dH"]'
finish
