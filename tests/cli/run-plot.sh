#!/bin/bash
# hamlie run --plot DIR: the run's figures drawn as it goes.  The same figures
# as `hamlie plot` draws from the run's CSV (compared file by file: the PNGs
# must be identical), the formats asked for, and no CSV left when the figures
# cannot be written.
# usage (from the repo root): bash tests/cli/run-plot.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: run-plot.sh path/to/hamlie}
case $HAMLIE in /*) ;; *) HAMLIE=$PWD/$HAMLIE ;; esac
. "$(dirname "$0")/lib/harness.sh"

OSC='(p^2+x^2)/2'
EULER=(run -H "$OSC" --scheme euler --dt 0.1 --t 20 --init x=1,p=0 --observe x/p)

# --plot beside --out: six figures, and the same bytes as hamlie plot's from the CSV
run 0 "${EULER[@]}" --out "$tmp/euler.csv" --plot "$tmp/a"
err_has "drew 6 figure files in $tmp/a"
run 0 plot "$tmp/euler.csv" --out "$tmp/b" # label: the file name, as run's
n=0
for f in "$tmp"/b/*.png; do
    n=$((n + 1))
    g=$tmp/a/$(basename "$f")
    if cmp -s "$f" "$g"; then ok; else bad "$g differs from hamlie plot's $(basename "$f")"; fi
done
if [ "$n" -eq 6 ]; then ok; else bad "hamlie plot drew $n PNGs, want 6"; fi
[ -f "$tmp/a/phase-x-p.png" ] && ok || bad "no phase-x-p.png"

# --json without --out: no CSV, the figures still drawn, counted in the summary
run 0 "${EULER[@]}" --json --plot "$tmp/c" --format svg,pdf
python3 -c 'import json, sys; d = json.load(open(sys.argv[1]))
assert d["figure_files"] == 12 and d["plot"].endswith("/c") and d["out"] is None' "$tmp/out" &&
    ok || bad "JSON summary of --plot: $(cat "$tmp/out")"
[ -f "$tmp/c/time-x.svg" ] && [ -f "$tmp/c/time-x.pdf" ] && [ ! -f "$tmp/c/time-x.png" ] && ok ||
    bad "--format svg,pdf not honoured"

# figures that cannot be written: exit 2, no CSV left behind
run 2 "${EULER[@]}" --out "$tmp/f.csv" --plot /proc/no/such
err_has "in --plot"
[ ! -e "$tmp/f.csv" ] && [ ! -e "$tmp/f.csv.tmp" ] && ok || bad "a CSV was left after --plot failed"

# usage
run 2 "${EULER[@]}" --format png
err_has "--format is for the figures of --plot DIR"
run 2 run -H "$OSC" --scheme euler --orders 0.1,0.05 --t 1 --init x=1,p=0 --plot "$tmp/d"
err_has "not with --orders"

finish
