"""The cross-checks: each runs one engine of hamlie and an independent
route on one zoo system and records whether they agree (ctx.record).

Tolerances are relative to the size of the state, scale = max |z_i|: at an
amplitude of 1e-8 an error of 4e-10 is 4 %, not a pass."""

import math

import mpmath
import sympy

import truth
from zoo import common_args, init_arg, variables


# the fields of a JSON answer that may be null (docs/json.md)
RUN_NULLABLE = ("sigma_final", "max_error", "out", "plot")
ERRORS_NULLABLE = ("leading", "invariants", "time", "corrected", "map", "K",
                   "h", "lambda", "scale", "tau", "tan_half_tau",
                   "double_step", "fails_at", "rational", "hamiltonians",
                   "polynomial",
                   # the check of the v_k by K(D), omitted past its budget
                   # (the JSON then says why: check_omitted)
                   "two_ways_agree", "K_coefficients")


def scale_of(state):
    return max([1e-30] + [abs(float(v)) for v in state.values()])


def distance(a, b):
    return max(abs(mpmath.mpf(a[k]) - mpmath.mpf(b[k])) for k in a)


def whole_steps(t, dt):
    """t rounded to a whole number of steps of dt."""
    return round(t / dt) * dt


# ---- the Taylor integrator: double against Arb, against closed forms -------

def taylor_tolerance(scale, t):
    """Relative 1e-10 per unit of time, and the integrator's absolute
    tolerance (1e-15 a step) where the amplitude is tiny."""
    return (1e-10 * scale + 1e-14) * (1 + t)


def taylor(ctx, s, point, t, digits=None, H=None):
    args = ["run"] + common_args(s, H) + ["--scheme", "lie", "--dt", t,
                                          "--t", t, "--init", init_arg(point),
                                          "--json"]
    args += ["--digits", digits] if digits else ["--tol", "1e-15"]
    return ctx.hamlie(*args)


def check_taylor(ctx, s, label, point):
    """double (tol 1e-15) against Arb at 30 digits, H conserved, and the
    closed form where there is one. Returns the double run's final state."""
    t = s["t"]
    d = taylor(ctx, s, point, t)
    a = taylor(ctx, s, point, t, digits=30)
    if not ctx.expect_done("taylor-double", s, label, None, d,
                           allow_null=RUN_NULLABLE):
        return None
    if not ctx.expect_done("taylor-arb30", s, label, None, a,
                           allow_null=("out",)):
        return None
    zd, za = d.json["final_state"], a.json["final_state"]
    sc = scale_of(za)
    gap = distance(zd, za)
    ctx.record("taylor-double-vs-arb30", s, label, None,
               gap <= taylor_tolerance(sc, t),
               "|z_double - z_arb| = %.3g at t = %g" % (gap, t), d)
    H0 = d.json["H0"]
    dH = d.json["max_abs_dH"]
    ctx.record("taylor-H-conserved", s, label, None,
               dH is not None and dH <= 1e-11 * max(1, abs(H0)),
               "max |H - H0| = %s (H0 = %s)" % (dH, H0), d)
    exact = truth.closed_form(s, point, t)
    if exact is None and ctx.ode_truth and len(variables(s)) == 2:
        exact = truth.ode(s, point, t)
    if exact is not None:
        gap = distance(zd, exact)
        ctx.record("taylor-vs-closed-form", s, label, None,
                   gap <= taylor_tolerance(sc, t),
                   "|z_double - truth| = %.3g at t = %g" % (gap, t), d)
    return zd


# ---- the exact flow (1 dof) against the Taylor integrator ------------------

def check_exact(ctx, s, label, point, taylor_state):
    """run --scheme exact against the closed form, else against the Taylor
    integrator's state at the same time (taylor_state, when given)."""
    dt = 0.5
    t = whole_steps(s["t"], dt)
    o = ctx.hamlie("run", *common_args(s), "--scheme", "exact", "--dt", dt,
                   "--t", t, "--init", init_arg(point), "--no-reference",
                   "--json")
    if not ctx.expect_done("exact-run", s, label, "exact", o,
                           allow_null=RUN_NULLABLE):
        return
    ze = o.json["final_state"]
    ref = truth.closed_form(s, point, t)
    what = "closed form"
    if ref is None:
        if taylor_state is None or t != s["t"]:
            r = taylor(ctx, s, point, t)
            if not r.ok or r.json is None:
                return
            taylor_state = r.json["final_state"]
        ref, what = taylor_state, "Taylor integrator"
    gap = distance(ze, ref)
    ctx.record("exact-vs-" + ("truth" if what == "closed form" else "taylor"),
               s, label, "exact",
               gap <= 1e-10 * scale_of(ref) * (1 + t) + 1e-15,
               "|z_exact - %s| = %.3g at t = %g" % (what, gap, t), o)


# ---- symbolic v_k against numeric v_k --------------------------------------

def check_fields(ctx, s, label, point, scheme, order):
    if ctx.skip_known_hang("errors-symbolic", s, label, scheme["name"]):
        return
    sym = ctx.hamlie("errors", *common_args(s), "--scheme", scheme["name"],
                     "--order", order, "--json")
    if not ctx.expect_done("errors-symbolic", s, label, scheme["name"], sym,
                           allow_null=ERRORS_NULLABLE):
        return
    num = ctx.hamlie("errors", *common_args(s), "--scheme", scheme["name"],
                     "--order", order, "--numeric", "--at", init_arg(point),
                     "--json")
    if not ctx.expect_done("errors-numeric", s, label, scheme["name"], num,
                           allow_null=ERRORS_NULLABLE + ("K_coefficients",)):
        return
    worst, where = 0.0, ""
    ok = True
    loc = truth.symbols_of(s)
    loc["D"] = sympy.Symbol("D")
    for fs, fn in zip(sym.json["fields"], num.json["fields"]):
        for v, text in fs["v"].items():
            value = truth.at(sympy.sympify(text, locals=loc), s, point)
            got = fn["v"][v]
            if got is None:
                ok, where = False, "v_%d[%s] is null" % (fs["k"], v)
                continue
            gap = abs(value - got)
            tol = 10 * fn["threshold"] + 1e-12
            if gap > tol:
                ok = False
            if gap / tol > worst:
                worst = float(gap / tol)
                where = "v_%d[%s]: symbolic %.6g, numeric %.6g" % (
                    fs["k"], v, float(value), got)
    ctx.record("vk-symbolic-vs-numeric", s, label, scheme["name"], ok,
               "worst %s (%.2g of the tolerance)" % (where, worst), num)
    order_sym = sym.json["order"]
    if scheme["order"] is not None:
        ctx.record("vk-order-vs-catalog", s, label, scheme["name"],
                   order_sym >= min(scheme["order"], order - 1),
                   "symbolic order %s, catalog %s" % (order_sym,
                                                      scheme["order"]), sym)
    if scheme["symplectic"] and sym.json.get("map"):
        check_map_canonical(ctx, s, label, scheme, sym.json["map"], point)



# ---- canonicity: J^T Omega J = Omega --------------------------------------

def omega_defect(jac, n):
    """max |J^T Omega J - Omega| for a 2n x 2n Jacobian (q's then p's)."""
    Om = mpmath.zeros(2 * n, 2 * n)
    for i in range(n):
        Om[i, n + i], Om[n + i, i] = 1, -1
    R = jac.T * Om * jac - Om
    return max(abs(R[i, j]) for i in range(2 * n) for j in range(2 * n))


def check_map_canonical(ctx, s, label, scheme, images, point, D=0.1):
    """An explicit scheme's map from `errors --json`, differentiated by SymPy."""
    loc = truth.symbols_of(s)
    loc["D"] = sympy.Symbol("D")
    z = variables(s)
    n = len(s["q"])
    J = mpmath.zeros(2 * n, 2 * n)
    for i, v in enumerate(z):
        img = sympy.sympify(images[v], locals=loc).subs(loc["D"],
                                                         sympy.Rational(D))
        for j, w in enumerate(z):
            J[i, j] = truth.at(sympy.diff(img, loc[w]), s, point)
    defect = omega_defect(J, n)
    ctx.record("canonical-map-sympy", s, label, scheme["name"], defect < 1e-14,
               "max |J^T Om J - Om| = %.3g at D = %g" % (float(defect), D), None)


def one_step(ctx, s, scheme, point, dt):
    o = ctx.hamlie("run", *common_args(s), "--scheme", scheme, "--dt", dt,
                   "--t", dt, "--init", init_arg(point), "--no-reference",
                   "--json")
    return o


def check_step_canonical(ctx, s, label, scheme, point, dt=0.1, eps=1e-5):
    """Any scheme: the Jacobian of one step by central differences."""
    if ctx.skip_known_hang("step", s, label, scheme["name"]):
        return
    z = variables(s)
    n = len(s["q"])
    J = mpmath.zeros(2 * n, 2 * n)
    for j, w in enumerate(z):
        cols = []
        for sign in (1, -1):
            moved = dict(point)
            moved[w] = float(point[w]) + sign * eps
            o = one_step(ctx, s, scheme["name"], moved, dt)
            if not ctx.expect_done("step", s, label, scheme["name"], o,
                                   allow_null=RUN_NULLABLE):
                return
            cols.append(o.json["final_state"])
        for i, v in enumerate(z):
            J[i, j] = (mpmath.mpf(cols[0][v]) - mpmath.mpf(cols[1][v])) / (2 * eps)
    defect = omega_defect(J, n)
    ctx.record("canonical-step-jacobian", s, label, scheme["name"],
               defect < 1e-6, "max |J^T Om J - Om| = %.3g (differences, "
               "dt = %g)" % (float(defect), dt), o)


# ---- observed order against the catalog; H conserved ------------------------

def check_orders(ctx, s, label, scheme, point):
    if ctx.skip_known_hang("run-orders", s, label, scheme["name"]):
        return
    p = scheme["order"]
    steps = (0.2, 0.1, 0.05)
    t = 2
    o = ctx.hamlie("run", *common_args(s), "--scheme", scheme["name"],
                   "--orders", ",".join(map(str, steps)), "--t", t,
                   "--init", init_arg(point), "--json")
    if not ctx.expect_done("run-orders", s, label, scheme["name"], o,
                           allow_null=("order", "order_final")):
        return
    rows = o.json["orders"]
    errs = [r["max_error"] for r in rows]
    size = scale_of(point)
    if max(errs) < 1e-11 * size:
        ctx.record("order-vs-catalog", s, label, scheme["name"], None,
                   "errors at round-off (%s): not measurable" % errs, o)
        return
    if errs[-1] > 0.05 * size and errs[-2] > 1.1 * errs[-1]:
        # decreasing, but the steps are too long for this orbit
        ctx.record("order-vs-catalog", s, label, scheme["name"], None,
                   "errors %s: not yet asymptotic" % errs, o)
        return
    last = rows[-1]["order"]
    ok = last is not None and last >= p - 0.3 and (last <= p + 1.2)
    ctx.record("order-vs-catalog", s, label, scheme["name"], ok,
               "observed %s, catalog %d (errors %s)" % (
                   "%.3f" % last if last is not None else None, p,
                   ", ".join("%.3g" % e for e in errs)), o)


def check_energy(ctx, s, label, scheme, point):
    if ctx.skip_known_hang("run-energy", s, label, scheme["name"]):
        return
    dt, t = 0.1, 2
    o = ctx.hamlie("run", *common_args(s), "--scheme", scheme["name"], "--dt",
                   dt, "--t", t, "--init", init_arg(point), "--no-reference",
                   "--json")
    if not ctx.expect_done("run-energy", s, label, scheme["name"], o,
                           allow_null=RUN_NULLABLE):
        return
    H0, dH = o.json["H0"], o.json["max_abs_dH"]
    steps = round(t / dt)
    ctx.record("H-conserved", s, label, scheme["name"],
               dH <= 1e-13 * steps * max(1, abs(H0)),
               "max |H - H0| = %.3g over %d steps (H0 = %.6g)" % (dH, steps, H0),
               o)


# ---- the same H written two ways -------------------------------------------

def check_two_ways(ctx, s, label, point, schemes):
    for name in schemes:
        if ctx.skip_known_hang("run-two-ways", s, label, name):
            continue
        runs = []
        for H in (s["H"], s["H2"]):
            if name == "lie":
                runs.append(taylor(ctx, s, point, 1, H=H))
            else:
                runs.append(ctx.hamlie("run", *common_args(s, H), "--scheme",
                                       name, "--dt", 0.1, "--t", 1, "--init",
                                       init_arg(point), "--no-reference",
                                       "--json"))
        if not all(ctx.expect_done("run-two-ways", s, label, name, r,
                                   allow_null=RUN_NULLABLE)
                   for r in runs):
            continue
        a, b = (r.json["final_state"] for r in runs)
        gap = distance(a, b)
        same_order = list(a) == list(b)
        ctx.record("same-H-two-ways", s, label, name,
                   gap <= 1e-13 * scale_of(a) and same_order,
                   "final states %.3g apart%s" % (
                       gap, "" if same_order else
                       "; variables in another order: %s vs %s" % (list(a), list(b))),
                   runs[1])
    g = [ctx.hamlie("generator", *common_args(s, H), "--json")
         for H in (s["H"], s["H2"])]
    if all(ctx.expect_done("generator", s, "two-ways", None, o) for o in g):
        ctx.record("same-H-two-ways-symbols", s, "-", "generator",
                   g[0].json["symbols"] == g[1].json["symbols"],
                   "%s vs %s" % (g[0].json["symbols"]["coordinates"],
                                 g[1].json["symbols"]["coordinates"]), g[1])


# ---- SymPy as the truth: generator, Lie series ----------------------------

def check_sympy(ctx, s, points):
    order = s["lie_order"]
    z, f = truth.vector_field(s)
    loc = truth.symbols_of(s)
    g = ctx.hamlie("generator", *common_args(s), "--json")
    if ctx.expect_done("generator", s, "-", None, g):
        worst = 0
        for name, fi in zip(map(str, z), f):
            mine = sympy.sympify(g.json["generator"][name], locals=loc)
            for _, pt in points:
                worst = max(worst, abs(truth.at(mine - fi, s, pt)))
        ctx.record("generator-vs-sympy", s, "-", None, worst < 1e-20,
                   "max |g_hamlie - g_sympy| = %.3g" % float(worst), g)
    lie = ctx.hamlie("lie", *common_args(s), "--order", order, "--json")
    if not ctx.expect_done("lie", s, "-", None, lie):
        return
    loc["D"] = sympy.Symbol("D")
    worst, where = 0, ""
    for entry in lie.json["series"]:
        var = entry["input"]
        mine = [sympy.sympify(c, locals=loc) for c in entry["coefficients"]]
        ref = truth.lie_coefficients(s, var, order)
        for k, (a, b) in enumerate(zip(mine, ref)):
            for _, pt in points:
                va, vb = truth.at(a, s, pt), truth.at(b, s, pt)
                gap = abs(va - vb) / max(1, abs(vb))
                if gap > worst:
                    worst, where = gap, "D^%d of %s" % (k, var)
    ctx.record("lie-vs-sympy", s, "-", None, worst < 1e-20,
               "max relative gap %.3g (%s)" % (float(worst), where), lie)


def finite(x):
    return x is not None and math.isfinite(x)


# ---- defects found by the harness itself: one case each ---------------------

REG_N2 = [("itoh-abe", "px^2/2 + py^2/2 + y*px + x^2/2",
           "x=-0.4,y=0.7,px=0.7,py=-0.15"),
          ("yoshida4", "p^2/2 + q^2*p", "q=0.3,p=0.2"),
          ("yoshida4", "p^2/2 + q*p", "q=0.3,p=0.2"),
          ("avf", "p^2/2 + p*q^2", "q=0.4907,p=0.7674"),  # crashed (SIGSEGV)
          ("itoh-abe", "p^2/2 + p*q^2", "q=0.4907,p=0.7674")]
KEPLER = "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)"
NEAR_COLLISION = "x=-0.85292,y=0.741467,px=0.285809,py=-0.46234"


def check_regressions(ctx):
    """N2: a scheme that applies to any H runs on these (some crashed) (its error against
    the Taylor integrator after one step of 0.1 is O(dt^2) at most). N3: a
    scheme that claims to preserve H either does, or stops with exit 2."""
    for scheme, H, init in REG_N2:
        o = ctx.hamlie("run", "-H", H, "--scheme", scheme, "--dt", 0.1, "--t",
                       0.1, "--init", init, "--json")
        ok = o.ok and o.json is not None and finite(o.json["max_error"])
        ctx.record("regression-N2", None, H, scheme,
                   ok and o.json["max_error"] < 1e-2,
                   "max_error %s" % o.json["max_error"] if ok else o.why(), o)
    # N7: an orbit that meets a singularity of the field: the Taylor
    # integrator stops there (as it does for 1/p: "step size underflow")
    if not ctx.skip_known_hang("regression-N7", None, "essential-singularity",
                               "lie"):
        o = ctx.hamlie("run", "-H", "10*q + sin(1/p)", "--pairs", "q:p",
                       "--scheme", "lie", "--tol", "1e-12", "--t", 1,
                       "--init", "q=0,p=0.01", "--json")
        ctx.record("regression-N7", None, "essential-singularity", "lie",
                   o.rc == 2 and not o.crashed and "error" in o.err, o.why(), o)
    o = ctx.hamlie("run", "-H", KEPLER, "--scheme", "avf", "--dt", 0.1, "--t",
                   2, "--init", NEAR_COLLISION, "--no-reference", "--json")
    if o.ok and o.json is not None:
        dH = o.json["max_abs_dH"]
        ctx.record("regression-N3", None, "near-collision", "avf",
                   finite(dH) and dH < 1e-10,
                   "exit 0 with max |H - H0| = %s" % dH, o)
    else:
        ctx.record("regression-N3", None, "near-collision", "avf",
                   o.rc == 2 and not o.crashed, o.why(), o)
