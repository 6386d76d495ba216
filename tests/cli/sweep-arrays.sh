#!/bin/bash
# sweep --save-every K / --event G --direction D: every member's trajectory
# and crossings (issue 15, parts 4 and 7):
#  - crossings of q = 0 upward by the harmonic oscillator q = a cos t,
#    p = -a sin t against the closed form: t = 3 pi/2 + 2 pi k, p = a (to
#    1e-12 with lie, to the Hermite interpolant's 1e-5 with rk4 at dt 0.1);
#    down and both directions counted;
#  - each member's trajectory equals `hamlie run --every K` of its start,
#    bit for bit (17 digits), and the closed form with lie;
#  - h5py reads /trajectories and /crossings (data, offsets, columns), the
#    same numbers as the CSV sidecars; the summary is unchanged by asking
#    for arrays;
#  - the same bytes with 1 and 2 threads (HDF5 and CSV sidecars), and after
#    a kill -9 mid-sweep and --resume (the journal carries the arrays);
#  - bad input: an event formula error (with its position), an unknown
#    symbol, --save-every 0, --direction without --event, arrays without
#    --out: exit 2, nothing written.
# usage (from the repo root): bash tests/cli/sweep-arrays.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: sweep-arrays.sh path/to/hamlie}
case $HAMLIE in /*) ;; *) HAMLIE=$PWD/$HAMLIE ;; esac
. "$(dirname "$0")/lib/harness.sh"
cd "$tmp" || exit 2
PY=/usr/bin/python3
pycheck() {
    local code=$1
    shift
    if $PY -c "import sys, csv, math, numpy as np
$code" "$@" >"$tmp/py" 2>&1; then ok; else bad "python check: $code"; sed 's/^/    /' "$tmp/py" >&2; fi
}

# ---- the oscillator: crossings against the closed form -----------------------
HO=(sweep -H '(p^2+q^2)/2' --grid 'q=0.5:2:4,p=0' --scheme lie,rk4 --dt 0.1 --t 20 --quiet)
run 0 "${HO[@]}" --event q --direction up --save-every 10 --out ho.csv
pycheck '
rows = list(csv.DictReader(open("ho-cross.csv")))
assert list(rows[0].keys()) == ["member", "t", "q", "p"], rows[0].keys()
summ = list(csv.DictReader(open("ho.csv")))
assert len(summ) == 8
by = {}
for r in rows:
    by.setdefault(int(r["member"]), []).append(r)
for m, s in enumerate(summ):
    a, lie = float(s["q0"]), s["scheme"] == "lie"
    want = [1.5 * math.pi + 2 * math.pi * k for k in range(4) if 1.5 * math.pi + 2 * math.pi * k <= 20]
    got = by.get(m, [])
    assert len(got) == len(want) == 3, (m, len(got), want)
    tol = 1e-12 if lie else 1e-5
    for r, t in zip(got, want):
        assert abs(float(r["t"]) - t) < tol * (1 + t), (m, r["t"], t)
        assert abs(float(r["q"])) < tol and abs(float(r["p"]) - a) < tol * 10, (m, r)
'
# down: at pi/2 + 2 pi k (3 before 20); both: every pi/2 + pi k (6)
run 0 "${HO[@]}" --event 'q = 0' --direction down --out down.csv
run 0 "${HO[@]}" --event q --out both.csv
pycheck '
down = [r for r in csv.DictReader(open("down-cross.csv")) if r["member"] == "0"]
both = [r for r in csv.DictReader(open("both-cross.csv")) if r["member"] == "0"]
assert [round(float(r["t"]) / (math.pi / 2)) for r in down] == [1, 5, 9], down
assert [round(float(r["t"]) / (math.pi / 2)) for r in both] == [1, 3, 5, 7, 9, 11], both
'
# the trajectory of member 5 (q0 = 1.5, rk4) is that of hamlie run, bit for bit
"$HAMLIE" run -H '(p^2+q^2)/2' --scheme rk4 --init q=1.5,p=0 --dt 0.1 --t 20 --every 10 \
    --no-reference >run.csv 2>/dev/null || bad "hamlie run failed"
pycheck '
traj = [r for r in csv.DictReader(open("ho-traj.csv")) if r["member"] == "5"]
ref = list(csv.DictReader(open("run.csv")))
assert len(traj) == len(ref) == 21, (len(traj), len(ref))
for a, b in zip(traj, ref):
    assert [float(a[k]) for k in ("t", "q", "p")] == [float(b[k]) for k in ("t", "q", "p")], (a, b)
# lie (member 4) against the closed form, at t = k
for r in (r for r in csv.DictReader(open("ho-traj.csv")) if r["member"] == "4"):
    t = float(r["t"])
    assert abs(float(r["q"]) - 1.5 * math.cos(t)) < 1e-12 and abs(float(r["p"]) + 1.5 * math.sin(t)) < 1e-12, r
'
# asking for arrays leaves the summary as it was
run 0 "${HO[@]}" --out plain.csv
if cmp -s plain.csv ho.csv; then ok; else bad "the summary changed with --save-every/--event"; fi

# ---- HDF5: h5py reads the ragged arrays, the same numbers as the CSV ----------
if "$HAMLIE" "${HO[@]}" --event q --direction up --save-every 10 --out ho.h5 --threads 1 2>h5err; then
    ok
    run 0 "${HO[@]}" --event q --direction up --save-every 10 --out ho2.h5 --threads 2
    if cmp -s ho.h5 ho2.h5; then ok; else bad "the HDF5 file with arrays differs with 2 threads"; fi
    pycheck '
import h5py
f = h5py.File("ho.h5", "r")
for g, name in (("trajectories", "ho-traj.csv"), ("crossings", "ho-cross.csv")):
    d, off = f[g + "/data"], f[g + "/offsets"][:]
    assert list(d.attrs["columns"]) == ["member", "t", "q", "p"], d.attrs["columns"]
    assert off.dtype == np.int64 and len(off) == 9 and off[0] == 0 and off[-1] == d.shape[0]
    rows = list(csv.DictReader(open(name)))
    want = np.array([[float(r[k]) for k in ("member", "t", "q", "p")] for r in rows])
    assert np.array_equal(d[:], want), g
    for m in range(8):
        assert (d[off[m]:off[m + 1], 0] == m).all()
assert f["trajectories"].attrs["save_every"] == 10
assert f["crossings"].attrs["event"] == "q" and f["crossings"].attrs["direction"] == "up"
assert np.diff(f["trajectories/offsets"][:]).tolist() == [21] * 8
'
else
    echo "note: no HDF5 here: $(head -1 h5err)"
fi

# ---- 1 and 2 threads: the same sidecars ----------------------------------------
run 0 "${HO[@]}" --event q --save-every 7 --out t1.csv --threads 1
run 0 "${HO[@]}" --event q --save-every 7 --out t2.csv --threads 2
for k in traj cross; do
    if cmp -s t1-$k.csv t2-$k.csv; then ok; else bad "t1-$k.csv and t2-$k.csv differ"; fi
done

# ---- interrupted, resumed: the same files ------------------------------------
# The final write made to fail (a folder where a sidecar goes) keeps the
# whole journal; cut short mid-record, as a kill would leave it, --resume
# runs the members missing and gives the same files as an uninterrupted run.
R=(sweep -H 'p^2/2 - cos(q)' --grid 'q=-3:3:7,p=-2:2:4' --scheme stormer-verlet-kdk,lie --dt 0.1
   --t 30 --save-every 13 --event 'q = 0' --direction both)
run 0 "${R[@]}" --out whole.csv --threads 2
mkdir part-cross.csv
run 2 "${R[@]}" --out part.csv --threads 2
err_has "part-cross.csv"
rmdir part-cross.csv
if [ -s part.csv.journal ] && [ "$(ls part*)" = part.csv.journal ]; then ok; else
    bad "a failed write should keep the journal and leave no file ($(ls))"; fi
size=$(stat -c %s part.csv.journal)
truncate -s $((size * 3 / 5)) part.csv.journal
run 0 "${R[@]}" --out part.csv --resume --threads 1
err_has "(the others done before)"
for f in part.csv part-traj.csv part-cross.csv; do
    if cmp -s "$f" "whole${f#part}"; then ok; else bad "resumed $f differs from the whole run's"; fi
done
if [ -e part.csv.journal ]; then bad "the journal outlived the finished sweep"; else ok; fi

# ---- bad input: exit 2, a clear message, nothing written -----------------------
B=(sweep -H '(p^2+q^2)/2' --grid 'q=1,p=0' --scheme rk4 --dt 0.1 --t 1)
run 2 "${B[@]}" --event 'q +* 2' --out bad.csv
err_has "event: expected an expression after '+'"
err_has "     ^" # under the '*'
run 2 "${B[@]}" --event 'q + zz' --out bad.csv
err_has "unknown symbol 'zz'"
run 2 "${B[@]}" --event '3' --out bad.csv
err_has "never crossed"
run 2 "${B[@]}" --save-every 0 --out bad.csv
err_has "--save-every wants a whole number"
run 2 "${B[@]}" --direction up --out bad.csv
err_has "--direction is for the crossings of --event"
run 2 "${B[@]}" --event q --direction sideways --out bad.csv
err_has "--direction wants up, down or both"
run 2 "${B[@]}" --save-every 2
err_has "name one with --out"
if ls bad* >/dev/null 2>&1; then bad "bad input left $(ls bad*)"; else ok; fi

finish
