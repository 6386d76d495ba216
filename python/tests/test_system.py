"""System, generator, bracket, check, canonical, lie_series, schemes:
against SymPy computed here and the command line's JSON."""
import pytest
import sympy as sp

import hamlie
from conftest import cli, lie_series, poisson, same

q, p, x, px, y, py, D, k = sp.symbols("q p x px y py D k")

SYSTEMS = [
    ("p^2/2 - cos(q)", [q], [p]),
    ("(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", [x, y], [px, py]),
    ("p^2/2 + q^4/4 - q^2/2", [q], [p]),
]


@pytest.mark.parametrize("H_text,qs,ps", SYSTEMS)
def test_generator_is_dH(H_text, qs, ps):
    s = hamlie.System(H_text)
    H = sp.sympify(H_text.replace("^", "**"), locals={str(v): v for v in qs + ps})
    assert s.coordinates == qs and s.momenta == ps
    assert same(s.H, H)
    g = s.generator()
    for qj, pj in zip(qs, ps):
        assert same(g[qj], sp.diff(H, pj))
        assert same(g[pj], -sp.diff(H, qj))


def test_generator_matches_cli():
    H = "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3"
    g = hamlie.System(H).generator()
    j = cli("generator", "-H", H)
    for name, comp in j["generator"].items():
        assert same(g[sp.Symbol(name)], sp.sympify(comp))


def test_sympy_in_and_out():
    H = p ** 2 / 2 - sp.cos(q)
    s = hamlie.System(H)
    assert same(s.H, H)
    assert s.generator() == {q: p, p: -sp.sin(q)}
    # what the printer must get right: powers, roots, rationals, E, pi, floats
    for expr in [p ** 2 / 2 + q ** sp.Rational(3, 2), p ** 2 / 2 + 1 / sp.sqrt(1 + q ** 2),
                 p ** 2 / 2 - sp.exp(q) * sp.E + sp.pi * q, p ** 2 / 2 + sp.Float(0.25) * q ** 2,
                 sp.Rational(1, 3) * p ** 2 + sp.atan(q) + sp.log(1 + q ** 2)]:
        assert same(hamlie.System(expr).H, expr), expr


def test_parameters():
    s = hamlie.System("p^2/2 + k*q^2/2", params={"k": sp.Rational(1, 3)})
    assert same(s.H, p ** 2 / 2 + q ** 2 / 6)
    s2 = hamlie.System("p^2/2 + k*q^2/2")
    assert s2.parameters == [k]
    assert same(s2.generator()[p], -k * q)
    assert hamlie.System("p^2/2 + k*q^2/2", params="k=2").parameter_values == {k: 2}


@pytest.mark.parametrize("f,g", [("p*cos(q)", "H"), ("q^3*p", "sin(q)*p^2"), ("q", "p")])
def test_bracket_against_sympy(f, g):
    s = hamlie.System("p^2/2 - cos(q)")
    H = s.H
    loc = {"q": q, "p": p, "H": H}
    F, G = (sp.sympify(t.replace("^", "**"), locals=loc) for t in (f, g))
    assert same(s.bracket(f, g), poisson(F, G, [q], [p]))
    assert same(s.bracket(F, G), poisson(F, G, [q], [p]))  # SymPy in


def test_check_kepler_integrals():
    s = hamlie.System("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)")
    L = x * py - y * px
    c = s.check([L, "H", "x*px"])
    assert c.integral == [True, True, False]
    assert same(c.bracket_with_H[2], poisson(x * px, s.H, [x, y], [px, py]))
    assert c.involution is False
    assert same(c.involution_brackets[0, 1], 0)
    assert same(c.involution_brackets[0, 2], poisson(L, x * px, [x, y], [px, py]))
    assert c.rank == 3 and c.rank_with_H == 3
    assert c._repr_latex_().count("not an integral") == 1
    j = cli("check", "-H", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", "--integral", "x*py - y*px",
            "--integral", "H", "--integral", "x*px")
    assert [i["is_integral"] for i in j["integrals"]] == c.integral
    for mine, theirs in zip(c.bracket_with_H, j["integrals"]):
        assert same(mine, sp.sympify(theirs["bracket_with_H"]))
    for b in j["involution"]["brackets"]:
        assert same(c.involution_brackets[b["i"] - 1, b["j"] - 1], sp.sympify(b["value"]))


def test_canonical():
    s = hamlie.System("(p^2+x^2)/2")
    ok, br = s.canonical("X = x + D*p; P = p - D*(x + D*p)")
    assert ok and br == sp.Matrix([[0, 1], [-1, 0]])
    ok, br = s.canonical("X = x + D*p; P = p - D*x")
    assert not ok and same(br[0, 1], 1 + D ** 2)


@pytest.mark.parametrize("H_text,qs,ps", SYSTEMS[:2])
def test_lie_series_against_sympy(H_text, qs, ps):
    s = hamlie.System(H_text)
    order = 5
    series = s.lie_series(order=order)
    for z in qs + ps:
        assert same(series[z], lie_series(z, s.H, qs, ps, D, order)), z
    f = qs[0] * ps[0]
    assert same(s.lie_series(order=3, of=f), lie_series(f, s.H, qs, ps, D, 3))


def test_lie_series_matches_cli():
    j = cli("lie", "-H", "p^2/2 - cos(q)", "--order", "6")
    series = hamlie.System("p^2/2 - cos(q)").lie_series(order=6)
    for item in j["series"]:
        z = sp.Symbol(item["input"])
        assert same(series[z], sp.sympify(item["series"]))


def test_schemes_match_cli():
    mine = hamlie.schemes()
    theirs = cli("schemes")["schemes"]
    assert [r["name"] for r in mine] == [r["name"] for r in theirs]
    for a, b in zip(mine, theirs):
        assert {key: a[key] for key in b} == b
    assert {r["name"] for r in mine} >= {"euler", "rk4", "stormer-verlet-kdk", "lieN"}


def test_step_renamed():
    h = sp.Symbol("h")
    s = hamlie.System("p^2/2 + q^2/2", step="h")
    assert s.step == h
    assert same(s.lie_series(order=2)[q], q + h * p - h ** 2 / 2 * q)


def test_names_sympy_would_take_stay_symbols():
    E, beta = sp.Symbol("E"), sp.Symbol("beta")
    s = hamlie.System("p^2/2 + E*q^2/2 + beta*q^4")
    assert s.parameters == [E, beta]
    assert same(s.generator()[p], -E * q - 4 * beta * q ** 3)


def test_pairs_as_list():
    s = hamlie.System("px^2/2 + x^2/2", pairs=[("x", "px")])
    assert s.variables == [x, px]


@pytest.mark.parametrize("H,exc", [
    ("p^2/2 - cos(q", hamlie.Error), (["p"], TypeError), (sp.Abs(q) + p ** 2, ValueError),
    (sp.I * q + p ** 2, ValueError), ("p^2/2 + q\0", ValueError), (float("nan"), ValueError),
])
def test_bad_systems(H, exc):
    with pytest.raises(exc):
        hamlie.System(H)


def test_bad_formula_types():
    s = hamlie.System("p^2/2 - cos(q)")
    with pytest.raises(TypeError):
        s.bracket(1.5j, "p")
    with pytest.raises(TypeError):
        s.check([None])
    with pytest.raises(hamlie.Error) as info:
        s.bracket("q*D", "p")  # the step is not a function of the phase variables
    assert info.value.position == 2
