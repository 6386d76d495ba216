#!/usr/bin/env python3
"""The peer of bench/errors_analysis.c (issue 4): the same error fields in SymPy.

For a one-step scheme psi_D with expansion sum_k D^k psi_k, the error fields
    v_k(z) = k! ([D^k] psi_D(z) - g^k z / k!),   k = 2..order,
for every coordinate z (g phi = {phi, H}, the Lie terms by diff).
  rk4-henon-heiles:  the four RK4 stages with D a Symbol, expanded.
  midpoint-pendulum: Q = q + D (p + P)/2, P = p - D sin((q + Q)/2) solved as a
                     series in D by fixed-point iteration, sin expanded in
                     Taylor form around q, truncated at D^order each pass.
Prints one line per case: name, order, seconds (or "timeout").
  --order=N: another order (8 by default; --check uses 5: the v_k for k <= N
  do not depend on N, the truncation only drops higher powers of D).
  --check: prints v_3 and v_5 of each case as sympify-able strings (JSON).
"""
import json
import signal
import sys
import time

import sympy as sp

D = sp.Symbol("D")
TIMEOUT = 600


def trunc(e, n):
    """e, a polynomial in D, without its terms of degree > n."""
    p = sp.Poly(sp.expand(e), D)
    return sum((c * D**k for (k,), c in p.terms() if k <= n), sp.S.Zero)


def lie_terms(H, qs, ps, order, normal):
    """g^k z for k = 0..order, for every coordinate z."""
    out = []
    for z in qs + ps:
        t = [z]
        for _ in range(order):
            t.append(normal(sum(sp.diff(t[-1], q) * sp.diff(H, p) - sp.diff(t[-1], p) * sp.diff(H, q)
                                for q, p in zip(qs, ps))))
        out.append(t)
    return out


def fields(psi, H, qs, ps, order, normal):
    """v[k][i] = k! ([D^k] psi_i - g^k z_i / k!), k = 0..order."""
    lie = lie_terms(H, qs, ps, order, normal)
    v = [[None] * len(psi) for _ in range(order + 1)]
    for i, e in enumerate(psi):
        for k in range(order + 1):
            c = e.coeff(D, k) if k else e.subs(D, 0)
            v[k][i] = normal(sp.factorial(k) * c - lie[i][k])
    return v


def rk4_henon_heiles(order):
    x, y, px, py = sp.symbols("x y px py")
    H = (px**2 + py**2) / 2 + (x**2 + y**2) / 2 + x**2 * y - y**3 / 3
    qs, ps = [x, y], [px, py]
    z = qs + ps
    rhs = [sp.diff(H, p) for p in ps] + [-sp.diff(H, q) for q in qs]

    def f(w):
        return [r.subs(dict(zip(z, w)), simultaneous=True) for r in rhs]

    k1 = f(z)
    k2 = f([a + D / 2 * b for a, b in zip(z, k1)])
    k3 = f([a + D / 2 * b for a, b in zip(z, k2)])
    k4 = f([a + D * b for a, b in zip(z, k3)])
    psi = [sp.expand(a + D / 6 * (b1 + 2 * b2 + 2 * b3 + b4))
           for a, b1, b2, b3, b4 in zip(z, k1, k2, k3, k4)]
    return fields(psi, H, qs, ps, order, sp.expand)


def midpoint_pendulum(order):
    q, p = sp.symbols("q p")
    H = p**2 / 2 - sp.cos(q)
    dq, dp = sp.S.Zero, sp.S.Zero  # Q = q + dq, P = p + dp
    derivs = [sp.sin(q), sp.cos(q), -sp.sin(q), -sp.cos(q)]
    for _ in range(order + 1):  # each pass gains one order
        # sin(q + u) = sum_j u^j/j! sin^(j)(q), u = dq/2 = O(D); the powers of
        # u truncated as they are built (expanding u**j whole is ~90x slower)
        u, uj, s = dq / 2, sp.S.One, derivs[0]
        for j in range(1, order):
            uj = trunc(uj * u, order - 1)
            s += uj / sp.factorial(j) * derivs[j % 4]
        dq, dp = trunc(D * (2 * p + dp) / 2, order), trunc(-D * s, order)
    Q, P = q + dq, p + dp
    assert sp.simplify(Q.coeff(D, 2) + sp.sin(q) / 2) == 0, "Q_2 != -sin(q)/2"
    assert sp.simplify(P.coeff(D, 2) + p * sp.cos(q) / 2) == 0, "P_2 != -p cos(q)/2"
    return fields([Q, P], H, [q], [p], order, sp.expand)


CASES = {"rk4-henon-heiles": rk4_henon_heiles, "midpoint-pendulum": midpoint_pendulum}


class Timeout(Exception):
    pass


def on_alarm(signum, frame):
    raise Timeout


def main():
    args = sys.argv[1:]
    check = "--check" in args
    which = [a for a in args if not a.startswith("--")] or list(CASES)
    order = 8
    for a in args:
        if a.startswith("--order="):
            order = int(a.split("=")[1])
    signal.signal(signal.SIGALRM, on_alarm)
    for name in which:
        signal.alarm(TIMEOUT)
        try:
            t0 = time.perf_counter()
            v = CASES[name](order)
            t = time.perf_counter() - t0
        except Timeout:
            print(f"{name} {order} timeout", flush=True)
            continue
        finally:
            signal.alarm(0)
        if check:
            print(json.dumps({"case": name, "v3": [str(c) for c in v[3]],
                              "v5": [str(c) for c in v[5]]}), flush=True)
        else:
            print(f"{name} {order} {t:.6f}", flush=True)


if __name__ == "__main__":
    main()
