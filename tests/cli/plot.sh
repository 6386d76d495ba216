#!/bin/bash
# hamlie plot: runs written by hamlie run, drawn and compared.  The files
# must exist and be what they say (PNG/SVG/PDF magic, PNG size from its
# header); the PNG of the discrete gradient's phase portrait is decoded here
# (zlib + the PNG filters, in python) and its blue orbit must be a circle
# (equal aspect: as wide as high), Euler's spiral (red: the second run) must
# reach further out; bad CSVs exit 2 naming the file, line and column.
# usage (from the repo root): bash tests/cli/plot.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: plot.sh path/to/hamlie}
case $HAMLIE in /*) ;; *) HAMLIE=$PWD/$HAMLIE ;; esac # the work is done in $tmp
. "$(dirname "$0")/lib/harness.sh"

OSC='(p^2+x^2)/2'

# is_file KIND FILE: magic number of png, svg or pdf, and more than 2000 bytes
is_file() {
    local kind=$1 f=$2
    if [ ! -f "$f" ]; then bad "$f missing"; return; fi
    if [ "$(stat -c %s "$f")" -le 2000 ]; then bad "$f: only $(stat -c %s "$f") bytes"; return; fi
    case $kind in
    png) head -c 8 "$f" | od -An -tx1 | tr -d ' \n' | grep -qx '89504e470d0a1a0a' ;;
    svg) head -c 400 "$f" | grep -q '<svg' ;;
    pdf) head -c 5 "$f" | grep -q '^%PDF-' ;;
    esac
    if [ $? -eq 0 ]; then ok; else bad "$f is not a $kind file"; fi
}

# pycheck CODE: python with png(path) -> (w, h, rows of (r, g, b))
pycheck() {
    if python3 - "$1" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "python check: $1"; sed 's/^/    /' "$tmp/py" >&2; fi
import json, struct, sys, zlib
def png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), (depth, ctype)
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, rows, prev, stride = zlib.decompress(idat), [], bytearray(w * bpp), w * bpp
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows
def box(rows, want):
    xs = [x for row in rows for x, px in enumerate(row) if want(px)]
    ys = [y for y, row in enumerate(rows) for px in row if want(px)]
    return (min(xs), max(xs), min(ys), max(ys)) if xs else None
blue = lambda p: p[2] > 180 and p[0] < 110 and p[1] < 110
red = lambda p: p[0] > 180 and p[1] < 110 and p[2] < 110
exec(sys.argv[1])
PYEOF
}

cd "$tmp" || exit 2

# ---- two runs of the paper, compared ------------------------------------------
run 0 run -H "$OSC" --scheme paper-dg --dt 0.1 --t 20 --init x=1,p=0 --observe x/p --out dg.csv
run 0 run -H "$OSC" --scheme paper-euler --dt 0.1 --t 20 --init x=1,p=0 --observe x/p --out euler.csv
run 0 plot dg.csv euler.csv --out figs
has_text "2 runs (dg: 201 rows, euler: 201 rows); wrote 6 files to figs:"
for f in phase-x-p time-x time-p energy-error sigma observer-1-x_p; do
    is_file png "figs/$f.png"
    has_line "  $f.{png}"
done
[ ! -e figs/phase-x-p.svg ] && ok || bad "an svg written without --format svg"
pycheck '
w, h, rows = png("figs/phase-x-p.png")
assert (w, h) == (800, 600), (w, h)
# (the legend is in a corner: look at the middle band of rows only)
low = rows[int(0.4 * h):int(0.6 * h)]
bx0, bx1, by0, by1 = box(low, blue)
rx0, rx1, ry0, ry1 = box(low, red)
# Euler (red squares) spirals out to radius 1.01^100 = 2.7, the discrete
# gradient (blue dots) stays on the unit circle: 2.7 times narrower
assert rx1 - rx0 > 2.2 * (bx1 - bx0), (rx1 - rx0, bx1 - bx0)
assert abs((bx0 + bx1) / 2 - (rx0 + rx1) / 2) < 0.1 * (rx1 - rx0)'
# one run: no legend; the orbit is a circle drawn with equal aspect
run 0 plot dg.csv --out one --size 640x480
pycheck '
assert png("one/time-x.png")[:2] == (640, 480)
w, h, rows = png("one/phase-x-p.png")
bx0, bx1, by0, by1 = box(rows, blue)
bw, bh = bx1 - bx0, by1 - by0
assert bw > 200 and abs(bw - bh) <= 0.03 * bw, (bw, bh)
assert box(rows, red) is None'

# every format, JSON summary
run 0 plot dg.csv euler.csv --out figs2 --format png,svg,pdf --json
for f in phase-x-p energy-error sigma; do
    is_file png "figs2/$f.png"; is_file svg "figs2/$f.svg"; is_file pdf "figs2/$f.pdf"
done
pycheck '
d = json.load(open("'"$tmp"'/out"))
assert d["command"] == "plot" and d["out"] == "figs2"
assert d["files_written"] == 18, d["files_written"]
assert d["figures"] == ["phase-x-p", "time-x", "time-p", "energy-error", "sigma", "observer-1-x_p"], d["figures"]
assert [r["rows"] for r in d["runs"]] == [201, 201] and d["runs"][1]["label"] == "euler"'

# LaTeX: one figure environment per figure, the pdf preferred
run 0 plot euler.csv --out figs3 --format png,pdf --latex
has_text '\includegraphics[width=0.7\textwidth]{figs3/energy-error.pdf}'
n=$(grep -c 'begin{figure}' "$tmp/out")
[ "$n" -eq 6 ] && ok || bad "$n figure environments, want 6"

# --phase: a chosen projection only
run 0 plot euler.csv --out figs4 --phase p:x
is_file png figs4/phase-p-x.png
[ ! -e figs4/phase-x-p.png ] && ok || bad "--phase p:x also wrote phase-x-p"
run 2 plot euler.csv --out figs4 --phase x:zz
err_has "no such column (columns: t, x, p, H, sigma, x/p)"

# ---- N = 2: Henon-Heiles, a pair per degree of freedom -----------------------------
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
run 0 run -H "$HH" --scheme rk4 --dt 0.05 --t 30 --init x=0,y=0.1,px=0.4,py=0 --no-reference --out hh.csv
run 0 plot hh.csv --out hh
for f in phase-x-px phase-y-py time-x time-y time-px time-py energy-error; do is_file png "hh/$f.png"; done
[ ! -e hh/sigma.png ] && ok || bad "sigma drawn for a run without it"

# ---- errors: exit 2 with the place ---------------------------------------------
sed '5s/.*/0.4,1,oops,0.5,0,1/' euler.csv >broken.csv
run 2 plot broken.csv --out bad
err_has "broken.csv: line 5, column 3 (p): 'oops' is not a number"
[ ! -e bad ] && ok || bad "a folder made for a bad CSV"
sed '7s/,[^,]*$//' euler.csv >short.csv
run 2 plot short.csv --out bad
err_has "short.csv: line 7: 5 values, the header names 6 columns"
run 2 plot missing.csv --out bad
err_has "cannot read 'missing.csv'"
run 2 plot euler.csv hh.csv --out bad
err_has "different columns"
run 2 plot euler.csv --out bad --format png,gif
err_has "unknown figure format 'gif'"
run 2 plot euler.csv
err_has "missing --out"
run 2 plot euler.csv --out bad --size 640
err_has "--size wants WxH"
run 2 plot euler.csv --out bad --size 8x8
err_has "--size wants WxH"
run 2 plot --out bad
err_has "at least one CSV"
run 2 plot euler.csv --out bad -H "$OSC"
echo x >afile
run 2 plot euler.csv --out afile/sub
err_has "afile"
run 0 plot --help
has_text "usage: hamlie plot RUN.csv"

finish
