#!/usr/bin/env python3
"""What the Python binding costs on top of the library (issue 16's targets:
within 10 %).

1. A 10^6-step fixed-step run (RK4 on the pendulum, dt = 0.01 to t = 10^4,
   every row kept, the reference on) through hamlie.System.run against the
   same run through the library from C (bench-python_peer: the same calls,
   the rows copied into arrays by the row callback as the binding does).
2. A symbolic errors() call against `hamlie errors --json` for the same
   input: the C-level dict (_hamlie: every formula a string, as the CLI
   writes them), hamlie.Errors (formulas parsed by SymPy when first used),
   and the same with its v_k parsed.

Times are CPU seconds (time.process_time for this process, getrusage of the
children for the CLI and the C peer), best of REPS: the machine is shared,
and wall time would count the other jobs.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [build dir] [reps]
"""
import os
import re
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
BUILD = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build"))
REPS = int(sys.argv[2]) if len(sys.argv) > 2 else 3
sys.path.insert(0, os.path.join(BUILD, "python"))
import hamlie  # noqa: E402


def best_cpu(fn, reps=REPS):
    best, out = float("inf"), None
    for _ in range(reps):
        out = None  # the last result's arrays are freed outside the timing
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return best, out


def child_cpu(cmd):
    """CPU seconds (user + system) of one child process, and its stdout."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), out


def bench_run():
    H, scheme, dt, T, init = "p^2/2 - cos(q)", "rk4", 0.01, 10000.0, "q=1.3,p=0"
    out = subprocess.run([os.path.join(BUILD, "bench-python_peer"), H, scheme, str(dt), str(T),
                          init, str(REPS), "1"], check=True, capture_output=True, text=True).stdout
    c_ms = float(re.match(r"([0-9.]+) ms", out).group(1))
    s = hamlie.System(H)
    py, r = best_cpu(lambda: s.run(scheme, dt=dt, t=T, init={"q": 1.3, "p": 0}))
    final_c = [float(v) for v in out.split("final ")[1].split()]
    same = final_c == list(r.summary["final_state"])
    print(f"run: {scheme}, 10^6 steps, {len(r)} rows: C {c_ms / 1e3:.3f} s, "
          f"Python {py:.3f} s, ratio {py / (c_ms / 1e3):.3f} (final states equal: {same})")


def bench_errors(H, scheme, order):
    cli = [os.path.join(BUILD, "hamlie"), "errors", "-H", H, "--scheme", scheme,
           "--order", str(order), "--json"]
    c = min(child_cpu(cli)[0] for _ in range(REPS))
    s = hamlie.System(H)
    raw, _ = best_cpu(lambda: hamlie.System(H)._c.errors(scheme=scheme, order=order))
    full, _ = best_cpu(lambda: hamlie.System(H).errors(scheme, order=order))
    with_v, _ = best_cpu(lambda: hamlie.System(H).errors(scheme, order=order).v)
    print(f"errors: {scheme} on {H} to order {order}: CLI {c:.3f} s, "
          f"_hamlie {raw:.3f} s (ratio {raw / c:.3f}), "
          f"hamlie.Errors {full:.3f} s (ratio {full / c:.3f}), "
          f"and its v_k parsed by SymPy {with_v:.3f} s (ratio {with_v / c:.3f})")


if __name__ == "__main__":
    bench_run()
    bench_errors("p^2/2 - cos(q)", "yoshida4", 8)
    bench_errors("p^2/2 - cos(q)", "rk4", 10)
