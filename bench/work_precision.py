#!/usr/bin/python3
"""Work-precision benchmark: errors against the exact solutions, the figure,
and the speed ratios at equal error.  Run by bench/work_precision.sh; needs
Debian's python3 (mpmath, matplotlib), not a pyenv one.

Input: the raw rows of bench/work_precision.c and its peers (heyoka, Boost),
  method,system,T,tol,order,steps,ms,compile_ms,z0,z1[,z2,z3]
Output: a CSV with the errors (--csv), the figure (--png) and, on standard
output, the table of time ratios at equal final error (markdown).

The exact solutions, all from the initial state as the methods have it
(the doubles nearest 1.3, 0.1, sqrt 3, ...), in mpmath at 40 digits:
  oscillator    x = cos t, p = -sin t;
  pendulum      from (q0, 0): sin(q/2) = k sn(t + K, k^2), p = 2 k cn(t + K, k^2),
                k = sin(q0/2) (Jacobi elliptic functions, the argument reduced
                modulo the period 4K first);
  kepler        the two-body solution from the state's orbital elements
                (Kepler's equation E - e sin E = M solved by Newton);
  henon-heiles  no closed form: hamlie's Arb integrator at the most digits
                given (rows 'ref'; the second most, if present, says how far
                the reference itself is from the truth).
The final error is max_i |z_i(T) - z_i^exact(T)| over the whole state.
"""
import argparse
import csv
import math
import sys

import mpmath as mp

mp.mp.dps = 40

SYSTEMS = ["oscillator", "pendulum", "henon-heiles", "kepler"]
INITIAL = {
    "oscillator": [1.0, 0.0],
    "pendulum": [1.3, 0.0],
    "henon-heiles": [0.1, -0.1, 0.05, 0.1],
    "kepler": [0.5, 0.0, 0.0, 1.7320508075688772],
}


def energy(system, z):
    if system == "oscillator":
        return (z[0] ** 2 + z[1] ** 2) / 2
    if system == "pendulum":
        return z[1] ** 2 / 2 - mp.cos(z[0])
    if system == "henon-heiles":
        x, y, px, py = z
        return (px**2 + py**2) / 2 + (x**2 + y**2) / 2 + x**2 * y - y**3 / 3
    x, y, px, py = z
    return (px**2 + py**2) / 2 - 1 / mp.sqrt(x**2 + y**2)


def exact_oscillator(z0, t):
    x0, p0 = z0
    return [x0 * mp.cos(t) + p0 * mp.sin(t), p0 * mp.cos(t) - x0 * mp.sin(t)]


def exact_pendulum(z0, t):
    q0, p0 = z0
    assert p0 == 0, "the closed form here starts at a turning point"
    k = mp.sin(q0 / 2)
    m = k**2
    K = mp.ellipk(m)
    u = mp.fmod(t + K, 4 * K)
    sn = mp.ellipfun("sn", u, m=m)
    cn = mp.ellipfun("cn", u, m=m)
    return [2 * mp.asin(k * sn), 2 * k * cn]


def kepler_newton(M, e):
    E = M if e < 0.8 else mp.pi
    for _ in range(100):
        d = (E - e * mp.sin(E) - M) / (1 - e * mp.cos(E))
        E -= d
        if abs(d) < mp.mpf(10) ** (-mp.mp.dps + 2):
            break
    return E


def exact_kepler(z0, t):
    """mu = 1, an ellipse: elements from the state, M advanced by n t."""
    x, y, vx, vy = z0
    r = mp.sqrt(x**2 + y**2)
    v2 = vx**2 + vy**2
    a = 1 / (2 / r - v2)
    rv = x * vx + y * vy
    ex = (v2 - 1 / r) * x - rv * vx
    ey = (v2 - 1 / r) * y - rv * vy
    e = mp.sqrt(ex**2 + ey**2)
    w = mp.atan2(ey, ex)
    h = x * vy - y * vx
    E0 = mp.atan2(rv / mp.sqrt(a), 1 - r / a)  # e sin E0 = rv/sqrt(a), e cos E0 = 1 - r/a
    n = a ** mp.mpf(-1.5)
    M = mp.fmod(E0 - e * mp.sin(E0) + n * t, 2 * mp.pi)
    E = kepler_newton(M, e)
    b = a * mp.sqrt(1 - e**2)
    Edot = n / (1 - e * mp.cos(E))
    xp, yp = a * (mp.cos(E) - e), b * mp.sin(E)
    vxp, vyp = -a * mp.sin(E) * Edot, b * mp.cos(E) * Edot
    if h < 0:  # a retrograde orbit: the perifocal y axis flips
        yp, vyp = -yp, -vyp
    c, s = mp.cos(w), mp.sin(w)
    return [c * xp - s * yp, s * xp + c * yp, c * vxp - s * vyp, s * vxp + c * vyp]


EXACT = {"oscillator": exact_oscillator, "pendulum": exact_pendulum, "kepler": exact_kepler}


def self_check():
    """The closed forms at t = 0 give the initial state, and conserve H."""
    for s, f in EXACT.items():
        z0 = [mp.mpf(v) for v in INITIAL[s]]
        z = f(z0, mp.mpf(0))
        assert max(abs(a - b) for a, b in zip(z, z0)) < mp.mpf(10) ** -30, (s, z)
        z = f(z0, mp.mpf(123.4))
        assert abs(energy(s, z) - energy(s, z0)) < mp.mpf(10) ** -30, s


def read_rows(paths):
    rows = []
    for path in paths:
        with open(path) as fh:
            for rec in csv.reader(fh):
                if not rec or rec[0].startswith("#"):
                    continue
                m, s, T, tol, order, steps, ms, cms = rec[:8]
                rows.append(dict(method=m, system=s, T=float(T), tol=float(tol), order=int(order),
                                 steps=int(steps), ms=float(ms), compile_ms=float(cms),
                                 z=[mp.mpf(v) for v in rec[8:]]))
    return rows


def references(rows):
    """(system, T) -> (state, its own error estimate or None, where from)"""
    ref = {}
    for s in SYSTEMS:
        for T in sorted({r["T"] for r in rows if r["system"] == s}):
            z0 = [mp.mpf(v) for v in INITIAL[s]]
            arb = sorted((r for r in rows if r["method"] == "ref" and r["system"] == s
                          and r["T"] == T), key=lambda r: r["tol"])
            if s in EXACT:
                zx = EXACT[s](z0, mp.mpf(T))
                # an Arb reference, where there is one, checks the closed form
                check = max(abs(a - b) for a, b in zip(arb[0]["z"], zx)) if arb else None
                ref[(s, T)] = (zx, check, "closed form")
            elif arb:
                own = (max(abs(a - b) for a, b in zip(arb[0]["z"], arb[1]["z"]))
                       if len(arb) > 1 else None)
                ref[(s, T)] = (arb[0]["z"], own, "Arb %.0f digits" % -math.log10(arb[0]["tol"]))
    return ref


def errors(rows, ref):
    out = []
    for r in rows:
        if r["method"] == "ref" or (r["system"], r["T"]) not in ref:
            continue
        zx = ref[(r["system"], r["T"])][0]
        err = max(abs(a - b) for a, b in zip(r["z"], zx))
        z0 = [mp.mpf(v) for v in INITIAL[r["system"]]]
        E0 = energy(r["system"], z0)
        dE = abs(energy(r["system"], r["z"]) - E0) / abs(E0)
        out.append(dict(r, err=float(err), relE=float(dE)))
    return out


def front(points):
    """The Pareto front of (error, ms): sorted by error, time falling."""
    pts = sorted(points)
    fr = []
    for e, t in pts:
        if e <= 0:
            e = 1e-300
        if not fr or t < fr[-1][1]:
            fr.append((e, t))
    return fr


def time_at(fr, err):
    """The least time reaching error <= err, log-log interpolated on the
    front; None where the method never reaches err."""
    if not fr or err < fr[0][0]:
        return None
    for (e1, t1), (e0, t0) in zip(fr, fr[1:]):  # e1 < e0, t1 > t0
        if e1 <= err <= e0:
            f = (math.log(err) - math.log(e1)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(t1) + f * (math.log(t0) - math.log(t1)))
    return fr[-1][1]


def ratio_table(res, base, peers):
    print("| system | T | tol | %s error | %s ms | " % (base, base)
          + " | ".join("%s/%s" % (p, base) for p in peers) + " |")
    print("|---|---|---|---|---|" + "---|" * len(peers))
    for s in SYSTEMS:
        for T in sorted({r["T"] for r in res if r["system"] == s}):
            fronts = {p: front([(r["err"], r["ms"]) for r in res
                                if r["method"] == p and r["system"] == s and r["T"] == T])
                      for p in peers}
            for r in sorted((r for r in res if r["method"] == base and r["system"] == s
                             and r["T"] == T), key=lambda r: -r["tol"]):
                cells = []
                for p in peers:
                    tp = time_at(fronts[p], r["err"])
                    cells.append("-" if not fronts[p] else "not reached" if tp is None
                                 else "%.2f" % (tp / r["ms"]))
                print("| %s | %g | %g | %.1e | %.2f | %s |"
                      % (s, T, r["tol"], r["err"], r["ms"], " | ".join(cells)))


def ratio_summary(res, base, peers):
    """Per system and T: the median and the range of peer time / base time
    over base's points that the peer reaches."""
    print("| system | T | " + " | ".join("%s/%s median (min-max, n)" % (p, base) for p in peers)
          + " |")
    print("|---|---|" + "---|" * len(peers))
    for s in SYSTEMS:
        for T in sorted({r["T"] for r in res if r["system"] == s}):
            cells = []
            for p in peers:
                fr = front([(r["err"], r["ms"]) for r in res
                            if r["method"] == p and r["system"] == s and r["T"] == T])
                q = sorted(time_at(fr, r["err"]) / r["ms"] for r in res
                           if r["method"] == base and r["system"] == s and r["T"] == T
                           and fr and time_at(fr, r["err"]) is not None)
                n = len(q)
                cells.append("-" if not n else "%.2f (%.2f-%.2f, %d)"
                             % ((q[n // 2] if n % 2 else (q[n // 2 - 1] + q[n // 2]) / 2), q[0],
                                q[-1], n))
            print("| %s | %g | %s |" % (s, T, " | ".join(cells)))


STYLE = {
    "hamlie-native": ("C0", "o", "-"),
    "hamlie-interp": ("C0", "o", ":"),
    "heyoka": ("C3", "s", "-"),
    "rk8pd": ("C2", "^", "-"),
    "rkf78": ("C1", "v", "-"),
}


def figure(res, path):
    """One panel per system and T: error against time, each method's points
    joined in the order of its tolerances (1e-9 first).  The Arb runs
    (--digits), far off both axes, are written in the panel instead."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    Ts = sorted({r["T"] for r in res})
    fig, axes = plt.subplots(len(Ts), 4, figsize=(16, 4.2 * len(Ts)), squeeze=False)
    for i, T in enumerate(Ts):
        for j, s in enumerate(SYSTEMS):
            ax = axes[i][j]
            sel = [r for r in res if r["system"] == s and r["T"] == T]
            for m, (c, mk, ls) in STYLE.items():
                pts = sorted((-r["tol"], r["ms"], max(r["err"], 1e-18)) for r in sel
                             if r["method"] == m)
                if pts:
                    ax.loglog([p[1] for p in pts], [p[2] for p in pts], color=c, marker=mk,
                              linestyle=ls, label=m, markersize=4)
            arb = sorted((r for r in sel if r["method"] == "hamlie-arb"), key=lambda r: r["tol"],
                         reverse=True)
            text = "\n".join("--digits %.0f: %.0e in %.3g s" % (-math.log10(r["tol"]), r["err"],
                                                                 r["ms"] / 1e3) for r in arb)
            if text:
                ax.text(0.97, 0.97, "Arb: " + text, transform=ax.transAxes, ha="right",
                        va="top", fontsize=7, color="C5")
            ax.set_title("%s, t = %g" % (s, T))
            ax.set_xlabel("integration, CPU time (ms)")
            if j == 0:
                ax.set_ylabel("final error max |z - z_exact|")
            ax.grid(True, which="major", alpha=0.3)
    axes[0][0].legend(fontsize=8, loc="lower left")
    fig.suptitle("work-precision: tol 1e-9 ... 1e-16, integration alone, best of several runs "
                 "(bench/work_precision.sh); the Arb runs: wall clock", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=80)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("raw", nargs="+")
    ap.add_argument("--csv")
    ap.add_argument("--png")
    a = ap.parse_args()
    self_check()
    rows = read_rows(a.raw)
    ref = references(rows)
    print("## References\n")
    for (s, T), (_, own, src) in sorted(ref.items()):
        note = ("" if own is None else
                ", %s %.1e" % ("Arb reference differs from it by" if src == "closed form"
                               else "differs from the next-lower-digit Arb run by", float(own)))
        print("- %s, t = %g: %s%s" % (s, T, src, note))
    res = errors(rows, ref)
    if a.csv:
        with open(a.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["method", "system", "T", "tol", "order", "steps", "ms", "compile_ms",
                        "err", "relE"])
            for r in res:
                w.writerow([r["method"], r["system"], "%g" % r["T"], "%g" % r["tol"], r["order"],
                            r["steps"], "%.4f" % r["ms"], "%.2f" % r["compile_ms"],
                            "%.3e" % r["err"], "%.3e" % r["relE"]])
    print("\n## Final errors at the same tol (hamlie-native vs heyoka)\n")
    print("| system | T | tol | hamlie err | heyoka err | hamlie rel. dE | heyoka rel. dE "
          "| hamlie steps | heyoka steps |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in res:
        if r["method"] != "hamlie-native":
            continue
        h = [x for x in res if x["method"] == "heyoka" and x["system"] == r["system"]
             and x["T"] == r["T"] and x["tol"] == r["tol"]]
        print("| %s | %g | %g | %.1e | %s | %.1e | %s | %d | %s |"
              % (r["system"], r["T"], r["tol"], r["err"], "%.1e" % h[0]["err"] if h else "-",
                 r["relE"], "%.1e" % h[0]["relE"] if h else "-", r["steps"],
                 h[0]["steps"] if h else "-"))
    print("\n## Time of the peer / time of hamlie-native at hamlie's final error\n")
    print("(> 1: hamlie faster; the peer's time interpolated log-log on its "
          "error-time front; 'not reached': no tolerance of the peer got that error)\n")
    methods = {r["method"] for r in res}
    peers = [m for m in ("heyoka", "rk8pd", "rkf78", "hamlie-interp") if m in methods]
    ratio_summary(res, "hamlie-native", peers)
    print()
    ratio_table(res, "hamlie-native", peers)
    if a.png:
        figure(res, a.png)


if __name__ == "__main__":
    sys.exit(main())
