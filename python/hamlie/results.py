"""What hamlie's computations return: Check, Errors and Run.

Each keeps the library's raw answer (``.raw``: the dict with the keys of the
command line's ``--json``, formulas as strings) and offers it converted: SymPy
expressions keyed by the system's Symbols, NumPy arrays per variable.
"""
from functools import cached_property

import numpy as np
import sympy as sp


def _latex_field(field):
    """v as sum_i c_i d/dz_i in LaTeX"""
    terms = [f"\\left({sp.latex(c)}\\right) \\partial_{{{sp.latex(z)}}}"
             for z, c in field.items() if c != 0]
    return " + ".join(terms) if terms else "0"


class Check:
    """`hamlie check`: .integral[i] (bool), .bracket_with_H[i], .involution,
    .involution_brackets (Matrix), .rank, .rank_with_H."""

    def __init__(self, d, formulas, read):
        self.raw = d
        self.formulas = formulas  # as SymPy expressions
        self.integral = list(d["integral"])
        self.bracket_with_H = [read(s) for s in d["bracket_with_H"]]
        self.involution = d["involution"]
        self.involution_brackets = sp.Matrix([[read(s) for s in row]
                                              for row in d["involution_brackets"]])
        self.rank = d["rank"]
        self.rank_with_H = d["rank_with_H"]

    @property
    def all_integrals(self):
        return all(self.integral)

    def __repr__(self):
        return (f"Check(integral={self.integral}, involution={self.involution}, "
                f"rank={self.rank}, rank_with_H={self.rank_with_H})")

    def _repr_latex_(self):
        rows = [f"\\{{{sp.latex(f)}, H\\}} = {sp.latex(b)}"
                f"\\quad \\text{{{'integral' if ok else 'not an integral'}}}"
                for f, b, ok in zip(self.formulas, self.bracket_with_H, self.integral)]
        rows.append(f"\\text{{involution: {'yes' if self.involution else 'no'}; "
                    f"rank {self.rank}, with }} H \\text{{: {self.rank_with_H}}}")
        return "$\\begin{aligned}" + " \\\\ ".join("& " + r for r in rows) + \
            "\\end{aligned}$"


class Errors:
    """The error analysis of §4 (`hamlie errors`).

    .v[k]: the field v_k as {variable: component} (k = 2..order_computed;
    v[0], v[1] are None); .order; .leading (k of the first v_k != 0);
    .leading_kind ("time_shift", "hamiltonian", ...); .leading_lambda,
    .leading_h; .two_ways_agree; .expansion {variable: psi(D)}; .map (explicit
    schemes); .K (closed form) and .K_coefficients; .modified_fields,
    .modified_hamiltonians [h_1 = H, h_2, ...] and .modified_hamiltonian
    = sum_j D^(j-1) h_j; .tau (the series tau(D)), .W, .tau_closed,
    .tan_half_tau, .double_step; .invariants; .corrected; .raw (the dict).

    The formulas are parsed by SymPy when first asked for (SymPy's parser
    costs more than the analysis itself for large results), then kept.
    """

    def __init__(self, d, system):
        self.raw = d
        self.system = system
        self._read = system._read
        self.scheme = d["scheme"]
        self.order_computed = d["order_computed"]
        self.order = d["order"]
        self.two_ways_agree = d["two_ways_agree"]
        self.exact_to_order_computed = d["exact_to_order_computed"]
        lead = d["leading"] or {}
        self.leading = lead.get("k")
        self.leading_kind = lead.get("kind")
        self.leading_hamiltonian = lead.get("hamiltonian")
        self.explicit = d["explicit"]
        time = d["time"] or {}
        self.pure_time_translation = time.get("pure_time_translation")
        self.numeric_zero_test = d["numeric_zero_test"]

    # ---- formulas, converted on first use -------------------------------------
    @cached_property
    def v(self):
        return [None, None] + [self._read.field(f) for f in self.raw["fields"]]

    @cached_property
    def leading_lambda(self):
        return self._read((self.raw["leading"] or {}).get("lambda"))

    @cached_property
    def leading_h(self):
        return self._read((self.raw["leading"] or {}).get("h"))

    @cached_property
    def expansion(self):
        return {self._read.symbol(k): self._read(s) for k, s in self.raw["expansion"].items()}

    @cached_property
    def map(self):
        return self._read.field(self.raw["map"])

    @cached_property
    def K(self):
        return self._read.field(self.raw["K"])

    @cached_property
    def K_coefficients(self):
        ks = self.raw["K_coefficients"]
        return None if ks is None else [self._read.field(f) for f in ks]

    @cached_property
    def modified_fields(self):
        return [None] + [self._read.field(f) for f in self.raw["modified"]["fields"]]

    @cached_property
    def modified_hamiltonians(self):
        hs = self.raw["modified"]["hamiltonians"]
        return None if hs is None else [self._read(h) for h in hs]

    @cached_property
    def modified_hamiltonian(self):
        hs = self.modified_hamiltonians
        D = self.system.step
        return None if hs is None else sp.Add(*[D ** j * h for j, h in enumerate(hs)])

    def _time(self, key):
        return self._read((self.raw["time"] or {}).get(key))

    @cached_property
    def tau(self):
        return self._time("tau_series")

    @cached_property
    def W(self):
        return self._time("W_series")

    @cached_property
    def tau_closed(self):
        return self._time("tau")

    @cached_property
    def tan_half_tau(self):
        return self._time("tan_half_tau")

    @cached_property
    def double_step(self):
        return self._time("double_step")

    @cached_property
    def invariants(self):
        inv, read = self.raw["invariants"], self._read
        return None if inv is None else {
            "degree": inv["degree"],
            "polynomial": [read(s) for s in inv["polynomial"]],
            "rational": None if inv["rational"] is None else [read(s) for s in inv["rational"]]}

    @cached_property
    def corrected(self):
        c, read = self.raw["corrected"], self._read
        return None if c is None else {
            "subtracted_up_to": c["subtracted_up_to"], "map": read.field(c.get("map")),
            "v": [None, None] + [read.field(f) for f in c["fields"]], "order": c["order"],
            "leading_kind": (c["leading"] or {}).get("kind")}

    def __repr__(self):
        return (f"Errors({self.scheme}: order {self.order}, leading v_{self.leading} "
                f"{self.leading_kind})")

    def _repr_latex_(self):
        D = sp.latex(self.system.step)
        n = self.order_computed
        lines = [f"\\text{{{self.scheme}: order {self.order}}}"]
        for k in range(2, n + 1):
            lines.append(f"v_{{{k}}} = {_latex_field(self.v[k])}")
        if self.leading_kind:
            lines.append(f"\\text{{leading: }} v_{{{self.leading}}}\\ "
                         f"\\text{{({self.leading_kind.replace('_', ' ')})}}")
        if self.tau is not None:
            lines.append(f"\\tau({D}) = {sp.latex(self.tau)} + O({D}^{{{n + 1}}})")
        if self.modified_hamiltonian is not None:
            lines.append(f"\\tilde H = {sp.latex(self.modified_hamiltonian)}")
        return "$\\begin{aligned}" + " \\\\ ".join("& " + s for s in lines) + \
            "\\end{aligned}$"


class Run:
    """A trajectory: .t, one array per phase variable (.q, .p or .x, .px:
    also r["q"]), .z (rows x 2N), .H, .sigma (squared distance to the exact
    flow; NaN without a reference), .observers (rows x k) and .summary
    (steps, max_dH, final sigma, ...).  With digits=, the values are mpmath
    numbers in object arrays."""

    def __init__(self, d, system, scheme, observe, digits):
        self.system = system
        self.scheme = scheme
        self.observe = observe
        self.summary = d["summary"]
        names = [v.name for v in system.variables]
        n2 = len(names)
        if digits is None:
            self.t, self.z, self.H = d["t"], d["z"], d["H"]
            self.sigma, self.observers = d["sigma"], d["observers"]
        else:
            import mpmath
            dps = int(np.ceil(digits)) + 5
            def mpf(s):
                with mpmath.workdps(dps):
                    return mpmath.mpf(0) if s.startswith("[") else mpmath.mpf(s)
            rows = np.array([[mpf(s) for s in row] for row in d["rows_text"]], dtype=object)
            rows = rows.reshape(len(d["rows_text"]), 2 + n2 + len(observe))
            self.t, self.z, self.H = rows[:, 0], rows[:, 1:1 + n2], rows[:, 1 + n2]
            self.observers = rows[:, 2 + n2:]
            self.sigma = None
        self._columns = {name: self.z[:, i] for i, name in enumerate(names)}

    def __getattr__(self, name):
        cols = self.__dict__.get("_columns", {})
        if name in cols:
            return cols[name]
        raise AttributeError(name)

    def __getitem__(self, name):
        name = name.name if isinstance(name, sp.Symbol) else name
        if name in self._columns:
            return self._columns[name]
        if name in self.observe:
            return self.observers[:, self.observe.index(name)]
        raise KeyError(name)

    def __len__(self):
        return len(self.t)

    def __repr__(self):
        s = self.summary
        return (f"Run({self.scheme}: {s['steps']} steps to t = {s['t']:g}, "
                f"max |H - H0| = {s['max_dH']:.3g}, rows = {len(self)})")

    def _repr_latex_(self):
        s = self.summary
        txt = (f"\\text{{{self.scheme}: {s['steps']} steps to }} t = {s['t']:g},\\ "
               f"\\max|H - H_0| = {sp.latex(sp.Float(s['max_dH'], 3))}")
        sig = s.get("sigma")
        if sig is not None and np.isfinite(sig):
            txt += f",\\ \\sigma(t) = {sp.latex(sp.Float(sig, 3))}"
        return f"${txt}$"

    def plot(self, what=("phase", "energy", "sigma"), ax=None):
        """The figures of `hamlie plot` with matplotlib: the phase portrait of
        the first pair, the energy error and sigma against t.  Returns the
        matplotlib Figure."""
        import matplotlib.pyplot as plt
        what = [w for w in what if not (w == "sigma" and self.sigma is None)]
        fig, axes = plt.subplots(1, len(what), figsize=(4.5 * len(what), 4), squeeze=False)
        q, p = self.system.coordinates[0].name, self.system.momenta[0].name
        t = np.asarray(self.t, dtype=float)
        for ax_, w in zip(axes[0], what):
            if w == "phase":
                ax_.plot(np.asarray(self[q], dtype=float), np.asarray(self[p], dtype=float),
                         lw=0.8)
                ax_.set_xlabel(q), ax_.set_ylabel(p), ax_.set_title("phase portrait")
            elif w == "energy":
                H = np.asarray(self.H, dtype=float)
                ax_.plot(t, H - H[0], lw=0.8)
                ax_.set_xlabel("t"), ax_.set_title("H - H0")
            elif w == "sigma":
                ax_.semilogy(t[1:], np.asarray(self.sigma, dtype=float)[1:], lw=0.8)
                ax_.set_xlabel("t"), ax_.set_title("sigma = |z - z(t)|^2")
        fig.suptitle(self.scheme)
        fig.tight_layout()
        return fig
