#!/bin/bash
# hamlie reproduce: from an empty folder, on its defaults, all 14 figures in
# png, svg and pdf plus report.md and report.tex, exit 0; the summary lists
# the formulas that differ from the paper's print; --json agrees with the
# report; a folder that cannot be written (under a regular file) or a bad
# --format is exit 2 with nothing half-written.
# usage (from the repo root): bash tests/cli/reproduce.sh path/to/hamlie
set -u
HAMLIE=$(cd "$(dirname "${1:?usage: reproduce.sh path/to/hamlie}")" && pwd)/$(basename "$1")
. "$(dirname "$0")/lib/harness.sh"

FIGS="exact-phase exact-x exact-p exact-error euler-phase euler-x euler-p euler-inv
euler-error disgra-phase disgra-x disgra-p disgra-inv disgra-error"

mkdir "$tmp/w"
cd "$tmp/w" || exit 2
run 0 reproduce
missing=0
for f in $FIGS; do
    for e in png svg pdf; do
        [ -s "out/paper/$f.$e" ] || { missing=1; echo "missing out/paper/$f.$e" >&2; }
    done
done
[ "$missing" -eq 0 ] && ok || bad "figures missing"
[ -s out/paper/report.md ] && [ -s out/paper/report.tex ] && ok || bad "report missing"
n=$(ls out/paper | wc -l)
[ "$n" -eq 44 ] && ok || bad "out/paper has $n files, want 42 figures + 2 reports (no temporaries)"
# magic numbers
head -c 8 out/paper/euler-phase.png | grep -q PNG && ok || bad "euler-phase.png is not a PNG"
head -c 5 out/paper/euler-phase.pdf | grep -q '%PDF' && ok || bad "euler-phase.pdf is not a PDF"
grep -q '<svg' out/paper/euler-phase.svg && ok || bad "euler-phase.svg is not an SVG"
# the summary: counts and the known misprints, each with its correct expression
has_text "14 x png,svg,pdf written; closed-form checks: 14 passed, 0 failed"
has_text "differs  euler-v3"
has_text "correct: p ∂/∂x − x ∂/∂p"
has_text "differs  dg-W"
has_text "correct: 2*atan(D/2) - D"
has_text "differs  dg-K"
has_text "correct: 4*p/(4 + D^2) ∂/∂x − 4*x/(4 + D^2) ∂/∂p"
has_text "report    out/paper/report.md, out/paper/report.tex"
# the report's table has a row per formula and the figures
grep -q '^| \*\*euler-v3\*\*:.*| \*\*differs\*\* |' out/paper/report.md && ok || bad "report.md: euler-v3 row"
grep -q '^| \*\*dg-v5\*\*:.*| agrees |' out/paper/report.md && ok || bad "report.md: dg-v5 row"
[ "$(grep -c '^!\[' out/paper/report.md)" -eq 14 ] && ok || bad "report.md: 14 figures"
[ "$(grep -c 'includegraphics' out/paper/report.tex)" -eq 14 ] && ok || bad "report.tex: 14 figures"

# --json, --format png, another folder: the verdicts match the report
run 0 reproduce --out other --format png --json
if python3 - "$tmp/out" <<'PYEOF'; then ok; else bad "--json summary"; fi
import json, sys, os
d = json.load(open(sys.argv[1]))
assert d["out"] == "other" and d["formats"] == "png"
assert len(d["figures"]) == 14 and all(f["check_passed"] for f in d["figures"])
# the deviations are numbers, and check_passed is what they say
assert all(isinstance(f[k], float) for f in d["figures"] for k in ("check", "check_tol"))
assert all(f["check_passed"] == (f["check"] <= f["check_tol"]) for f in d["figures"])
v = {f["id"]: f["verdict"] for f in d["formulas"]}
differ = sorted(k for k, x in v.items() if x == "differs")
assert differ == sorted(["euler-v3", "dg-K", "dg-W", "dg-ahead", "rel-3"]), differ
md = open("other/report.md").read()
for k, x in v.items():
    line = [l for l in md.splitlines() if l.startswith("| **%s**:" % k)]
    assert len(line) == 1, k
    assert ("| **differs** |" in line[0]) == (x == "differs"), k
files = sorted(os.listdir("other"))
assert len(files) == 16 and all(f.endswith((".png", ".md", ".tex")) for f in files), files
PYEOF

# a folder that cannot be created: exit 2, nothing written
: >"$tmp/w/plain"
run 2 reproduce --out "$tmp/w/plain/sub"
[ -f "$tmp/w/plain" ] && [ ! -s "$tmp/w/plain" ] && ok || bad "the regular file was touched"
err_has "plain/sub"
# a bad format list: exit 2, the folder stays empty
mkdir "$tmp/w/empty"
run 2 reproduce --out "$tmp/w/empty" --format png,gif
[ -z "$(ls -A "$tmp/w/empty")" ] && ok || bad "files written despite a bad --format"
# usage errors
run 2 reproduce extra-arg
run 2 reproduce -H 'p^2/2'
run 0 reproduce --help
has_text "usage: hamlie reproduce"
finish
