#!/usr/bin/python3
"""Is the order the rule chooses on the error-time front?  (issue 17)

For each system, final time and tolerance, runs bench-work_precision at the
rule's order (order=0) and at every order from Jorba & Zou's to a few past
the rule's (order=P, the step of hl_flow_rule_at: the same tail), native
code, and computes the final errors against the exact solutions
(bench/work_precision.py; Henon-Heiles against an Arb reference).  Then,
per system and time, the front of (error, time) over all the runs, and for
the rule's runs and for Jorba & Zou's: time / the front's time at the same
error (1: on the front; 1.2: 20 % slower than the best order at that error).

Usage: bench/order_front.py [build-dir] [--sys 2,3] [--T 1e4,1e5]
       [--tols 1e-9,...,1e-13] [--above 3] [--reps 3] [--ref FILE] [--raw FILE]
--ref: 'ref' rows for Henon-Heiles (bench-work_precision sys=2 T=.. methods=none
ref=40; made if absent, which takes minutes).  --raw: reuse the rows of a
previous run (written to --save).  Needs Debian's python3 (mpmath).
"""
import argparse
import math
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import work_precision as wp  # noqa: E402


def p_jz(tol):
    return math.ceil(-math.log(tol) / 2) + 1


def run(bench, args):
    out = subprocess.run([bench] + args, check=True, capture_output=True, text=True).stdout
    return [line for line in out.splitlines() if line]


def measure(a):
    """Raw rows, method 'rule' for order=0 and 'order' for the forced ones."""
    bench = os.path.join(a.build, "bench-work_precision")
    lines = []
    for s in a.sys:
        for T in a.T:
            for tol in a.tols:
                common = ["sys=%d" % s, "T=%g" % T, "tols=%g" % tol, "reps=%d" % a.reps,
                          "methods=native"]
                rule = run(bench, common)[0]
                lines.append(rule.replace("hamlie-native", "rule", 1))
                chosen = int(rule.split(",")[4])
                for p in range(p_jz(tol), max(chosen, p_jz(tol)) + a.above + 1):
                    for line in run(bench, common + ["order=%d" % p]):
                        lines.append(line.replace("hamlie-native", "order", 1))
                print("# %s T %g tol %g: rule's order %d" % (lines[-1].split(",")[1], T, tol,
                                                              chosen), file=sys.stderr)
    return lines


def analyse(res):
    print("| system | T | tol | order (JZ, rule) | steps | ms | error "
          "| time / front's at that error | time / least at this tol |")
    print("|---|---|---|---|---|---|---|---|---|")
    summary = {}
    for s in dict.fromkeys(r["system"] for r in res):
        for T in sorted({r["T"] for r in res if r["system"] == s}):
            pts = [r for r in res if r["system"] == s and r["T"] == T]
            fr = wp.front([(r["err"], r["ms"]) for r in pts])
            for tol in sorted({r["tol"] for r in pts}, reverse=True):
                rule = [r for r in pts if r["tol"] == tol and r["method"] == "rule"][0]
                at_tol = [r for r in pts if r["tol"] == tol and r["method"] == "order"]
                least = min(r["ms"] for r in at_tol)
                for r in sorted(at_tol, key=lambda r: r["order"]):
                    tag = []
                    if r["order"] == p_jz(tol):
                        tag.append("JZ")
                    if r["order"] == rule["order"]:
                        tag.append("rule")
                    slow = r["ms"] / wp.time_at(fr, r["err"])
                    print("| %s | %g | %g | %d %s | %d | %.2f | %.2e | %.2f | %.2f |" %
                          (s, T, tol, r["order"], " ".join(tag), r["steps"], r["ms"], r["err"],
                           slow, r["ms"] / least))
                    for t in tag:
                        summary.setdefault((s, T, t), []).append(slow)
                        summary.setdefault((s, T, t + "-tol"), []).append(r["ms"] / least)
                summary.setdefault((s, T, "rule-run"), []).append(
                    rule["ms"] / wp.time_at(fr, rule["err"]))
    print("\n| system | T | rule: time / front's at its error (median; per tol) | JZ: the same "
          "| rule: time / least at its tol | JZ: the same |")
    print("|---|---|---|---|---|---|")
    for s in dict.fromkeys(k[0] for k in summary):
        for T in sorted({k[1] for k in summary if k[0] == s}):
            cells = []
            for t in ("rule", "JZ", "rule-tol", "JZ-tol"):
                v = summary.get((s, T, t), [])
                cells.append("%.2f (%s)" % (statistics.median(v), " ".join("%.2f" % x for x in v))
                             if v else "-")
            print("| %s | %g | %s |" % (s, T, " | ".join(cells)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("build", nargs="?", default="build")
    ap.add_argument("--sys", default="2,3")
    ap.add_argument("--T", default="1e4,1e5")
    ap.add_argument("--tols", default="1e-9,1e-10,1e-11,1e-12,1e-13")
    ap.add_argument("--above", type=int, default=3, help="orders past the rule's")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--ref", default="/tmp/order-front-ref.csv")
    ap.add_argument("--raw")
    ap.add_argument("--save", default="/tmp/order-front-raw.csv")
    a = ap.parse_args()
    a.sys = [int(x) for x in a.sys.split(",")]
    a.T = [float(x) for x in a.T.split(",")]
    a.tols = [float(x) for x in a.tols.split(",")]
    if a.raw is None:
        print("# load %s" % open("/proc/loadavg").read().strip(), file=sys.stderr)
        with open(a.save, "w") as fh:
            fh.write("\n".join(measure(a)) + "\n")
        a.raw = a.save
    if 2 in a.sys and not (os.path.exists(a.ref) and os.path.getsize(a.ref)):
        with open(a.ref, "w") as fh:
            fh.write("\n".join(run(os.path.join(a.build, "bench-work_precision"),
                                   ["sys=2", "T=" + ",".join("%g" % T for T in a.T),
                                    "methods=none", "ref=40"])) + "\n")
    rows = wp.read_rows([a.raw] + ([a.ref] if 2 in a.sys else []))
    analyse(wp.errors(rows, wp.references(rows)))


if __name__ == "__main__":
    sys.exit(main())
