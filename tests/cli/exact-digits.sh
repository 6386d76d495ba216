#!/bin/bash
# hamlie exact --init --digits: the 1-dof exact scheme in Arb.  The period
# against the closed form 4 K(sin^2(q0/2)) (mpmath, 40 digits), the steps
# against the Arb integrator over the whole time (printed difference), the
# double scheme against the Arb one, and bad --digits.
# usage (from the repo root): bash tests/cli/exact-digits.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: exact-digits.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
PEND='p^2/2 - cos(q)'

run 0 exact -H "$PEND" --init q=1.3,p=0 --dt 125 --digits 40
T=$(sed -n 's/^in Arb at 40 digits: period T = //p' "$tmp/out")
if python3 -c "
import mpmath, sys
mpmath.mp.dps = 50
ref = 4 * mpmath.ellipk(mpmath.sin(mpmath.mpf('1.3') / 2) ** 2)
assert abs(mpmath.mpf('$T') - ref) < mpmath.mpf('1e-37'), (ref, '$T')
"; then ok; else bad "period $T against 4 K(sin^2(0.65))"; fi
diff=$(sed -n 's/^max difference from the Arb integrator over t = 1000: //p' "$tmp/out")
python3 -c "assert float('$diff') < 1e-33" && ok || bad "Arb steps vs integrator: $diff"
dd=$(sed -n 's/^max difference of the double exact scheme from it: //p' "$tmp/out")
python3 -c "assert float('$dd') < 1e-12" && ok || bad "double scheme vs Arb: $dd"

run 2 exact -H "$PEND" --init q=1.3,p=0 --digits 8
err_has "--digits must be from 16 to 1000"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
run 2 exact -H "$PEND" --init q=0,p=2 --digits 30
[ ! -s "$tmp/out" ] && ok || bad "output on a failure"
finish
