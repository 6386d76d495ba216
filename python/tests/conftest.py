"""Shared by the binding's tests: the command line of the same build (its
--json is an independent reading of the same library through another
front end) and SymPy's own Poisson bracket and Lie series."""
import json
import os
import subprocess

import pytest
import sympy as sp

HERE = os.path.dirname(os.path.abspath(__file__))
CLI = os.environ.get("HAMLIE_CLI",
                     os.path.join(HERE, "..", "..", "build", "hamlie"))


def cli(*args, json_out=True):
    """`hamlie args... --json` of the build tree, parsed."""
    if not os.path.exists(CLI):
        pytest.skip(f"no hamlie command line at {CLI} (set HAMLIE_CLI)")
    cmd = [CLI, *args] + (["--json"] if json_out else [])
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode not in (0, 1):  # 1: a checked property does not hold
        raise AssertionError(f"{cmd} failed ({done.returncode}): {done.stderr}")
    out = done.stdout
    return json.loads(out) if json_out else out


def poisson(f, g, qs, ps):
    """SymPy's {f, g} = sum df/dq dg/dp - df/dp dg/dq"""
    return sum(sp.diff(f, q) * sp.diff(g, p) - sp.diff(f, p) * sp.diff(g, q)
               for q, p in zip(qs, ps))


def lie_series(f, H, qs, ps, D, order):
    """SymPy's exp(D g) f to D^order, g f = {f, H}"""
    term, total = f, f
    for k in range(1, order + 1):
        term = poisson(term, H, qs, ps)
        total += D ** k / sp.factorial(k) * term
    return total


def same(a, b):
    """a and b are the same expression (SymPy decides, not the strings)."""
    return sp.simplify(sp.expand(a - b)) == 0
