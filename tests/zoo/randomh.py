"""Random Hamiltonians from the formula grammar (sums, products, quotients,
powers of the phase variables and a parameter; sin, cos, exp, sqrt, log,
atan of them), pushed through generator, lie, errors and run: whatever the
answer, never a crash, a hang, or a value that is not finite reported with
exit 0."""

from call import non_finite_paths
from checks import ERRORS_NULLABLE, RUN_NULLABLE

FUNCS = ("sin", "cos", "exp", "sqrt", "log", "atan", "tanh")
DOF_NAMES = {1: (["q"], ["p"]), 2: (["x", "y"], ["px", "py"]),
             3: (["q1", "q2", "q3"], ["p1", "p2", "p3"])}


def leaf(rng, names):
    r = rng.random()
    if r < 0.6:
        return rng.choice(names)
    if r < 0.7:
        return "k"
    if r < 0.9:
        return str(rng.randint(1, 5))
    return "%d/%d" % (rng.randint(1, 9), rng.randint(2, 7))


def tree(rng, names, depth):
    if depth == 0 or rng.random() < 0.25:
        return leaf(rng, names)
    r = rng.random()
    a = tree(rng, names, depth - 1)
    if r < 0.3:
        return "(%s %s %s)" % (a, rng.choice("+-"), tree(rng, names, depth - 1))
    if r < 0.5:
        return "%s*%s" % (a, tree(rng, names, depth - 1))
    if r < 0.58:
        return "%s/(%s)" % (a, tree(rng, names, depth - 1))
    if r < 0.72:
        return "(%s)^%d" % (a, rng.choice((2, 3, 4, -1, -2)))
    return "%s(%s)" % (rng.choice(FUNCS), a)


def hamiltonian(rng):
    """(H, q names, p names): a kinetic part so that H moves, plus a
    random tree (at times mixing q and p)."""
    dof = rng.choice((1, 1, 2, 2, 3))
    q, p = DOF_NAMES[dof]
    kinetic = " + ".join("%s^2/2" % v for v in p)
    return "%s + %s" % (kinetic, tree(rng, q + p, rng.choice((2, 3, 4)))), q, p


SCHEMES = ("euler", "rk4", "stormer-verlet-kdk", "implicit-midpoint", "lie",
           "symplectic-euler-a", "avf", "itoh-abe")


def case(ctx, rng, index):
    H, q, p = hamiltonian(rng)
    point = ",".join("%s=%.4f" % (v, rng.uniform(-1, 1)) for v in q + p)
    scheme = rng.choice(SCHEMES)
    label = "random-H-%d" % index
    calls = [
        (("generator", "-H", H, "--json"), ()),
        (("lie", "-H", H, "--order", 3, "--json"), ()),
        (("errors", "-H", H, "--param", "k=2", "--scheme", scheme, "--order",
          3, "--json"), ERRORS_NULLABLE),
        (("errors", "-H", H, "--param", "k=2", "--scheme", scheme, "--order",
          4, "--numeric", "--at", point, "--json"),
         ERRORS_NULLABLE + ("K_coefficients",)),
        (("run", "-H", H, "--param", "k=2", "--scheme", scheme, "--dt", 0.1,
          "--t", 1, "--init", point, "--json"), RUN_NULLABLE),
        (("run", "-H", H, "--param", "k=2", "--scheme", "lie", "--tol", 1e-12,
          "--t", 1, "--init", point, "--json"), RUN_NULLABLE),
    ]
    for args, nullable in calls:
        o = ctx.hamlie(*args)
        robust(ctx, label, args[0], o, nullable)


def robust(ctx, label, command, o, nullable):
    """Exit 0 with finite JSON, or exit 1/2 with a message; anything else
    is recorded as a failure."""
    if o.hung or o.crashed:
        ctx.record("random-robust", None, label, command, False, o.why(), o)
        return
    if o.rc == 0:
        bad = (["stdout is not JSON"] if o.json is None
               else non_finite_paths(o.json, allow_null=nullable))
        ctx.record("random-robust", None, label, command, not bad,
                   "exit 0 with " + "; ".join(bad[:3]) if bad else "exit 0", o)
        return
    ok = o.rc in (1, 2) and "error" in o.err.lower()
    ctx.record("random-robust", None, label, command, ok,
               "exit %s: %s" % (o.rc, o.err.strip()[:120]), o)
