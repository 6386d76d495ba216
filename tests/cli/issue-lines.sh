#!/bin/bash
# The command lines of the issues, run as written (with the values an issue
# leaves as "..." filled in): each must exit as stated and say what it is
# for.  A guard against a name or an option drifting away from what was
# promised (as `--scheme stormer-verlet` once did).
# usage (from the repo root): bash tests/cli/issue-lines.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: issue-lines.sh path/to/hamlie}
case $HAMLIE in /*) ;; *) HAMLIE=$PWD/$HAMLIE ;; esac
. "$(dirname "$0")/lib/harness.sh"
mkdir "$tmp/work" && cd "$tmp/work" || exit 1 # $tmp/out is the harness's

OSC='(p^2+x^2)/2'
PEND='p^2/2 - cos(q)'
KEPLER='(px^2+py^2)/2 - 1/sqrt(x^2+y^2)'
HH='(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3'

# issue 3: the foundation
run 0 generator -H "$OSC"
has_line '𝔤 = p ∂/∂x − x ∂/∂p'
run 0 generator -H "$KEPLER" --latex
run 0 bracket -H "$KEPLER" 'x*py - y*px' 'H'
has_text '= 0'
run 0 check -H "$KEPLER" --integral 'x*py-y*px' --integral 'py*(x*py-y*px) - x/sqrt(x^2+y^2)'
run 1 canonical --map 'X = x + D*p; P = p - D*x'
has_text '1 + D^2'
run 0 lie -H "$PEND" --order 6
run 0 lie -H "$OSC" --order 8 --of 'x^2 - p'

# issue 4: schemes and their error analysis (each also with --json, --latex)
for f in "" --json --latex; do
    run 0 schemes $f
    run 0 errors -H "$OSC" --scheme euler --order 7 $f
    run 0 errors -H "$OSC" --map 'X = (4*x+4*D*p-D^2*x)/(4+D^2); P = (4*p-4*D*x-D^2*p)/(4+D^2)' --order 7 $f
    run 0 errors -H "$OSC" --equations '(X-x)/D = (P+p)/2; (P-p)/D = -(X+x)/2' --order 7 $f
    run 0 errors -H "$PEND" --scheme implicit-midpoint --order 6 $f
    run 0 errors -H "$HH" --scheme rk4 --order 6 $f
    run 0 errors -H "$OSC" --scheme euler --order 6 --correct 4 $f
done
run 0 errors -H "$OSC" --scheme euler --order 6 --correct 4
has_text 'order: 4'
run 0 errors -H "$PEND" --scheme implicit-midpoint --order 6
has_text 'modified Hamiltonian: H~ = p^2/2 - cos(q) - D^2/24*(p^2*cos(q) - cos(q)^2)'

# issue 5: running schemes
run 0 run -H "$OSC" --scheme euler --dt 0.1 --t 20 --init x=1,p=0
has_line 't,x,p,H,sigma'
run 0 run -H "$PEND" --scheme stormer-verlet --dt 0.01 --t 1e4 --init q=1.3,p=0 --out run.csv --json
[ -s run.csv ] && ok || bad "run.csv not written"
run 0 run -H "$KEPLER" --scheme lie --tol 1e-15 --t 1e4 --init x=0.5,y=0,px=0,py=1.7320508075688772 --json
run 0 run -H "$KEPLER" --scheme lie --digits 50 --t 10 --init x=0.5,y=0,px=0,py=1.7320508075688772 --json
run 0 run -H "$PEND" --scheme gauss2 --dt 0.1 --t 2 --init q=1.3,p=0 --orders 0.1,0.05,0.025
run 0 run -H "$OSC" --map 'X = x + D*p; P = p - D*x' --dt 0.1 --t 1 --init x=1,p=0
run 0 run -H "$PEND" --equations '(Q-q)/D = (p+P)/2; (P-p)/D = -sin((q+Q)/2)' --dt 0.1 --t 1 --init q=1.3,p=0
run 0 errors -H "$PEND" --scheme rk4 --at 'q=1.3,p=0' --order 8 --numeric
has_text 'order: 4'

# issue 6: exact schemes
run 0 exact -H "$OSC" --steps
has_line '  X = x*cos(D) + p*sin(D)'
run 0 exact -H '(px^2+py^2)/2+(x^2+4*y^2)/2'
run 0 exact -H "$PEND" --init q=1.3,p=0
has_text 'period T = 7.01925031184'
run 0 exact -H "$OSC" --action-angle 'theta = atan2(x, p); I = (p^2+x^2)/2; x = sqrt(2*I)*sin(theta); p = sqrt(2*I)*cos(theta); nu = 1'
run 0 run -H "$PEND" --scheme exact --dt 0.5 --t 1000 --init q=1.3,p=0 --json
python3 -c 'import json, sys; d = json.load(open(sys.argv[1]))
assert d["max_error"] < 1e-12 and d["max_abs_dH"] < 1e-14, d' "$tmp/out" && ok ||
    bad "run --scheme exact on the pendulum: $(cat "$tmp/out")"

# issue 7: the paper, and plots of any run
run 0 reproduce --format png
has_text 'formulas'
[ -f out/paper/report.md ] && [ -f out/paper/euler-phase.png ] && ok || bad "reproduce: out/paper incomplete"
run 0 reproduce --out paper2 --format png,svg,pdf
[ "$(ls paper2 | grep -c '\.\(png\|svg\|pdf\)$')" -eq 42 ] && ok || bad "reproduce --out: not 42 figure files"
run 0 run -H "$OSC" --scheme euler --dt 0.1 --t 20 --init x=1,p=0 --plot figs
[ -f figs/phase-x-p.png ] && ok || bad "run --plot: no phase portrait"
run 0 plot run.csv --out figs2
[ -f figs2/phase-q-p.png ] && ok || bad "plot: no phase portrait"

finish
