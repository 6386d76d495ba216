#!/usr/bin/python3
"""The cost of an adaptive Taylor step against its order: measure, fit, misfit.

Runs bench-work_precision at forced orders (order=P, native code, the step of
hl_flow_rule_at) on the four systems of the work-precision figure and six of
the zoo's tapes (other mixes of products, libm calls, linear instructions and
state), takes ns a step (best-of CPU time / steps), and fits the figures of
hl_tape_taylor_step_cost (src/tape/cost.c) per term of the tape
(bench-work_precision methods=terms, tape/cost_impl.h):

  ns(p) = C0 + Ccall calls + (Clin linear + Cstate state) p + Cprod products p^2
          [+ Cknee max(0, products p^2 - K)]

The last term is the knee: past a size of the recursion (products p^2 is
most of its straight-line code) a step costs more per product, as the code
outgrows the core's caches of decoded instructions (--knee K, or --knee 0:
the K of least misfit on a grid).

by least squares on the relative misfit (each row divided by its ns: the
choice of the order needs ratios, not ns).  Prints the figures as cost.c's
#defines, the misfit per row and per system, and the same for cost.c's
current model (read from the source) for comparison.

Usage: bench/cost_fit.py [build-dir] [--orders 12,14,...] [--steps 20000] [--reps 3]
       [--rounds 2] [--knee K]
       [--sys 0,...,9] [--raw FILE (reuse rows)] [--save FILE]
Needs Debian's python3 (numpy).  A few minutes on 2 cores (the first run
compiles each order's recursion: the disk cache keeps them for the next).
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TERMS = ("products", "linear", "calls", "state")


def run_bench(bench, args):
    out = subprocess.run([bench] + args, check=True, capture_output=True, text=True).stdout
    return [line.split(",") for line in out.splitlines() if line]


def measure(a):
    """Rows: dict(system, order, ns, steps, products, linear, calls, state)."""
    bench = os.path.join(a.build, "bench-work_precision")
    rows = []
    for s in a.sys:
        terms = None
        for p in a.orders:
            # a short probe (it compiles, or loads the cache) for the steps a
            # unit of time, then a run of about a.steps steps
            T = 100.0
            for rec in run_bench(bench, ["sys=%d" % s, "order=%d" % p, "T=%g" % T,
                                         "tols=%g" % a.tol, "reps=1", "methods=native,terms"]):
                if rec[0] == "terms":
                    terms = dict(zip(TERMS, map(float, rec[2:6])))
                elif rec[0] == "hamlie-native":
                    T = min(1e5, max(T, T * a.steps / max(1, int(rec[5]))))
            for rec in run_bench(bench, ["sys=%d" % s, "order=%d" % p, "T=%.3g" % T,
                                         "tols=%g" % a.tol, "reps=%d" % a.reps,
                                         "methods=native"]):
                if rec[0] == "hamlie-native":
                    steps, ms = int(rec[5]), float(rec[6])
                    rows.append(dict(system=rec[1], order=int(rec[4]), steps=steps,
                                     ns=1e6 * ms / steps, **terms))
                    print("# %-16s p %2d  %6d steps  %7.1f ns a step" %
                          (rec[1], int(rec[4]), steps, rows[-1]["ns"]), file=sys.stderr)
    return rows


def features(r, knee):
    p = r["order"]
    f = [1.0, r["calls"], r["linear"] * p, r["state"] * p, r["products"] * p * p]
    if knee is not None:
        f.append(max(0.0, r["products"] * p * p - knee))
    return f


NAMES = ["TAYLOR_NS_PER_STEP", "TAYLOR_NS_PER_CALL", "TAYLOR_NS_PER_LINEAR_P",
         "TAYLOR_NS_PER_STATE_P", "TAYLOR_NS_PER_PRODUCT_P2", "TAYLOR_NS_PER_PRODUCT_P2_PAST_KNEE"]


def fit(rows, knee):
    """Least squares of the relative misfit, coefficients >= 0 (a negative one
    is dropped and the rest refitted)."""
    X = np.array([features(r, knee) for r in rows])
    y = np.array([r["ns"] for r in rows])
    A, b = X / y[:, None], np.ones(len(y))
    keep = list(range(X.shape[1]))
    while True:
        c, *_ = np.linalg.lstsq(A[:, keep], b, rcond=None)
        if (c >= 0).all():
            break
        keep.pop(int(np.argmin(c)))
    coef = np.zeros(X.shape[1])
    coef[keep] = c
    return coef


def current_model():
    """cost.c's figures (its #defines), as the fit's coefficients."""
    src = open(os.path.join(HERE, "..", "src", "tape", "cost.c")).read()
    val = {m[1]: float(m[2]) for m in re.finditer(r"#define (TAYLOR_NS_\w+) ([0-9.eE+-]+)", src)}
    k = re.search(r"#define TAYLOR_KNEE_PRODUCTS_P2 ([0-9.eE+]+)", src)
    knee = float(k[1]) if k else None
    return [val.get(n, 0.0) for n in NAMES[:5 + (knee is not None)]], knee


def misfit(rows, coef, knee):
    return [float(np.dot(features(r, knee), coef)) / r["ns"] - 1 for r in rows]


def report(title, rows, coef, knee):
    m = misfit(rows, coef, knee)
    print("\n## %s\n" % title)
    for n, c in zip(NAMES, coef):
        print("#define %-34s %.3g" % (n, c))
    if knee is not None:
        print("#define %-34s %g" % ("TAYLOR_KNEE_PRODUCTS_P2", knee))
    print("\nmisfit (model/measured - 1): median |.| %.1f %%, worst %+.0f %%" %
          (100 * statistics.median(abs(x) for x in m), 100 * max(m, key=abs)))
    print("| system | " + " | ".join("p %d" % p for p in sorted({r["order"] for r in rows}))
          + " |")
    by = {}
    for r, x in zip(rows, m):
        by.setdefault(r["system"], {})[r["order"]] = (r["ns"], x)
    orders = sorted({r["order"] for r in rows})
    print("|---|" + "---|" * len(orders))
    for s, d in by.items():
        print("| %s | " % s + " | ".join("%.0f (%+.0f%%)" % (d[p][0], 100 * d[p][1])
                                         if p in d else "-" for p in orders) + " |")
    return m


# ---- the orders the rule (src/flow/rule.c) would choose with a model ----
# A copy of rule.c's arithmetic, for the report only: Jorba & Zou's order and
# step, the raised orders' step (a tenth of the tail), the ratio's bound.
MAX_LN_RATIO, RAISED_MARGIN = -1.5, math.log(10)


def p_jz(ln_tol):
    return math.ceil(-ln_tol / 2) + 1


def ln_tail(p, ln_r):
    return (p + 1) * ln_r - math.log1p(-math.exp(ln_r))


def ratio_for_tail(p, target):
    ln_r = target / (p + 1)
    for _ in range(8):
        ln_r = (target + math.log1p(-math.exp(ln_r))) / (p + 1)
    return ln_r


def chosen_order(ln_tol, ns):
    """ns(p): a step's cost; the order rule.c chooses (tol 1e-13 .. 1.5e-8)."""
    p0 = p_jz(ln_tol)
    tail = ln_tail(p0, -2 - 0.7 / (p0 - 1)) - RAISED_MARGIN
    best, order = ns(p0) * math.exp(-ratio_for_tail(p0, tail)), p0
    for p in range(p0 + 1, 200):
        ln_r = ratio_for_tail(p, tail)
        if ln_r > MAX_LN_RATIO:
            break
        if ns(p) * math.exp(-ln_r) < best:
            best, order = ns(p) * math.exp(-ln_r), p
    return order


def orders_table(rows, models):
    tols = (1e-9, 1e-10, 1e-11, 1e-12, 1e-13)
    print("\n## Orders the rule would choose, tol %s\n" % " ".join("%g" % t for t in tols))
    print("| tape | " + " | ".join(name for name, _, _ in models) + " |")
    print("|---|" + "---|" * len(models))
    for s in dict.fromkeys(r["system"] for r in rows):
        r = next(x for x in rows if x["system"] == s)
        cells = []
        for _, coef, knee in models:
            def ns(p, coef=coef, knee=knee):
                return float(np.dot(features(dict(r, order=p), knee), coef))
            cells.append(" ".join(str(chosen_order(math.log(t), ns)) for t in tols))
        print("| %s | %s |" % (s, " | ".join(cells)))


def read_raw(path):
    rows = []
    for line in open(path):
        if line.startswith("system"):
            continue
        f = line.strip().split(",")
        rows.append(dict(system=f[0], order=int(f[1]), steps=int(f[2]), ns=float(f[3]),
                         **dict(zip(TERMS, map(float, f[4:8])))))
    return rows


def median_rows(rounds):
    """Per system and order, the median ns over rounds (a round's point can
    meet a burst of load that best-of-reps does not filter)."""
    out = {}
    for rows in rounds:
        for r in rows:
            out.setdefault((r["system"], r["order"]), []).append(r)
    return [dict(v[0], ns=statistics.median(r["ns"] for r in v)) for v in out.values()]


def save_raw(path, rows):
    with open(path, "w") as fh:
        fh.write("system,order,steps,ns," + ",".join(TERMS) + "\n")
        for r in rows:
            fh.write("%s,%d,%d,%.2f,%g,%g,%g,%g\n" % (r["system"], r["order"], r["steps"],
                                                       r["ns"], *(r[t] for t in TERMS)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("build", nargs="?", default="build")
    ap.add_argument("--orders", default="12,14,16,18,20,22,24,26,28,32,36,40")
    ap.add_argument("--sys", default="0,1,2,3,4,5,6,7,8,9")
    ap.add_argument("--steps", type=int, default=20000, help="steps a timed run")
    ap.add_argument("--tol", type=float, default=1e-9,
                    help="the tolerance (its Jorba-Zou order at most the least order)")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--knee", type=float, default=0,
                    help="the knee's products p^2 (0: fitted; -1: no knee)")
    ap.add_argument("--rounds", type=int, default=2, help="measurements a point (median)")
    ap.add_argument("--raw", help="read the rows from these files (comma-separated; the "
                    "median a point) instead of measuring")
    ap.add_argument("--save", help="write the measured rows to this file")
    a = ap.parse_args()
    a.orders = [int(x) for x in a.orders.split(",")]
    a.sys = [int(x) for x in a.sys.split(",")]
    if a.raw:
        rows = median_rows([read_raw(path) for path in a.raw.split(",")])
    else:
        rounds = []
        for _ in range(a.rounds):
            print("# load %s" % open("/proc/loadavg").read().strip(), file=sys.stderr)
            rounds.append(measure(a))
        rows = median_rows(rounds)
        if a.save:
            save_raw(a.save, rows)
    if a.knee < 0:
        a.knee = None
    cur, cur_knee = current_model()
    m0 = report("cost.c now", rows, cur, cur_knee)
    m1 = report("refit", rows, fit(rows, None), None)
    if a.knee == 0:
        def score(k):
            return statistics.median(abs(x) for x in misfit(rows, fit(rows, k), k))
        a.knee = min(range(500, 6001, 100), key=score)
    models = [("cost.c now", cur, cur_knee), ("refit", fit(rows, None), None)]
    if a.knee is not None:
        models.append(("refit, knee", fit(rows, a.knee), a.knee))
        m1 = report("refit with a knee at products p^2 = %g" % a.knee, rows, models[-1][1],
                    a.knee)
    orders_table(rows, models)
    # the ratios are what the choice of the order reads: the misfit's spread
    # within a system, not its level, moves the choice
    print("\nmisfit spread within a system (max - min), now / refit:")
    for s in dict.fromkeys(r["system"] for r in rows):
        i = [k for k, r in enumerate(rows) if r["system"] == s]
        print("  %-16s %4.0f %% / %4.0f %%" % (s, 100 * (max(m0[k] for k in i) - min(m0[k] for k in i)),
                                             100 * (max(m1[k] for k in i) - min(m1[k] for k in i))))


if __name__ == "__main__":
    sys.exit(main())
