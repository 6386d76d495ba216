"""hamlie.System: a Hamiltonian system and every computation on it.

Formulas go in as strings in hamlie's language or as SymPy expressions, and
come back as SymPy expressions; trajectories come back as NumPy arrays.  All
the mathematics is done by the C library (libhamlie) through the extension
``_hamlie``; this module only converts.
"""
import math
import numbers

import sympy as sp

from . import _hamlie
from ._sympy import Reader, names_of, to_text
from .results import Check, Errors, Run


def _params_text(params):
    """{name: value} or "k=2,w=1/3" as hamlie's --param text."""
    if params is None or isinstance(params, str):
        return params
    if not isinstance(params, dict):
        raise TypeError(f"params must be a dict or a str, not {type(params).__name__}")
    items = []
    for name, value in params.items():
        name = name.name if isinstance(name, sp.Symbol) else name
        if not isinstance(name, str):
            raise TypeError(f"a parameter's name must be a str or a Symbol, not {name!r}")
        items.append(f"{name}={to_text(value, f'the value of {name}')}")
    return ",".join(items)


def _pairs_text(pairs):
    """"x:px,y:py", or [(x, px), ...] of names or Symbols."""
    if pairs is None or isinstance(pairs, str):
        return pairs
    out = []
    for pair in pairs:
        if len(pair) != 2:
            raise ValueError(f"a pair is (coordinate, momentum), not {pair!r}")
        out.append(":".join(p.name if isinstance(p, sp.Symbol) else str(p) for p in pair))
    return ",".join(out)


def _init_text(init):
    """{"q": 1.3, "p": 0} (names or Symbols; numbers, strings or SymPy) as "q=1.3,p=0"."""
    if isinstance(init, str):
        return init
    if not isinstance(init, dict):
        raise TypeError(f"init must be a dict or a str, not {type(init).__name__}")
    items = []
    for name, value in init.items():
        name = name.name if isinstance(name, sp.Symbol) else name
        if not isinstance(name, str):
            raise TypeError(f"init's keys are the variables' names, not {name!r}")
        if isinstance(value, numbers.Real) and not isinstance(value, bool) \
                and not math.isfinite(float(value)):
            raise ValueError(f"the initial value of {name} must be finite, not {value!r}")
        items.append(f"{name}={to_text(value, f'the initial value of {name}')}")
    return ",".join(items)


class System:
    """A Hamiltonian system: ``System("p^2/2 - cos(q)")`` or
    ``System(p**2/2 - sp.cos(q))``.

    params: values of parameters, ``{"k": 2}`` or ``"k=2"`` (others stay
    symbolic); pairs: ``"x:px"`` or ``[("x", "px")]`` (default: inferred from
    the names as the command line does); step: the step's name (``"D"``).
    """

    def __init__(self, H=None, params=None, pairs=None, step="D", extra=None):
        step = step.name if isinstance(step, sp.Symbol) else step
        extra = [to_text(f, "an extra formula") for f in (extra or [])]
        H_text = None if H is None else to_text(H, "H")
        self._c = _hamlie.System(H_text, _pairs_text(pairs), _params_text(params), step,
                                 extra or None)
        info = self._c.info()
        self._info = info
        names = info["coordinates"] + info["momenta"] + info["parameters"] + [info["step"]]
        self._read = Reader(names + list(info["parameter_values"]))
        sym = self._read.symbol
        self.coordinates = [sym(n) for n in info["coordinates"]]
        self.momenta = [sym(n) for n in info["momenta"]]
        self.parameters = [sym(n) for n in info["parameters"]]
        self.step = sym(info["step"])
        self.parameter_values = {sym(k): self._read(v)
                                 for k, v in info["parameter_values"].items()}
        self.H = self._read(info["H"])

    # ---- what it is -----------------------------------------------------------
    @property
    def ndof(self):
        return len(self.coordinates)

    @property
    def variables(self):
        """q_1..q_N, p_1..p_N as Symbols"""
        return self.coordinates + self.momenta

    def __repr__(self):
        return f"hamlie.System(H = {self.H})"

    def _repr_latex_(self):
        return f"$H = {sp.latex(self.H)}$"

    def _text(self, f, what="formula"):
        return to_text(f, what)

    # ---- §2 -----------------------------------------------------------------------
    def generator(self):
        """The evolution generator g = sum dH/dp d/dq - dH/dq d/dp as
        {variable: component}: {q: p, p: -sin(q)}."""
        comps = self._c.generator()
        return {v: self._read(c) for v, c in zip(self.variables, comps)}

    def bracket(self, f, g):
        """The Poisson bracket {f, g} ("H" names the Hamiltonian)."""
        return self._read(self._c.bracket(self._text(f, "f"), self._text(g, "g")))

    def check(self, integrals):
        """Integrals of motion {I, H} = 0, involution {I_i, I_j} = 0 and the
        rank of the Jacobian, as `hamlie check` computes them."""
        if isinstance(integrals, (str, sp.Basic)):
            integrals = [integrals]
        texts = [self._text(f, "an integral") for f in integrals]
        d = self._c.check(texts)
        return Check(d, [self._read(self._c.read(t)) for t in texts], self._read)

    def canonical(self, map):
        """Is a map "X = ...; P = ..." canonical for every value of the step?
        Returns (bool, the Matrix of brackets {Z_a, Z_b})."""
        ok, br = self._c.canonical(self._text(map, "map"))
        return ok, sp.Matrix([[self._read(c) for c in row] for row in br])

    def lie_terms(self, f, order):
        """[g^k f for k = 0..order]"""
        return [self._read(t) for t in self._c.lie_terms(self._text(f, "f"), int(order))]

    def lie_series(self, order=4, of=None):
        """exp(D g) applied to each phase variable (a dict) or to `of` (one
        expression), truncated after D^order: sum_k D^k/k! g^k."""
        def series(f):
            terms = self.lie_terms(f, order)
            return sp.Add(*[self.step ** k / sp.factorial(k) * t for k, t in enumerate(terms)])
        if of is not None:
            return series(of)
        return {v: series(v.name) for v in self.variables}

    # ---- §4 and runs ----------------------------------------------------------------
    def errors(self, scheme=None, order=4, map=None, equations=None, correct=0, invariants=2):
        """The error analysis of §4 (`hamlie errors`) of a catalog scheme, a
        map or equations: an :class:`Errors`."""
        d = self._c.errors(scheme=scheme, map=None if map is None else self._text(map, "map"),
                           equations=None if equations is None else
                           self._text(equations, "equations"),
                           order=int(order), correct=int(correct), invariants=int(invariants))
        return Errors(d, self)

    def run(self, scheme=None, dt=None, t=None, init=None, map=None, equations=None, tol=None,
            digits=None, every=1, observe=None, reference=True, order=4, ref_tol=1e-15):
        """A trajectory (`hamlie run`) as a :class:`Run` of NumPy arrays.

        scheme: a catalog name ("rk4", "lie6", "lie" with tol= for the
        adaptive Taylor integrator, "exact"), or map=/equations= for a user
        scheme; dt, t: the step and the final time (t/dt steps); init:
        {"q": 1.3, "p": 0}; digits: the adaptive integrator in Arb (values
        are mpmath numbers); observe: formulas evaluated along the run.
        """
        if t is None or init is None:
            raise TypeError("run needs t= and init=")
        t_text = None
        if isinstance(t, str):
            t_text, t = t, float(t)
        elif digits is not None:
            t_text = repr(float(t))
        observe = [self._text(f, "an observer") for f in (observe or [])]
        d = self._c.run(scheme=scheme, map=None if map is None else self._text(map, "map"),
                        equations=None if equations is None else self._text(equations, "equations"),
                        init=_init_text(init), t=t, dt=dt, order=int(order), every=int(every),
                        tol=tol, digits=digits, observe=observe, reference=bool(reference),
                        ref_tol=ref_tol, t_text=t_text)
        name = scheme if scheme is not None else ("map" if map is not None else "equations")
        return Run(d, self, name, observe, digits)
