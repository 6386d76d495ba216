"""Failures the harness knows and that are still open (the twelve defects
of issue 13 are fixed: their entries are gone, so a regression fails).
Each entry: the defect's number and patterns (regular expressions)
over the check's kind, the system, the point's label, the scheme (or the
command, for random Hamiltonians) and the failure's detail. A
listed failure is counted as expected; a listed case that passes is said
(the defect's fix has landed: remove its entry)."""

import re

KNOWN = [
    # 6 (what is left of it): the symbolic expansion of Gonzalez's
    # discrete gradient on Kepler (0/0 over |Z - z|^2 with radicals of both
    # points: minutes), and RK4 there at the edge of the CPU budget; the
    # double pendulum and Calogero-Moser not re-checked
    dict(defect=6, kind="errors-symbolic-done", hang=True,
         system="kepler-.*|double-pendulum|calogero-2",
         scheme="rk4|gonzalez"),
    # (soak, every scheme: the same with rk4, yoshida4, lie at order 5 on
    # 1-dof polynomial and radical H, and at order 3 on random H)
    dict(defect=6, kind="errors-symbolic-done", detail="no answer.*"),
    dict(defect=6, kind="random-robust", scheme="errors", detail="no answer.*"),
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
