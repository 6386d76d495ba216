#!/usr/bin/env bash
# Before/after against heyoka at equal error (issue 17): two builds of
# bench-work_precision (say, the main branch's and this one's) and heyoka,
# run one after the other system by system, for several rounds, so that the
# machine's load falls alike on all three; then the ratio of heyoka's time
# over each build's at that build's final error (bench/work_precision.py),
# per round, and the median over the rounds.
#
# Usage: bench/work_precision_ab.sh BEFORE-BENCH AFTER-BENCH [rounds] [out-dir]
#   BENCH: a bench-work_precision binary (copy it out of a build dir);
#   rounds 3; out-dir /tmp/work-precision-ab.
# Environment: WP_SYS (1,2,3: pendulum, Henon-Heiles, Kepler), WP_T (1e4,1e5),
#   WP_TOLS (1e-9,...,1e-16), WP_REPS (3: best of, within a run),
#   WP_REF (a file of 'ref' rows for Henon-Heiles, else made at 40 digits),
#   HEYOKA_PREFIX (/opt/heyoka).  Needs heyoka; CPU times, as work_precision.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
before=$1
after=$2
rounds=${3:-3}
out=${4:-/tmp/work-precision-ab}
systems=${WP_SYS:-1,2,3}
T=${WP_T:-1e4,1e5}
tols=${WP_TOLS:-1e-9,1e-10,1e-11,1e-12,1e-13,1e-14,1e-15,1e-16}
reps=${WP_REPS:-3}
hy=${HEYOKA_PREFIX:-/opt/heyoka}
py=/usr/bin/python3
mkdir -p "$out"
if [ ! -x "$out/work_precision_heyoka" ]; then
    g++ -O2 -DNDEBUG -std=c++20 -I"$hy/include" bench/work_precision_heyoka.cpp \
        -o "$out/work_precision_heyoka" -L"$hy/lib" -Wl,-rpath,"$hy/lib" \
        -lheyoka -lfmt -lboost_serialization 2>/dev/null
fi
ref=${WP_REF:-$out/ref.csv}
[ -s "$ref" ] || "$after" sys=2 T="$T" methods=none ref=40 >"$ref"

for r in $(seq "$rounds"); do
    for b in before after; do : >"$out/$b.$r.csv"; done
    : >"$out/heyoka.$r.csv"
    echo "# round $r $(date -u '+%T') load $(cut -d' ' -f1-3 /proc/loadavg)" >&2
    for s in ${systems//,/ }; do
        "$before" sys="$s" T="$T" tols="$tols" methods=native reps="$reps" >>"$out/before.$r.csv"
        "$after" sys="$s" T="$T" tols="$tols" methods=native reps="$reps" >>"$out/after.$r.csv"
        "$out/work_precision_heyoka" "$reps" "$T" "$tols" "$s" >>"$out/heyoka.$r.csv"
    done
    for b in before after; do
        $py bench/work_precision.py "$ref" "$out/$b.$r.csv" "$out/heyoka.$r.csv" \
            >"$out/report.$b.$r.md"
    done
done

# the summary rows (| system | T | heyoka/hamlie-native median (min-max, n) | ...) per
# round, and the median of the rounds' medians
$py - "$out" "$rounds" <<'PY'
import re, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
table = {}
for b in ("before", "after"):
    for r in range(1, rounds + 1):
        text = open("%s/report.%s.%d.md" % (out, b, r)).read()
        part = text.split("## Time of the peer")[1]
        for m in re.finditer(r"^\| ([a-z-]+) \| ([0-9e+.]+) \| ([0-9.]+) \(([0-9.]+)-([0-9.]+), (\d+)\)",
                             part, re.M):
            table.setdefault((m[1], float(m[2])), {}).setdefault(b, []).append(
                (float(m[3]), float(m[4]), float(m[5]), int(m[6])))
print("| heyoka / hamlie-native at equal error | before: median of rounds (per round) "
      "| after: median of rounds (per round) |")
print("|---|---|---|")
for (s, T), d in sorted(table.items()):
    cells = []
    for b in ("before", "after"):
        v = d.get(b, [])
        med = statistics.median(x[0] for x in v) if v else float("nan")
        cells.append("%.2f (%s; n %s)" % (med, " ".join("%.2f" % x[0] for x in v),
                                          "/".join(str(x[3]) for x in v)))
    print("| %s, %g | %s |" % (s, T, " | ".join(cells)))
PY
