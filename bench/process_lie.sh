#!/usr/bin/env bash
# The whole process of the adaptive Taylor integrator against heyoka's
# (issue 17): `hamlie run -H H --scheme lie --tol 1e-15 --t T --init ...
# --json` against bench/process_lie_heyoka.cpp, a heyoka 7 program that does
# the same (H differentiated, integrated to T, the state at the same 1001
# rows, max |H - H0| over them, a JSON summary), on the four systems of
# bench/work_precision.c at t = 1e4 and 1e5, side by side in this script.
#
# Times are CPU seconds of the child (user + sys, through getrusage: the
# machine may be shared, and heyoka's compiler may use threads, which CPU
# time counts), the best of REPS runs.  hamlie is timed twice:
#   first: each run with an empty cache directory (compiles, when it pays,
#          into the cache: what a user's first run of a system costs);
#   warm:  the cache holds the compiled code (the second run on).
# heyoka keeps no compiled code between processes (its cache is in memory),
# so its every run is a first run.  Both must agree on the final state to
# 1e-8 (relative; both integrate to about 1e-10 at t = 1e4) and report a
# small max |H - H0|.  Target: heyoka / hamlie-warm >= 2 everywhere.
#
# Usage: bench/process_lie.sh [build-dir] [reps] [T-list]
#   HEYOKA_PREFIX (/opt/heyoka); without heyoka, hamlie's times alone.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-5}
Ts=${3:-1e4,1e5}
hy=${HEYOKA_PREFIX:-/opt/heyoka}
[ -x "$build/hamlie" ] || cmake --build "$build" --target hamlie_cli >/dev/null
peer=""
if [ -f "$hy/lib/libheyoka.so" ]; then
    peer="$build/process_lie_heyoka"
    if [ ! -x "$peer" ] || [ bench/process_lie_heyoka.cpp -nt "$peer" ]; then
        g++ -O2 -DNDEBUG -std=c++20 -I"$hy/include" bench/process_lie_heyoka.cpp -o "$peer" \
            -L"$hy/lib" -Wl,-rpath,"$hy/lib" -lheyoka -lfmt -lboost_serialization 2>/dev/null
    fi
else
    echo "process_lie: heyoka not found in $hy, hamlie alone" >&2
fi
cache=$(mktemp -d)
trap 'rm -rf "$cache"' EXIT
/usr/bin/python3 - "$build/hamlie" "$peer" "$reps" "$Ts" "$cache" <<'PY'
import json, os, resource, shutil, subprocess, sys
hamlie, peer, reps, Ts, cache = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
systems = {  # name: H, --init, the state's names in order
    "oscillator": ("(p^2+q^2)/2", "q=1,p=0", ["q", "p"]),
    "pendulum": ("p^2/2 - cos(q)", "q=1.3,p=0", ["q", "p"]),
    "henon-heiles": ("(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
                     "x=0.1,y=-0.1,px=0.05,py=0.1", ["x", "y", "px", "py"]),
    "kepler": ("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "x=0.5,y=0,px=0,py=1.7320508075688772",
               ["x", "y", "px", "py"]),
}
TOL = "1e-15"

def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime

def timed(argv, env):
    c0 = cpu()
    out = subprocess.run(argv, stdout=subprocess.PIPE, check=True, text=True, env=env).stdout
    return cpu() - c0, json.loads(out)

def hamlie_argv(name, T):
    H, init, _ = systems[name]
    return [hamlie, "run", "-H", H, "--scheme", "lie", "--tol", TOL, "--t", T, "--init", init,
            "--json", "--quiet"]

def clear(d):
    for f in os.listdir(d):
        os.unlink(os.path.join(d, f))

env = dict(os.environ, HAMLIE_CACHE_DIR=cache)
print(f"CPU s, best of {reps}; hamlie first = empty cache, warm = cache filled; "
      f"ratio = heyoka / hamlie")
print(f"{'system':13} {'t':>5} {'hamlie 1st':>10} {'warm':>7} {'heyoka':>7} "
      f"{'ratio 1st':>9} {'warm':>6} {'steps':>7} {'hy steps':>8} {'max|dH|':>8}  agree")
worst = float("inf")
for T in Ts.split(","):
    for name, (_, _, names) in systems.items():
        first = float("inf")
        for _ in range(reps):
            clear(cache)
            t, d = timed(hamlie_argv(name, T), env)
            first = min(first, t)
        warm = min(timed(hamlie_argv(name, T), env)[0] for _ in range(reps))
        ours = [d["final_state"][k] for k in names]
        hy, ratio1, ratio2, agree, hsteps = float("nan"), "", "", "", ""
        if peer:
            hy = float("inf")
            for _ in range(reps):
                t, p = timed([peer, name, T, TOL], os.environ)
                hy = min(hy, t)
            theirs = [p["final_state"][k] for k in names]
            agree = "yes" if all(abs(a - b) <= 1e-8 * max(1, abs(b))
                                 for a, b in zip(ours, theirs)) else "NO"
            ratio1, ratio2 = f"{hy / first:9.2f}", f"{hy / warm:6.2f}"
            hsteps = p["taylor_steps"]
            worst = min(worst, hy / warm)
        print(f"{name:13} {T:>5} {first:10.3f} {warm:7.3f} {hy:7.3f} {ratio1:>9} {ratio2:>6} "
              f"{d['taylor_steps']:7d} {hsteps:>8} {d['max_abs_dH']:8.1e}  {agree}")
if peer:
    print(f"worst warm ratio {worst:.2f} (target >= 2)")
PY
