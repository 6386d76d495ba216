#!/bin/bash
# hamlie sweep on 1 and 2 threads: 10^4 members (the pendulum on a 100 x 100
# grid, rk4, dt 0.01 to t = 50: 5e7 steps in all), each configuration run
# REPS times alternately; the median wall time, its CPU time (user + sys),
# and the speed-up.  On a machine shared with other jobs the wall-time
# ratio understates the threads' gain: the CPU-time figures show whether
# the second thread costs work (they should be about equal).
# Also checks that both files are the same bytes.
# usage: bash bench/sweep_threads.sh path/to/hamlie [REPS]
set -u
HAMLIE=${1:?usage: sweep_threads.sh path/to/hamlie [REPS]}
REPS=${2:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(sweep -H 'p^2/2 - cos(q)' --grid 'q=-3:3:100,p=-2:2:100' --scheme rk4 --dt 0.01 --t 50
      --quiet)
for r in $(seq "$REPS"); do
    for th in 1 2; do
        /usr/bin/time -f "$th %e %U %S" -a -o "$tmp/times" "$HAMLIE" "${args[@]}" \
            --threads "$th" --out "$tmp/t$th.csv"
    done
done
cmp -s "$tmp/t1.csv" "$tmp/t2.csv" && echo "files: identical" || echo "files: DIFFER"
/usr/bin/python3 - "$tmp/times" <<'PYEOF'
import statistics, sys
t = {1: [], 2: []}
for line in open(sys.argv[1]):
    th, wall, user, sys_ = line.split()
    t[int(th)].append((float(wall), float(user) + float(sys_)))
med = {k: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v)) for k, v in t.items()}
for k in (1, 2):
    print("threads %d: wall %.2f s, cpu %.2f s (median of %d)" % (k, med[k][0], med[k][1], len(t[k])))
print("speed-up (wall): %.2fx; cpu(2)/cpu(1) = %.3f; members/s on 2 threads: %.0f"
      % (med[1][0] / med[2][0], med[2][1] / med[1][1], 1e4 / med[2][0]))
PYEOF
