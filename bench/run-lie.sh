#!/usr/bin/env bash
# Lie series benchmark (issues 3 and 17): hamlie against SymPy on the same
# machine.  Two comparisons:
#  - the kernel: bench-lie_series (in process, best of 5) against
#    bench/lie_sympy.py (in process);
#  - the whole process: `hamlie lie -H ... --order N` (start-up, parsing, the
#    series, printing it as text), best of 15 runs of CPU time, against the SymPy
#    computation alone (its interpreter's start-up and import not counted,
#    which favours SymPy: the headline ratio), and against SymPy's whole
#    process too (`python3 bench/lie_sympy.py --print NAME`: start-up, import,
#    the series, printing it; CPU of the child, best of 3).
# Usage: bench/run-lie.sh [build-dir]     (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
PY=/usr/bin/python3 # Debian's, with sympy (the python3 on PATH may lack it)
[ -x "$build/bench-lie_series" ] || cmake --build "$build" --target bench-lie_series >/dev/null
[ -x "$build/hamlie" ] || cmake --build "$build" --target hamlie_cli >/dev/null

ours=$("$build/bench-lie_series" 5)
theirs=$("$PY" bench/lie_sympy.py)
"$PY" - "$ours" "$theirs" "$build/hamlie" <<'PY'
import resource, subprocess, sys, time
ours = {l.split()[0]: l.split() for l in sys.argv[1].splitlines()}
theirs = {l.split()[0]: l.split() for l in sys.argv[2].splitlines()}
hamlie = sys.argv[3]
H = {"henon-heiles": "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
     "kepler": "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)"}

def cpu():  # CPU seconds of the children: a loaded machine disturbs it less than wall time
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime

def whole(name, order, reps=15):
    best = float("inf")
    for _ in range(reps):
        t0 = cpu()
        subprocess.run([hamlie, "lie", "-H", H[name], "--order", order],
                       stdout=subprocess.DEVNULL, check=True)
        best = min(best, cpu() - t0)
    return best

def sympy_whole(name, reps=3):
    best = float("inf")
    for _ in range(reps):
        t0 = cpu()
        subprocess.run([sys.executable, "bench/lie_sympy.py", "--print", name],
                       stdout=subprocess.DEVNULL, check=True)
        best = min(best, cpu() - t0)
    return best

print(f"{'system':14} {'order':>5} {'kernel s':>10} {'sympy s':>10} {'ratio':>8} "
      f"{'process s':>10} {'ratio':>8} {'sympy proc s':>12} {'ratio':>8} {'terms':>8}")
for name, (n, order, t, terms) in ours.items():
    ts = float(theirs[name][2])
    tw = whole(name, order)
    tp = sympy_whole(name)
    print(f"{name:14} {order:>5} {float(t):10.4f} {ts:10.3f} {ts/float(t):7.0f}x "
          f"{tw:10.4f} {ts/tw:7.0f}x {tp:12.3f} {tp/tw:7.0f}x {terms:>8}")
def floor(argv, reps=15):
    best = float("inf")
    for _ in range(reps):
        t0 = cpu()
        subprocess.run(argv, stdout=subprocess.DEVNULL, check=True)
        best = min(best, cpu() - t0)
    return best

print("process: the whole `hamlie lie` command (text output to /dev/null) against SymPy's "
      "computation alone (headline, target >= 100x)")
print("sympy proc: SymPy's whole process (interpreter, import, series, print) against the "
      "same hamlie process")
print(f"floor on this machine now: /bin/true {floor(['/bin/true']):.4f} s, "
      f"hamlie --version {floor([hamlie, '--version']):.4f} s (start-up: libraries loaded)")
PY
