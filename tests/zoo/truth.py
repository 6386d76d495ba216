"""Truths that do not come from hamlie: SymPy's derivatives and Lie
series, the flow of a quadratic H as a matrix exponential (mpmath), the
pendulum by Jacobi's elliptic functions, the nonlinear oscillator
(q^2+p^2)^2/4 in closed form, and mpmath's own Taylor ODE solver."""

import mpmath
import sympy

mpmath.mp.dps = 30


def symbols_of(s):
    names = s["q"] + s["p"] + list(s["params"])
    return {n: sympy.Symbol(n) for n in names}


def sympy_H(s, text=None):
    """H with the parameters substituted (hamlie's ^ is sympy's **)."""
    loc = symbols_of(s)
    H = sympy.sympify((text or s["H"]).replace("^", "**"), locals=loc)
    return H.subs({loc[k]: sympy.nsimplify(v) for k, v in s["params"].items()})


def vector_field(s):
    """(z, f) with f = J grad H: dq/dt = H_p, dp/dt = -H_q."""
    loc = symbols_of(s)
    H = sympy_H(s)
    q = [loc[n] for n in s["q"]]
    p = [loc[n] for n in s["p"]]
    f = [sympy.diff(H, v) for v in p] + [-sympy.diff(H, v) for v in q]
    return q + p, f


def lie_coefficients(s, var, order):
    """g^k var / k!, k = 0..order, as SymPy expressions (not simplified)."""
    z, f = vector_field(s)
    phi = symbols_of(s)[var]
    out = []
    for k in range(order + 1):
        out.append(phi / sympy.factorial(k))
        phi = sum(fi * sympy.diff(phi, zi) for fi, zi in zip(f, z))
    return out


def at(expr, s, point):
    """A SymPy expression at a point, to 30 correct digits: the point's
    doubles as exact rationals, so that evalf raises its precision where
    terms cancel (the Yoshida map's coefficients cancel to 1e-8, its v_5's
    terms of 1e107 to 1e2: evalf's default of 100 extra digits gave 0e+6)."""
    loc = symbols_of(s)
    vals = {loc[k]: sympy.Rational(float(v)) for k, v in point.items()}
    return mpmath.mpf(sympy.N(expr.subs(vals), 30, maxn=4000))


def linear_flow(s, point, t):
    """The flow of a quadratic H: z(t) = expm(t M) (z0, 1), M = [[A, b], [0, 0]]
    with J grad H = A z + b."""
    z, f = vector_field(s)
    n = len(z)
    zero = {v: 0 for v in z}
    M = mpmath.zeros(n + 1, n + 1)
    for i, fi in enumerate(f):
        for j, zj in enumerate(z):
            M[i, j] = mpmath.mpf(sympy.N(sympy.diff(fi, zj), 30))
        M[i, n] = mpmath.mpf(sympy.N(fi.subs(zero), 30))
    z0 = mpmath.matrix([float(point[str(v)]) for v in z] + [1])
    zt = mpmath.expm(M * t) * z0
    return {str(v): zt[i] for i, v in enumerate(z)}


def pendulum(point, t):
    """p^2/2 - cos q: librations by sn/cn, rotations by am/dn."""
    q0, p0 = mpmath.mpf(point["q"]), mpmath.mpf(point["p"])
    E = p0 ** 2 / 2 - mpmath.cos(q0)
    if E < 1:
        k = mpmath.sqrt((1 + E) / 2)
        m = k ** 2
        if k == 0:
            return {"q": q0, "p": p0}
        K = mpmath.ellipk(m)
        s0 = mpmath.sin(q0 / 2) / k
        s0 = max(min(s0, 1), -1)
        u0 = mpmath.ellipf(mpmath.asin(s0), m)
        if p0 < 0:
            u0 = 2 * K - u0
        u = u0 + t
        sn = mpmath.ellipfun("sn", u, m=m)
        cn = mpmath.ellipfun("cn", u, m=m)
        # q stays in the well of q0: its centre is 2 pi round(q0 / 2 pi)
        centre = 2 * mpmath.pi * mpmath.nint(q0 / (2 * mpmath.pi))
        return {"q": centre + 2 * mpmath.asin(k * sn), "p": 2 * k * cn}
    m = 2 / (E + 1)
    w = mpmath.sqrt((E + 1) / 2)
    sign = 1 if p0 > 0 else -1
    u = mpmath.ellipf(q0 / 2, m) + sign * w * t
    phi = _am(u, m)
    return {"q": 2 * phi, "p": sign * 2 * w * mpmath.ellipfun("dn", u, m=m)}


def _am(u, m):
    """Jacobi's amplitude for any real u: am(u + 2K) = am(u) + pi."""
    K = mpmath.ellipk(m)
    j = mpmath.nint(u / (2 * K))
    r = u - 2 * K * j
    return j * mpmath.pi + mpmath.atan2(mpmath.ellipfun("sn", r, m=m),
                                        mpmath.ellipfun("cn", r, m=m))


def nonlinear_oscillator(point, t):
    """(q^2+p^2)^2/4: a rotation at the rate w = q^2 + p^2."""
    q0, p0 = mpmath.mpf(point["q"]), mpmath.mpf(point["p"])
    w = q0 ** 2 + p0 ** 2
    c, sn = mpmath.cos(w * t), mpmath.sin(w * t)
    return {"q": q0 * c + p0 * sn, "p": p0 * c - q0 * sn}


def ode(s, point, t):
    """mpmath's Taylor-series ODE solver on J grad H (independent of
    hamlie's integrator)."""
    z, f = vector_field(s)
    F = sympy.lambdify(z, f, modules="mpmath")
    y0 = [mpmath.mpf(float(point[str(v)])) for v in z]
    with mpmath.workdps(20):
        sol = mpmath.odefun(lambda _t, y: F(*y), 0, y0)
        yt = sol(t)
    return {str(v): yt[i] for i, v in enumerate(z)}


def closed_form(s, point, t):
    """The closed-form flow when the system has one, else None."""
    if "quadratic" in s["tags"]:
        return linear_flow(s, point, t)
    if s["name"] == "pendulum":
        return pendulum(point, t)
    if s["name"] == "nonlinear-osc":
        return nonlinear_oscillator(point, t)
    return None
