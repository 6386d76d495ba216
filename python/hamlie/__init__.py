"""hamlie from Python: Lie-series analysis of Hamiltonian systems.

    import hamlie, sympy as sp
    s = hamlie.System("p^2/2 - cos(q)")
    s.generator()                      # {q: p, p: -sin(q)}
    e = s.errors("stormer-verlet-kdk", order=6)
    r = s.run("rk4", dt=0.1, t=100, init={"q": 1.3, "p": 0})

Everything is computed by hamlie's C library (libhamlie) through the
extension module ``hamlie._hamlie``; see docs/python.md.
"""
from . import _hamlie
from ._hamlie import Error
from ._sympy import HamliePrinter, to_text
from .results import Check, Errors, Run
from .system import System

__all__ = ["System", "Error", "Errors", "Run", "Check", "schemes", "to_text", "HamliePrinter"]
__version__ = "0.1.0"


def schemes():
    """The catalog of one-step schemes: a list of dicts (name, order,
    symplectic, preserves_H, implicit, ..., description, text), as
    `hamlie schemes --json` lists them."""
    return _hamlie.schemes()
