#!/usr/bin/env python3
"""The peer of bench/lie_series.c: the same Lie series computed in SymPy.

For each coordinate z of the system, the terms g^k z (k = 0..order) with
g(phi) = {phi, H}, each kept in normal form the way a SymPy user would
(expand for polynomials, cancel for rational functions with a square root),
then sum D^k/k! g^k z.  Prints one line per system: name, order, CPU seconds.
With --print NAME: computes NAME's series once and prints them, as `hamlie
lie` does; bench/run-lie.sh times that whole process (start-up and import
included).
"""
import sys
import time

import sympy as sp


def lie_series(H, qs, ps, order, normal):
    D = sp.Symbol("D")
    out = []
    for z in qs + ps:
        term, total = z, z
        for k in range(1, order + 1):
            term = normal(sum(sp.diff(term, q) * sp.diff(H, p) - sp.diff(term, p) * sp.diff(H, q)
                              for q, p in zip(qs, ps)))
            total += D**k / sp.factorial(k) * term
        out.append(total)
    return out


def bench(name, H, qs, ps, order, normal, repeat):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.process_time()  # CPU: the machine may be shared
        lie_series(H, qs, ps, order, normal)
        best = min(best, time.process_time() - t0)
    print(f"{name} {order} {best:.6f}", flush=True)


def systems():
    x, y, px, py = sp.symbols("x y px py")
    return {
        "henon-heiles": ((px**2 + py**2) / 2 + (x**2 + y**2) / 2 + x**2 * y - y**3 / 3,
                         [x, y], [px, py], 12, sp.expand),
        "kepler": ((px**2 + py**2) / 2 - 1 / sp.sqrt(x**2 + y**2), [x, y], [px, py], 8,
                   sp.cancel),
    }


def main():
    if sys.argv[1:2] == ["--print"]:
        H, qs, ps, order, normal = systems()[sys.argv[2]]
        for z, total in zip(qs + ps, lie_series(H, qs, ps, order, normal)):
            print(f"exp(D g) {z} = {total} + O(D^{order + 1})")
        return
    which = sys.argv[1:] or ["henon-heiles", "kepler"]
    for name, (H, qs, ps, order, normal) in systems().items():
        if name in which:
            bench(name, H, qs, ps, order, normal, 1)


if __name__ == "__main__":
    main()
