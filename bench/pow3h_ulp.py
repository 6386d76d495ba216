#!/usr/bin/python3
"""Accuracy of w^(3/2) in double (issue 17, src/rules/pow3h.c): the error in
ulps of the result, against mpmath at 60 digits, of
  w*sqrt(w)       (hamlie's POW3H: two roundings)
  sqrt(w*w*w)     (three roundings, the first two halved by the root)
  pow(w, 1.5)     (glibc, via Python's math.pow, which calls it)
  fma-corrected   fma(w, r, -(fma(r, r, -w) (r / 2))), r = sqrt(w): w sqrt(w) is
                  w r - (r^2 - w) r / 2 up to u^2 (not used: where the result
                  overflows, from w ~ 2^720 the correction, u times the result,
                  does too, and about half of those w give -inf; +inf gives NaN)
for w log-uniform over [1e-200, 1e200] (N draws; results normal) and uniform
in [1, 4) (one period of the error pattern).  fma is exact in Fraction, then
rounded once.
Usage: /usr/bin/python3 bench/pow3h_ulp.py [N]   (N = 20000: about 3 s of CPU)"""
import math
import random
import sys
from fractions import Fraction

import mpmath

mpmath.mp.dps = 60


def fma(a, b, c):
    return float(Fraction(a) * Fraction(b) + Fraction(c))


def ulps(got, w):
    exact = mpmath.mpf(w) ** mpmath.mpf(1.5)
    if not math.isfinite(got):
        return math.inf
    ulp = math.ulp(float(exact))  # the spacing at the rounded result, subnormals included
    return float(abs(mpmath.mpf(got) - exact) / ulp)


def forms(w):
    r = math.sqrt(w)
    p = w * r
    www = w * w * w
    out = {"w*sqrt(w)": p, "pow(w,1.5)": math.pow(w, 1.5)}
    out["sqrt(w*w*w)"] = math.sqrt(www) if math.isfinite(www) and www > 0 else math.nan
    out["fma-corrected"] = fma(w, r, -(fma(r, r, -w) * (r / 2)))
    return out


def sample(n, draw):
    """per form: the worst error and its w, the sum of errors, the number
    correctly rounded, the number not finite (sqrt(w*w*w) overflowing)"""
    worst, total, exact, lost = {}, {}, {}, {}
    for _ in range(n):
        w = draw()
        for name, v in forms(w).items():
            e = ulps(v, w)
            lost[name] = lost.get(name, 0) + (not math.isfinite(e))
            if not math.isfinite(e):
                continue
            if e > worst.get(name, (-1, 0))[0]:
                worst[name] = (e, w)
            total[name] = total.get(name, 0) + e
            exact[name] = exact.get(name, 0) + (e <= 0.5)
    return worst, total, exact, lost


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 200000
    random.seed(17)
    for label, draw in [("log-uniform 1e-200..1e200", lambda: 10 ** random.uniform(-200, 200)),
                        ("uniform [1, 4)", lambda: random.uniform(1, 4))]:
        worst, total, exact, lost = sample(n, draw)
        print(f"{label}, {n} draws:")
        for name in worst:
            e, w = worst[name]
            m = n - lost[name]
            print(f"  {name:12} max {e:6.3f} ulp (w = {w!r}), mean {total[name] / m:5.3f}, "
                  f"correctly rounded {100 * exact[name] / m:5.1f} %, "
                  f"not finite {100 * lost[name] / n:4.1f} %")


if __name__ == "__main__":
    main()
