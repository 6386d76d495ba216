"""errors(): the v_k, order, kind, K, tau, modified Hamiltonian against the
expansion SymPy computes here from the scheme's formulas, closed forms for
the oscillator (the paper's study) and the command line's JSON."""
import pytest
import sympy as sp

import hamlie
from conftest import cli, poisson, same

q, p, x, D = sp.symbols("q p x D")


def g_powers(z, H, qs, ps, n):
    """[g^k z for k = 0..n]"""
    out = [z]
    for _ in range(n):
        out.append(poisson(out[-1], H, qs, ps))
    return out


def v_fields(images, H, qs, ps, n):
    """v_k(z) = k! ([D^k] psi(z) - g^k z / k!) from a map's images (SymPy)"""
    v = {}
    for z, img in zip(qs + ps, images):
        ser = sp.series(img, D, 0, n + 1).removeO()
        g = g_powers(z, H, qs, ps, n)
        for k in range(2, n + 1):
            v.setdefault(k, {})[z] = sp.factorial(k) * (ser.coeff(D, k) - g[k] / sp.factorial(k))
    return v


def test_stormer_verlet_on_pendulum():
    s = hamlie.System("p^2/2 - cos(q)")
    n = 5
    e = s.errors("stormer-verlet-kdk", order=n)
    ph = p - D / 2 * sp.sin(q)
    Q = q + D * ph
    P = ph - D / 2 * sp.sin(Q)
    v = v_fields([Q, P], s.H, [q], [p], n)
    for k in range(2, n + 1):
        for z in (q, p):
            assert same(e.v[k][z], v[k][z]), (k, z)
    assert e.order == 2 and e.leading == 3 and e.leading_kind == "hamiltonian"
    assert e.two_ways_agree is True
    assert same(e.map[q], Q) and same(e.map[p], P)
    # the leading field is J grad h: v(q) = dh/dp, v(p) = -dh/dq
    assert same(e.v[3][q], sp.diff(e.leading_h, p))
    assert same(e.v[3][p], -sp.diff(e.leading_h, q))


def test_euler_on_oscillator_closed_forms():
    """The paper's oscillator: explicit Euler is z -> (I + D J) z, so
    v_k = -g^k z for every k >= 2, and K(D) = (p + D x, -x + D p)
    divided by nothing: K = d/dD psi at psi_{-D}."""
    s = hamlie.System("(p^2+x^2)/2")
    n = 6
    e = s.errors("euler", order=n)
    for k in range(2, n + 1):
        g = g_powers(x, s.H, [x], [p], k)[k], g_powers(p, s.H, [x], [p], k)[k]
        assert same(e.v[k][x], -g[0]) and same(e.v[k][p], -g[1])
    assert e.order == 1 and e.leading == 2 and e.leading_kind == "scaling"
    # psi_{-D}(z) = (x - D p, p + D x); d psi/dD = (p, -x) there
    assert same(e.K[x], p + D * x) and same(e.K[p], -x + D * p)


def test_implicit_midpoint_time_reparametrisation():
    """Implicit midpoint on the oscillator is the rotation by
    tau = 2 atan(D/2) (the paper's §4 part 4)."""
    s = hamlie.System("(p^2+x^2)/2")
    n = 7
    e = s.errors("implicit-midpoint", order=n)
    assert e.leading_kind == "time_shift" and e.pure_time_translation
    tau = sp.series(2 * sp.atan(D / 2), D, 0, n + 2).removeO()
    assert same(e.tau, tau)
    assert same(e.W, tau - D)
    assert same(e.tau_closed, 2 * sp.atan(D / 2))
    assert same(e.tan_half_tau, D / 2)
    assert same(e.double_step, 2 * D / (1 - D ** 2 / 4))


def test_against_cli_json():
    H, scheme = "p^2/2 - cos(q)", "stormer-verlet-kdk"
    e = hamlie.System(H).errors(scheme, order=5)
    j = cli("errors", "-H", H, "--scheme", scheme, "--order", "5")
    for f in j["fields"]:
        for name, comp in f["v"].items():
            assert same(e.v[f["k"]][sp.Symbol(name)], sp.sympify(comp))
    assert e.order == j["order"] and e.leading_kind == j["leading"]["kind"]
    theirs = j["modified"]["hamiltonians"]
    assert len(e.modified_hamiltonians) == len(theirs)
    for mine, t in zip(e.modified_hamiltonians, theirs):
        assert same(mine, sp.sympify(t))
    for mine, t in zip(e.K_coefficients, j["K_coefficients"]):
        for name, comp in t.items():
            assert same(mine[sp.Symbol(name)], sp.sympify(comp))


def test_modified_hamiltonian_symplectic_euler_oscillator():
    """The modified Hamiltonian of symplectic Euler to order 4 (terms to
    D^3) is conserved by the map itself up to O(D^5): computed here by
    SymPy from the map, not from hamlie's fields."""
    s = hamlie.System("(p^2+x^2)/2")
    e = s.errors(map="X = x + D*p; P = p - D*X", order=4)
    Ht = e.modified_hamiltonian
    assert same(Ht.subs(D, 0), s.H)
    X = x + D * p
    P = p - D * X
    drift = sp.series(Ht.subs({x: X, p: P}, simultaneous=True) - Ht, D, 0, 5).removeO()
    assert same(drift, 0)


def test_user_equations_and_correct():
    s = hamlie.System("(p^2+x^2)/2")
    e = s.errors(equations="(X-x)/D = (P+p)/2; (P-p)/D = -(X+x)/2", order=5, correct=3)
    assert e.order == 2
    assert e.corrected is not None and e.corrected["order"] >= 3


def test_repr_latex():
    e = hamlie.System("(p^2+x^2)/2").errors("implicit-midpoint", order=4)
    tex = e._repr_latex_()
    assert tex.startswith("$") and "v_{3}" in tex and "\\tau" in tex


@pytest.mark.parametrize("kw,exc", [
    (dict(scheme="no-such-scheme"), hamlie.Error),
    (dict(scheme="rk4", order=1), ValueError),
    (dict(scheme="rk4", order=99), ValueError),
    (dict(scheme=3), TypeError),
    (dict(), TypeError),
    (dict(scheme="rk4", map="X = x"), TypeError),
    (dict(map="X = x + D*; P = p"), hamlie.Error),
])
def test_bad_input(kw, exc):
    s = hamlie.System("(p^2+x^2)/2")
    with pytest.raises(exc):
        s.errors(**kw)


def test_unknown_scheme_is_value_error_with_catalog():
    with pytest.raises(ValueError, match="unknown scheme 'nope'.*rk4"):
        hamlie.System("(p^2+x^2)/2").errors("nope")


def test_formula_error_has_position():
    with pytest.raises(hamlie.Error) as info:
        hamlie.System("(p^2+x^2)/2").errors(map="X = x + D*; P = p - D*x")
    assert info.value.position is not None
    assert info.value.source == "X = x + D*; P = p - D*x"
    assert info.value.source[info.value.position - 1] in "*;"
