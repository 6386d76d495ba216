"""Formulas across the boundary: SymPy expressions to hamlie's text and back.

hamlie's library reads its own formula language (``^`` or ``**``, the
functions below, ``pi``) and writes results in a style ``sympy.sympify``
reads (``HL_STYLE_SYMPY``).  Going in, a SymPy expression is printed by
:class:`HamliePrinter`, which refuses what hamlie's language has no word for
(``Abs``, ``I``, ``erf``, ...) instead of sending text that would mean
something else.  Coming out, a string is parsed with every name of the system
bound to a plain ``Symbol`` (no assumptions), so the user's own
``sympy.symbols("q p")`` compare equal to what comes back, and names SymPy
would read as its own objects (``E``, ``I``, ``S``, ``N``, ``beta``,
``gamma``...) stay symbols.
"""
import math
import numbers

import sympy as sp
from sympy.parsing.sympy_parser import parse_expr
from sympy.printing.str import StrPrinter

# SymPy function classes hamlie's language has, by hamlie's name.
_FUNCTIONS = {
    sp.sin: "sin", sp.cos: "cos", sp.tan: "tan", sp.sinh: "sinh", sp.cosh: "cosh",
    sp.tanh: "tanh", sp.exp: "exp", sp.log: "log", sp.atan: "atan", sp.asin: "asin",
    sp.acos: "acos", sp.asinh: "asinh", sp.atan2: "atan2",
}


class HamliePrinter(StrPrinter):
    """str() of SymPy with the corners hamlie's parser reads differently."""

    def _print_Function(self, expr):
        name = _FUNCTIONS.get(type(expr))
        if name is None:
            raise ValueError(f"hamlie has no function {type(expr).__name__!s} "
                             f"(in {expr}); it knows {', '.join(sorted(_FUNCTIONS.values()))}, "
                             f"sqrt and powers")
        return f"{name}({', '.join(self._print(a) for a in expr.args)})"

    def _print_Exp1(self, expr):
        return "exp(1)"

    def _print_Pi(self, expr):
        return "pi"

    def _print_Float(self, expr):
        # the shortest decimal that reads back as the same double
        return repr(float(expr))

    def _print_ImaginaryUnit(self, expr):
        raise ValueError("hamlie works over the reals: the formula has I")

    def _print_Infinity(self, expr):
        raise ValueError("a formula cannot be infinite (oo)")

    _print_NegativeInfinity = _print_Infinity
    _print_ComplexInfinity = _print_Infinity

    def _print_NaN(self, expr):
        raise ValueError("a formula cannot be NaN")

    def _print_Relational(self, expr):
        return f"{self._print(expr.lhs)} = {self._print(expr.rhs)}"

    def _print_Symbol(self, expr):
        return expr.name

    def emptyPrinter(self, expr):
        raise ValueError(f"hamlie cannot read {type(expr).__name__} ({expr!s})")


_printer = HamliePrinter({"order": "none"})


def to_text(x, what="formula"):
    """A formula as hamlie's text: str as given, SymPy printed, numbers exact."""
    if isinstance(x, str):
        return x
    if isinstance(x, bool):
        raise TypeError(f"{what} must be a formula (str or SymPy expression), not bool")
    if isinstance(x, sp.Basic):
        if isinstance(x, sp.Equality):
            return f"{_printer.doprint(x.lhs)} = {_printer.doprint(x.rhs)}"
        return _printer.doprint(x)
    if isinstance(x, numbers.Integral):
        return str(int(x))
    if isinstance(x, numbers.Rational):  # fractions.Fraction: exact
        return f"({x.numerator})/({x.denominator})"
    if isinstance(x, numbers.Real):
        v = float(x)
        if not math.isfinite(v):
            raise ValueError(f"{what} must be finite, not {v!r}")
        return repr(v)
    raise TypeError(f"{what} must be a formula (str or SymPy expression), "
                    f"not {type(x).__name__}")


def names_of(x):
    """The symbol names a formula uses (for hamlie's variable inference)."""
    if isinstance(x, sp.Basic):
        return sorted(s.name for s in x.free_symbols)
    return []


class Reader:
    """Parses hamlie's SymPy-style output with the system's names bound."""

    def __init__(self, names):
        self.symbols = {n: sp.Symbol(n) for n in names}
        self._local = dict(self.symbols)

    def __call__(self, text):
        if text is None:
            return None
        return parse_expr(text, local_dict=self._local, evaluate=True)

    def symbol(self, name):
        s = self.symbols.get(name)
        if s is None:
            s = self.symbols[name] = self._local[name] = sp.Symbol(name)
        return s

    def field(self, d):
        """{name: text} as {Symbol: expression}"""
        if d is None:
            return None
        return {self.symbol(k): self(v) for k, v in d.items()}
