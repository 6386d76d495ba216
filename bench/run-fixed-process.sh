#!/usr/bin/env bash
# Fixed-step schemes as whole processes (issue 17): `hamlie run --scheme S
# --dt DT --t T --no-reference --json` against a hand-written C loop of the
# same scheme with H at every step (bench/fixed_hand.c, compiled here with
# cc -O2 as a program of its own: no library loaded but libm), 10^7 steps,
# best of REPS runs each: CPU time (user + sys of the child, steadier than
# the wall clock on a shared machine) and wall time.  The two agree on the
# final state and max |H - H0| after 10^5 steps (to 1e-9: over 10^7 steps
# rounding differences grow with the phase error, rk4 most): each pair
# computes the same scheme.  Target: CPU ratio <= 1.3.
# Usage: bench/run-fixed-process.sh [build-dir] [reps] [steps]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
reps=${2:-3}
steps=${3:-10000000}
[ -x "$build/hamlie" ] || cmake --build "$build" --target hamlie_cli >/dev/null
hand="$build/fixed_hand"
${CC:-cc} -O2 -o "$hand" bench/fixed_hand.c -lm
/usr/bin/python3 - "$build/hamlie" "$hand" "$reps" "$steps" <<'PY'
import json, resource, subprocess, sys, time
hamlie, hand, reps, steps = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(float(sys.argv[4]))
systems = {  # name: H, --init, the state's names in order, dt
    "pendulum": ("p^2/2 - cos(q)", "q=1.3,p=0", ["q", "p"], 0.01),
    "henon-heiles": ("(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
                     "x=0.1,y=-0.1,px=0.05,py=0.1", ["x", "y", "px", "py"], 0.01),
    "kepler": ("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "x=0.5,y=0,px=0,py=sqrt(3)",
               ["x", "y", "px", "py"], 0.001),
}

def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime

def best(argv, n=reps):
    t, w, out = float("inf"), float("inf"), None
    for _ in range(n):
        c0, w0 = cpu(), time.perf_counter()
        out = subprocess.run(argv, stdout=subprocess.PIPE, check=True, text=True).stdout
        t, w = min(t, cpu() - c0), min(w, time.perf_counter() - w0)
    return t, w, out

def hamlie_run(H, scheme, dt, n, init, reps=reps):
    return best([hamlie, "run", "-H", H, "--scheme", scheme, "--dt", repr(dt), "--t",
                 repr(dt * n), "--init", init, "--no-reference", "--json", "--quiet"], reps)

def same(H, scheme, dt, init, names, name, n=100000):
    d = json.loads(hamlie_run(H, scheme, dt, n, init, 1)[2])
    vals = [float(v) for v in best([hand, name, scheme, repr(dt), str(n)], 1)[2].split()]
    ours = [d["final_state"][k] for k in names] + [d["max_abs_dH"]]
    return all(abs(a - b) <= 1e-9 * max(1e-3, abs(b)) for a, b in zip(ours, vals))

print(f"{'system':13} {'scheme':19} {'cpu s':>7} {'hand':>7} {'ratio':>6} "
      f"{'wall s':>7} {'hand':>7} {'ratio':>6} {'in-run':>7}  same")
worst = 0
for name, (H, init, names, dt) in systems.items():
    for scheme in ["stormer-verlet-kdk", "rk4"]:
        th, wh, out = hamlie_run(H, scheme, dt, steps, init)
        tc, wc, _ = best([hand, name, scheme, repr(dt), str(steps)])
        ok = same(H, scheme, dt, init, names, name)
        worst = max(worst, th / tc)
        print(f"{name:13} {scheme:19} {th:7.3f} {tc:7.3f} {th / tc:6.2f} {wh:7.3f} {wc:7.3f} "
              f"{wh / wc:6.2f} {json.loads(out)['wall_time_s']:7.3f}  {'yes' if ok else 'NO'}")
print(f"worst CPU ratio {worst:.2f} (target <= 1.3); in-run: hamlie's own wall_time_s "
      "(set-up, compilation and the loop; not the process start-up)")
PY
