#!/usr/bin/env python3
"""The differential-testing harness of issue 13: every engine of hamlie
against an independent route, on the zoo (zoo.py) and on random
Hamiltonians (randomh.py).

usage: driver.py HAMLIE [--seed N] [--points N] [--random N] [--all-schemes]
                 [--stride K] [--minutes M] [--cpu S] [--jobs J] [--ode]
                 [--run-known-hangs] [--only RE] [--no-zoo]

Prints each failure with a command line that reproduces it, then the
counts. A failure listed in known.py (a defect of issue 13 being fixed
elsewhere) is counted as expected, and said when it passes. Exit status 1
when a check fails that is not listed, or a call crashes or hangs."""

import argparse
import json
import os
import random
import re
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import checks  # noqa: E402
import known  # noqa: E402
import randomh  # noqa: E402
from call import PYTHON, Hamlie, non_finite_paths  # noqa: E402
from zoo import ZOO, points  # noqa: E402


class Context:
    """The binary, the options, and the tally of every check."""

    def __init__(self, hamlie, opts):
        self.hamlie, self.opts = hamlie, opts
        self.ode_truth = opts.ode
        self.lock = threading.Lock()
        self.counts = {"pass": 0, "fail": 0, "xfail": 0, "xpass": 0, "n/a": 0}
        self.kinds = {}
        self.crashes = self.hangs = 0
        self.cases = 0
        self.failures, self.xpasses, self.xfails = [], [], []
        self.deadline = time.monotonic() + 60 * opts.minutes if opts.minutes else None

    def count_case(self):
        with self.lock:
            self.cases += 1

    def out_of_time(self):
        return self.deadline is not None and time.monotonic() > self.deadline

    def record(self, kind, s, label, scheme, passed, detail, outcome):
        system = s["name"] if s else "-"
        defect = known.defect_of(kind, system, label, scheme or "-", detail)
        with self.lock:
            tally = self.kinds.setdefault(kind, [0, 0])
            if passed is None:
                self.counts["n/a"] += 1
                return
            tally[0 if passed else 1] += 1
            if outcome is not None and outcome.hung:
                self.hangs += 1
            if outcome is not None and outcome.crashed:
                self.crashes += 1
            line = "%s %s [%s] %s: %s" % (kind, system, label, scheme or "",
                                          detail)
            repro = outcome.repro() if outcome is not None else ""
            if passed and defect:
                self.counts["xpass"] += 1
                self.xpasses.append("defect %s now passes: %s" % (defect, line))
            elif passed:
                self.counts["pass"] += 1
            elif defect:
                self.counts["xfail"] += 1
                self.xfails.append((defect, line, repro))
            else:
                self.counts["fail"] += 1
                self.failures.append((line, repro))
                print("FAIL " + line + ("\n    " + repro if repro else ""),
                      flush=True)

    def skip_known_hang(self, kind, s, label, scheme):
        """A case listed as running out of its budget is not run (each
        would cost the whole budget), unless --run-known-hangs (soak.sh)."""
        if self.opts.run_known_hangs or not known.known_hang(
                kind + "-done", s["name"] if s else "-", label, scheme or "-"):
            return False
        self.record(kind, s, label, scheme, None, "known hang, not run", None)
        return True

    def expect_done(self, kind, s, label, scheme, o, allow_null=()):
        """A call that must succeed: exit 0, JSON, every number finite.
        Records a failure (and returns False) otherwise."""
        if o.ok and o.json is not None:
            bad = non_finite_paths(o.json, allow_null=allow_null)
            if not bad:
                return True
            why = "exit 0 with " + "; ".join(bad[:3])
        else:
            why = o.why()
        self.record(kind + "-done", s, label, scheme, False, why, o)
        return False


def applicable(scheme, s):
    if scheme["exact"] or scheme["order"] is None:
        return False
    if scheme["oscillator_only"]:
        return s["name"] in ("harmonic",)
    if scheme["quadratic_only"]:
        return "quadratic" in s["tags"]
    return True


def rotate(items, start, count):
    if not items:
        return []
    if count >= len(items):
        return list(items)
    return [items[(start + j) % len(items)] for j in range(count)]


def system_cases(ctx, index, s, catalog):
    o = ctx.opts
    rng = random.Random("%d/%s" % (o.seed, s["name"]))
    pts = points(s, rng, o.points)
    first_random = [p for p in pts if p[0].startswith("random")][:1] or pts[:1]
    usable = [c for c in catalog if applicable(c, s)]
    everything = o.all_schemes
    # the Taylor integrator at every point; the exact flow for 1 dof
    for label, point in pts:
        if ctx.out_of_time():
            return
        ctx.count_case()
        zd = checks.check_taylor(ctx, s, label, point)
        if len(s["q"]) == 1 and ("even_p" in s["tags"]):
            checks.check_exact(ctx, s, label, point, zd)
    # SymPy: the generator and the Lie series
    checks.check_sympy(ctx, s, first_random + pts[:1])
    # symbolic against numeric v_k
    for c in (usable if everything else rotate(usable, 5 * index, 2)):
        if ctx.out_of_time():
            return
        order = min((c["order"] or 4) + 1, 5)
        checks.check_fields(ctx, s, first_random[0][0], first_random[0][1], c,
                            order)
    # observed orders: from a random point, and from the bottom of the well
    # (a turning point of p where the odd Taylor coefficients vanish)
    order_points = first_random + [p for p in pts if p[0] == "bottom"]
    for c in (usable if everything else rotate(usable, 3 * index, 4)):
        for label, point in (order_points if everything else order_points[:1]):
            if ctx.out_of_time():
                return
            checks.check_orders(ctx, s, label, c, point)
    if not everything and order_points[1:]:
        rk4 = [c for c in usable if c["name"] == "rk4"]
        for c in rk4:
            checks.check_orders(ctx, s, order_points[1][0], c, order_points[1][1])
    # H conserved where the catalog says so
    keepers = [c for c in usable if c["preserves_H"]]
    for c in (keepers if everything else rotate(keepers, index, 1)):
        checks.check_energy(ctx, s, first_random[0][0], c, first_random[0][1])
    # canonicity of one step by differences, where the scheme is symplectic
    symplectic = [c for c in usable if c["symplectic"]]
    if everything or len(s["q"]) <= 2:
        for c in (symplectic if everything else rotate(symplectic, index, 1)):
            if ctx.out_of_time():
                return
            checks.check_step_canonical(ctx, s, first_random[0][0], c,
                                        first_random[0][1])
    # the same H written two ways
    two = ["lie", "itoh-abe"] + (["rk4", "gonzalez"] if everything else [])
    checks.check_two_ways(ctx, s, first_random[0][0], first_random[0][1], two)


def run_random(ctx, count, seed):
    rng = random.Random(seed)
    for i in range(count):
        if ctx.out_of_time():
            return i
        ctx.count_case()
        randomh.case(ctx, rng, i)
    return count


def quick_defaults(opts):
    """Under the sanitizers (a build directory named *asan*, or
    HAMLIE_ZOO_QUICK=1) every call is several times slower: a third of the zoo,
    fewer random cases, a larger CPU budget. Options given win."""
    quick = ("asan" in os.path.abspath(opts.hamlie)
             or os.environ.get("HAMLIE_ZOO_QUICK") == "1")
    for name, normal, sanitized in (("points", 1, 1), ("random", 30, 15),
                                    ("stride", 1, 3), ("cpu", 5, 20)):
        if getattr(opts, name) is None:
            setattr(opts, name, sanitized if quick else normal)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("hamlie")
    ap.add_argument("--seed", type=int, default=13)
    ap.add_argument("--points", type=int, default=None,
                    help="random initial points per system, besides the "
                    "special ones (default 1)")
    ap.add_argument("--random", type=int, default=None,
                    help="random Hamiltonians (default 30)")
    ap.add_argument("--stride", type=int, default=None,
                    help="every k-th zoo system (default 1: all)")
    ap.add_argument("--all-schemes", action="store_true",
                    help="every applicable scheme on every system (else a rotation)")
    ap.add_argument("--minutes", type=float, default=0,
                    help="stop starting new cases after this time (0: no limit)")
    ap.add_argument("--cpu", type=float, default=None,
                    help="CPU seconds per call before it counts as a hang "
                    "(default 5)")
    ap.add_argument("--run-known-hangs", action="store_true",
                    help="also run the cases known.py lists as hangs")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--ode", action="store_true",
                    help="also mpmath.odefun as the truth for 1-dof systems")
    ap.add_argument("--only", default="", help="systems whose name matches")
    ap.add_argument("--no-zoo", action="store_true")
    opts = ap.parse_args()
    quick_defaults(opts)

    ham = Hamlie(opts.hamlie, opts.cpu)
    ctx = Context(ham, opts)
    start = time.monotonic()
    cat = ham("schemes", "--json")
    catalog = json.loads(cat.out)["schemes"]
    zoo = [s for s in ZOO[::opts.stride] if re.search(opts.only, s["name"])]
    random_done = [0]

    def one_at_a_time(task, *args):
        with PYTHON.held():
            task(*args)

    def zoo_task(i, s):
        system_cases(ctx, i, s, catalog)

    def random_task():
        random_done[0] = run_random(ctx, opts.random, opts.seed)

    # the random Hamiltonians run beside the zoo (one more worker), so that
    # a time budget (--minutes) is shared between them
    with ThreadPoolExecutor(max_workers=opts.jobs + 1) as pool:
        futures = [pool.submit(one_at_a_time, random_task),
                   pool.submit(one_at_a_time, checks.check_regressions, ctx)]
        if not opts.no_zoo:
            futures += [pool.submit(one_at_a_time, zoo_task, i, s)
                        for i, s in enumerate(zoo)]
        for f in futures:
            f.result()
    report(ctx, zoo if not opts.no_zoo else [], random_done[0],
           time.monotonic() - start)
    return 1 if ctx.failures else 0


def report(ctx, zoo, randoms, seconds):
    c = ctx.counts
    for defect, line, repro in sorted(ctx.xfails, key=str):
        print("expected (defect %s): %s\n    %s" % (defect, line, repro))
    for line in ctx.xpasses:
        print(line)
    print("\nper check (passed/failed):")
    for kind in sorted(ctx.kinds):
        print("  %-32s %5d %5d" % (kind, *ctx.kinds[kind]))
    dofs = sorted({len(s["q"]) for s in zoo})
    print("\nzoo systems: %d (dof %s); random Hamiltonians: %d; cases (initial "
          "points and random H): %d; calls: %d; %.0f s"
          % (len(zoo), dofs, randoms, ctx.cases, ctx.hamlie.calls, seconds))
    print("cross-checks: %d passed, %d failed, %d expected failures (known "
          "defects), %d known defects passing, %d not measurable"
          % (c["pass"], c["fail"], c["xfail"], c["xpass"], c["n/a"]))
    print("crashes: %d, hangs: %d" % (ctx.crashes, ctx.hangs))
    if ctx.out_of_time():
        print("time budget reached: the cases after it were not started")


if __name__ == "__main__":
    sys.exit(main())
