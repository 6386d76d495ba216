#!/bin/bash
# Arb is loaded on first use (src/cli/arb_lazy.c): the module does not link
# libflint-arb; `lie` and `bracket` never load it (ld.so's trace); a command
# that computes in Arb loads it and gets the right digits (the pendulum's
# period against 4 K(sin^2(q0/2)), mpmath); without it: exit 2, the reason,
# and nothing on stdout.
# usage (from the repo root): bash tests/cli/arb-lazy.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: arb-lazy.sh path/to/hamlie}
case $HAMLIE in /*) ;; *) HAMLIE=$PWD/$HAMLIE ;; esac
. "$(dirname "$0")/lib/harness.sh"

loaded() { cat "$tmp"/ld.* 2>/dev/null | grep -E 'file=[^ ]*libflint-arb[^ ]* +\[0\]; +(needed|dynamically loaded)' -q; }
traced() { rm -f "$tmp"/ld.*; LD_DEBUG=files LD_DEBUG_OUTPUT=$tmp/ld run "$@"; }

MODULE=$(dirname "$HAMLIE")/hamlie-cli.so
if readelf -d "$MODULE" | grep -q 'NEEDED.*arb'; then bad "$MODULE is linked with Arb"; else ok; fi

traced 0 lie -H '(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3' --order 6
has_text "exp(D 𝔤) x = x + D*px"
if loaded; then bad "lie loaded libflint-arb"; else ok; fi
traced 0 bracket -H 'p^2/2 - 1/sqrt(q^2)' q p
if loaded; then bad "bracket loaded libflint-arb"; else ok; fi

PEND='p^2/2 - cos(q)'
traced 0 exact -H "$PEND" --init q=1.3,p=0 --dt 125 --digits 30
if loaded; then ok; else bad "exact --digits did not load libflint-arb"; fi
T=$(sed -n 's/^in Arb at 30 digits: period T = //p' "$tmp/out")
if /usr/bin/python3 -c "
import mpmath
mpmath.mp.dps = 40
ref = 4 * mpmath.ellipk(mpmath.sin(mpmath.mpf('1.3') / 2) ** 2)
assert abs(mpmath.mpf('$T') - ref) < mpmath.mpf('1e-27'), (ref, '$T')
"; then ok; else bad "period '$T' against 4 K(sin^2(0.65))"; fi

HAMLIE_ARB_LIB=/nonexistent/libflint-arb.so.2 run 2 exact -H "$PEND" --init q=1.3,p=0 --digits 30
err_has "cannot load /nonexistent/libflint-arb.so.2: this command computes with Arb"
[ ! -s "$tmp/out" ] && ok || bad "output on a failure: $(head -c 200 "$tmp/out")"
HAMLIE_ARB_LIB=libm.so.6 run 2 exact -H "$PEND" --init q=1.3,p=0 --digits 30
err_has "in libm.so.6: this command computes with Arb"
finish
