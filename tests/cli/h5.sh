#!/bin/bash
# HDF5 result files (src/report/h5.c, libhdf5 loaded on first use):
#  - section --out f.h5: h5py reads every column, equal bit for bit to the
#    CSV of the same command (17 digits round-trip); the inputs as
#    attributes; each orbit's start, crossings, status and reason (failed
#    orbits: status HL_ENOCONV and the message printed on stderr);
#  - the same command twice gives the same bytes (cmp);
#  - without libhdf5 ($HAMLIE_HDF5_LIB=/nonexistent): exit 2, the reason,
#    nothing written (no file, no temporary, no figure folder);
#  - an unwritable output: exit 2, the path named, nothing left;
#  - sweep --out f.h5: summary/<column>, status and reason equal the sweep's
#    CSV (members that blow up included); the same file with 1 and 2
#    threads, and after a kill -9 mid-sweep and --resume (cmp); without
#    libhdf5: exit 2 before computing, no file and no journal;
#  - start-up: `lie` and a CSV section never load libhdf5; --out f.h5 does.
# usage (from the repo root): bash tests/cli/h5.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: h5.sh path/to/hamlie}
case $HAMLIE in /*) ;; *) HAMLIE=$PWD/$HAMLIE ;; esac
. "$(dirname "$0")/lib/harness.sh"
cd "$tmp" || exit 2
PY=/usr/bin/python3
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
# pycheck CODE ARGS...: python with h5py, numpy, csv; sys.argv[1:] the args
pycheck() {
    local code=$1
    shift
    if $PY -c "import sys, csv, math, h5py, numpy as np
$code" "$@" >"$tmp/py" 2>&1; then ok; else bad "python check: $code"; sed 's/^/    /' "$tmp/py" >&2; fi
}

# ---- a section as CSV and as HDF5: the same numbers ----
SEC=(section -H "$HH" --energy 1/8 --surface x=0 --orbits 5 --crossings 30 --tol 1e-14)
run 0 "${SEC[@]}" --out hh.csv
run 0 "${SEC[@]}" --out hh.h5
has_text "wrote them to hh.h5"
pycheck '
rows = list(csv.DictReader(open(sys.argv[1])))
f = h5py.File(sys.argv[2], "r")
names = ["orbit", "crossing", "t", "x", "y", "px", "py", "H"]
assert list(f.attrs["columns"]) == names, f.attrs["columns"]
assert list(f.attrs["variables"]) == ["x", "y", "px", "py"]
assert len(rows) == 150 and all(f["crossings/" + n].shape == (150,) for n in names)
for n in names:
    col = f["crossings/" + n][:]
    want = np.array([float(r[n]) for r in rows])
    assert np.array_equal(col, want), (n, col[:3], want[:3])   # bit for bit
assert f["crossings/orbit"].dtype == np.int64 and f["crossings/t"].dtype == np.float64
a = f.attrs
assert a["command"] == "section" and a["H"] == sys.argv[3] and a["energy"] == 0.125
assert a["energy_input"] == "1/8" and a["surface"] == "x=0" and a["direction"] == "up"
assert a["scheme"] == "lie (adaptive Taylor)" and a["located_on"] == "taylor-polynomial"
assert a["tol"] == 1e-14 and "dt" not in a and a["orbits"] == 5 and a["crossings_per_orbit"] == 30
assert a["hamlie_version"] == sys.argv[4]
o = f["orbits"]
assert list(o["crossings"][:]) == [30] * 5 and list(o["status"][:]) == [0] * 5
assert list(o["reason"].asstr()[:]) == [""] * 5
# the starts: on the section, on H = E, and the first crossing of each orbit is not its start
for i in range(5):
    x, y, px, py = (o[n + "0"][i] for n in ("x", "y", "px", "py"))
    assert x == 0 and px > 0 and py == 0
    assert abs((px*px + py*py)/2 + y*y/2 - y**3/3 - 0.125) < 1e-15
' hh.csv hh.h5 "$HH" "$("$HAMLIE" --version | sed 's/^hamlie //')"

# ---- the same command, the same bytes ----
run 0 "${SEC[@]}" --out hh2.h5
if cmp -s hh.h5 hh2.h5; then ok; else bad "the same section gave two different HDF5 files"; fi
if ls ./*.tmp >/dev/null 2>&1; then bad "a temporary file was left: $(ls ./*.tmp)"; else ok; fi

# ---- failed orbits: recorded with their reason, the others' crossings kept ----
run 1 section -H "$HH" --energy 1/8 --surface x=0 --orbits 3 --crossings 50 --scheme \
    stormer-verlet-kdk --dt 0.05 --t-max 40 --out fail.h5
pycheck '
f = h5py.File(sys.argv[1], "r")
err = open(sys.argv[2]).read()
st, why, n = f["orbits/status"][:], f["orbits/reason"].asstr()[:], f["orbits/crossings"][:]
assert f.attrs["dt"] == 0.05 and "tol" not in f.attrs and f.attrs["located_on"] == "hermite-cubic"
assert f.attrs["scheme"] == "stormer-verlet-kdk"
assert all(s == 7 for s in st), st          # HL_ENOCONV: fewer crossings than asked by t-max
for i in range(3):
    assert 0 < n[i] < 50 and why[i].startswith("%d of 50 crossings" % n[i]), (n[i], why[i])
    assert ("orbit %d failed after %d crossings: %s" % (i, n[i], why[i])) in err
assert len(f["crossings/t"]) == sum(n)
' fail.h5 "$tmp/err"

# ---- without libhdf5: exit 2, the reason, nothing written ----
HAMLIE_HDF5_LIB=/nonexistent/libhdf5.so run 2 "${SEC[@]}" --out nolib.h5 --plot nolib-fig
err_has "/nonexistent/libhdf5.so not found: install libhdf5"
if [ -e nolib.h5 ] || [ -e nolib.h5.tmp ] || [ -e nolib-fig ]; then
    bad "without libhdf5 something was written: $(ls -d nolib*)"; else ok; fi
# a CSV needs no libhdf5
HAMLIE_HDF5_LIB=/nonexistent/libhdf5.so run 0 "${SEC[@]}" --out nolib.csv

# ---- an unwritable output: the path named, nothing left ----
run 2 "${SEC[@]}" --out no-such-dir/x.h5
err_has "cannot write 'no-such-dir/x.h5'"
if [ -e no-such-dir ]; then bad "no-such-dir was made"; else ok; fi

# ---- a sweep: the summary equals the CSV, members that failed included ----
SW=(sweep -H 'p^2/2 - q^4' --grid 'q=0.1:3:4,p=-0.5:0.5:3' --scheme euler,stormer-verlet-kdk
    --dt 0.1,0.05 --t 10 --quiet)
run 1 "${SW[@]}" --out sw.csv --threads 1
run 1 "${SW[@]}" --out sw.h5 --threads 1
run 1 "${SW[@]}" --out sw2.h5 --threads 2
if cmp -s sw.h5 sw2.h5; then ok; else bad "sweep.h5 with 1 and 2 threads differ"; fi
pycheck '
rows = list(csv.DictReader(open(sys.argv[1])))
f = h5py.File(sys.argv[2], "r")
s, a = f["summary"], f.attrs
cols = list(a["columns"])
assert list(rows[0].keys()) == cols + ["status", "reason"]
assert a["command"] == "sweep" and a["H"] == "p^2/2 - q^4" and a["grid"] == "q=0.1:3:4,p=-0.5:0.5:3"
assert list(a["schemes"]) == ["euler", "stormer-verlet-kdk"] and a["dts"] == "0.1,0.05"
assert a["t"] == 10 and a["members"] == len(rows) == 48 and len(a["fingerprint"]) == 16
for c in cols:
    got = s[c][:]
    if c == "scheme":
        want = np.array([list(a["schemes"]).index(r[c]) for r in rows])
    else:
        want = np.array([float(r[c]) for r in rows])
    assert got.shape == (48,) and np.array_equal(got, want, equal_nan=True), (c, got[:4], want[:4])
assert s["member"].dtype == np.int64 and s["max_dH"].dtype == np.float64
names = list(a["status_names"])
st, why = s["status"][:], s["reason"].asstr()[:]
assert [names[k] for k in st] == [r["status"] for r in rows]
assert list(why) == [r["reason"] for r in rows]
assert 0 < sum(st != 0) < 48 and all((st != 0) == (why != ""))   # some blew up, not all
' sw.csv sw.h5

# ---- killed mid-sweep, resumed: the same file as an uninterrupted run ----
LONG=(sweep -H 'p^2/2 - cos(q)' --grid 'q=-3:3:30,p=-2:2:30' --scheme stormer-verlet-kdk,rk4
      --dt 0.01 --t 100 --threads 2 --quiet)
run 0 "${LONG[@]}" --out whole.h5
"$HAMLIE" "${LONG[@]}" --out part.h5 2>/dev/null &
pid=$!
for _ in $(seq 600); do # until some members are in the journal
    [ "$(stat -c %s part.h5.journal 2>/dev/null || echo 0)" -gt 3000 ] && break
    sleep 0.02
done
kill -KILL $pid 2>/dev/null
wait $pid 2>/dev/null
if [ -e part.h5 ]; then bad "the sweep finished before the kill: make it longer"; else ok; fi
run 0 "${LONG[@]}" --out part.h5 --resume
if cmp -s whole.h5 part.h5; then ok; else bad "a resumed sweep's HDF5 file differs from a whole run's"; fi
if [ -e part.h5.journal ]; then bad "the journal was left after the resumed sweep"; else ok; fi

# ---- a sweep without libhdf5: refused before computing, nothing written ----
HAMLIE_HDF5_LIB=/nonexistent/libhdf5.so run 2 "${SW[@]}" --out sw-nolib.h5
err_has "/nonexistent/libhdf5.so not found: install libhdf5"
if ls sw-nolib* >/dev/null 2>&1; then bad "without libhdf5 the sweep left $(ls sw-nolib*)"; else ok; fi

# ---- start-up: only an HDF5 output loads libhdf5 ----
loaded() { cat "$tmp"/ld.* 2>/dev/null | grep -E 'file=[^ ]*('"$1"')[^ ]* +\[0\]; +(needed|dynamically loaded)' -q; }
traced() { rm -f "$tmp"/ld.*; LD_DEBUG=files LD_DEBUG_OUTPUT=$tmp/ld run "$@"; }
traced 0 lie -H 'p^2/2 + q^2/2' --order 3
if loaded 'libhdf5'; then bad "lie loaded libhdf5"; else ok; fi
if loaded 'libflint'; then ok; else bad "the trace does not work (lie loaded no libflint)"; fi
traced 0 "${SEC[@]}" --out traced.csv
if loaded 'libhdf5'; then bad "section --out f.csv loaded libhdf5"; else ok; fi
traced 0 "${SEC[@]}" --out traced.h5
if loaded 'libhdf5'; then ok; else bad "section --out f.h5 did not load libhdf5"; fi

finish
