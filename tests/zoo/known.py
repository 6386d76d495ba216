"""Failures that belong to a defect of issue 13 being fixed in another
branch. Each entry: the defect's number and patterns (regular expressions)
over the check's kind, the system, the point's label, the scheme (or the
command, for random Hamiltonians) and the failure's detail. A
listed failure is counted as expected; a listed case that passes is said
(the defect's fix has landed: remove its entry)."""

import re

KNOWN = [
    # 1: the Taylor integrator takes one huge step where the last Taylor
    # coefficients vanish (quartic wells started at the bottom); every
    # result that uses it as a reference inherits it
    dict(defect=1, system="quartic|quartic-2d", label="bottom|p<0",
         kind="taylor-.*|exact-vs-taylor|order-vs-catalog"),
    # 2: the exact flow by quadrature at equilibria, tiny amplitudes, near
    # separatrices, pendulum rotations and librations from the bottom
    dict(defect=2, kind="exact-.*",
         system="(?!harmonic|inverted|field).*",  # quadratic H: closed form
         label="equilibrium.*|saddle|near-separatrix.*|rotation"),
    dict(defect=2, kind="exact-.*", system="pendulum", label="bottom|tiny-.*"),
    dict(defect=2, kind="exact-.*", system="quartic|nonlinear-osc",
         label="tiny-.*"),
    dict(defect=2, kind="exact-run-done", system="pendulum",
         detail="unbounded orbit.*"),  # rotations (E > 1)
    # 6: the closed-form K(D) of `errors` swells (no answer in the CPU
    # budget) on Kepler, the double pendulum and Calogero-Moser
    dict(defect=6, kind="errors-symbolic-done", hang=True,
         system="kepler-.*|double-pendulum|calogero-2",
         scheme="rk4|gonzalez"),
    # (soak, every scheme: the same with rk4, yoshida4, lie at order 5 on
    # 1-dof polynomial and radical H, and at order 3 on random H)
    dict(defect=6, kind="errors-symbolic-done", detail="no answer.*"),
    dict(defect=6, kind="random-robust", scheme="errors", detail="no answer.*"),
    # 7: the Gauss-Legendre set-up swells on Kepler; on Calogero-Moser it
    # is refused ("an expression nested more than 10000 deep")
    dict(defect=7, kind="run-.*-done|step-done", system="kepler-.*",
         scheme="gauss.*", hang=True),
    dict(defect=7, kind="run-.*-done|step-done", system="calogero-2",
         scheme="gauss3"),
    # 8: the order of the phase variables follows H's writing (the zoo's
    # second writings that move a name forward)
    dict(defect=8, kind="same-H-two-ways.*",
         system="aniso-2d|aniso-3d|coupled-osc|kepler-2d|kepler-3d|toda-2"),
    # ---- found by this harness, beyond the twelve -------------------------
    # N4: the section-4 analysis of RK4 on the Toda lattices (2 and 3 dof) is
    # refused: "too many functions and roots (the limit is 32)"
    dict(defect="N4", kind="errors-symbolic-done", system="toda-.*",
         scheme="rk4"),
    # N5: Gonzalez's discrete gradient at an equilibrium (Z = z, the
    # difference quotient 0/0): "the Jacobian of the scheme's equations is
    # singular"; errors --numeric: "does not determine the unknowns"
    dict(defect="N5", kind="run-.*-done|errors-numeric-done|step-done",
         label="equilibrium|saddle|origin", scheme="gonzalez"),
    # N6: errors --numeric with the paper's discrete gradient on the
    # oscillator: "numeric analysis: division by a series that is zero"
    # (the symbolic analysis of the same scheme works)
    dict(defect="N6", kind="errors-numeric-done", system="harmonic",
         scheme="paper-dg"),
    # N7 (random H in the soak): "no answer" from run; the regression case
    # (10*q + sin(1/p) from p = 0.01, an essential singularity) now stops
    # with "no progress", see tests/cli/hangs.sh
    dict(defect="N7", kind="random-robust", scheme="run", detail="no answer.*"),
]


def known_hang(kind, system, label, scheme):
    """Whether this case is listed as one that runs out of its budget."""
    d = _entry(kind, system, label, scheme, None)
    return bool(d and d.get("hang"))


def defect_of(kind, system, label, scheme, detail):
    d = _entry(kind, system, label, scheme, detail)
    return d["defect"] if d else None


def _entry(kind, system, label, scheme, detail):
    """The first entry matching; detail None (before the call) matches
    only entries without a detail pattern."""
    for d in KNOWN:
        if "detail" in d and (detail is None
                              or not re.search(d["detail"], detail)):
            continue
        if (re.fullmatch(d.get("kind", ".*"), kind)
                and re.fullmatch(d.get("system", ".*"), system)
                and re.fullmatch(d.get("label", ".*"), label)
                and re.fullmatch(d.get("scheme", ".*"), scheme)):
            return d
    return None
