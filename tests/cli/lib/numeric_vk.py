# The numeric error fields of `errors --numeric --at` against the symbolic
# ones of `errors --json` evaluated by SymPy at the same point (one degree of
# freedom, q and p).  usage: python3 numeric_vk.py SYMBOLIC.json NUMERIC.json
import json, sys, sympy
sym, num = (json.load(open(f)) for f in sys.argv[1:3])
q, p = sympy.symbols("q p")
pt = {q: num["at"]["q"], p: num["at"]["p"]}
for fs, fn in zip(sym["fields"], num["fields"]):
    assert fs["k"] == fn["k"]
    for v in ("q", "p"):
        want = float(sympy.sympify(fs["v"][v], locals={"q": q, "p": p}).subs(pt))
        got = fn["v"][v]
        assert abs(got - want) < 1e-9 * (1 + abs(want)), (fs["k"], v, got, want)
print("ok")
