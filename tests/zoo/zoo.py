"""The zoo: Hamiltonians of 1 to 3 degrees of freedom, each with the same H
written a second way, its parameters, the points where defects hide, and a
box from which random initial points are drawn.

Each entry:
  name     a short identifier (used in the known-defect table)
  H        the Hamiltonian as a user types it
  H2       the same function written another way (terms permuted, factors
           reordered, squares expanded): every number must be the same
  params   {name: value} given with --param
  pairs    --pairs, when the names do not say it
  q, p     the coordinate and momentum names, in pair order
  special  [(label, {var: value})]: equilibria, turning points (p = 0),
           symmetric points, tiny amplitudes, near separatrices, p < 0
  box      (lo, hi) per phase variable for random points (same for all)
  t        the time horizon of the trajectory checks
  tags     'quadratic' (linear flow: the truth is exp(tA)), 'separable'
           (T(p) + V(q)), 'even_p' (H(q,-p) = H(q,p): the 1-dof exact flow
           by quadrature applies), 'closed' (a closed-form solution in
           truth.py)
"""

SQ3 = "sqrt(3)"


def sys_(name, H, H2, q, p, special, box, t=2.0, params=None, pairs=None,
         tags=(), sampler=None, lie_order=4):
    entry = dict(name=name, H=H, H2=H2, q=list(q), p=list(p),
                 special=special, box=box, t=t, params=params or {},
                 pairs=pairs, tags=set(tags), lie_order=lie_order)
    if sampler:
        entry["sampler"] = sampler
    return entry


def pt(**kv):
    return kv


def kepler_point(q, p):
    """A bound orbit of eccentricity below about 0.5 (so that steps of 0.2
    stay far from the singularity), in any direction and quadrant."""
    def draw(rng):
        pos = [rng.gauss(0, 1) for _ in q]
        r = sum(c * c for c in pos) ** 0.5
        radius = rng.uniform(0.8, 1.2)
        pos = [c * radius / r for c in pos]
        # a velocity perpendicular to pos: Gram-Schmidt on a random vector
        v = [rng.gauss(0, 1) for _ in q]
        along = sum(a * b for a, b in zip(v, pos)) / radius ** 2
        v = [a - along * b for a, b in zip(v, pos)]
        vn = sum(c * c for c in v) ** 0.5
        speed = rng.uniform(0.85, 1.1) / radius ** 0.5
        radial = rng.uniform(-0.15, 0.15)
        vel = [speed * a / vn + radial * b / radius for a, b in zip(v, pos)]
        return dict(zip(q + p, pos + vel))
    return draw


ZOO = [
    # ---- polynomial, 1 dof ---------------------------------------------
    sys_("harmonic", "(p^2+x^2)/2", "x^2/2 + p*p/2", "x", "p",
         [("equilibrium", pt(x=0, p=0)), ("turning", pt(x=1, p=0)),
          ("p<0", pt(x=0, p=-1)), ("tiny-1e-8", pt(x=1e-8, p=0))],
         (-2, 2), t=4, tags={"quadratic", "separable", "even_p"}),
    sys_("harmonic-w", "p^2/2 + w^2*q^2/2", "(w*q)^2/2 + p^2/2", "q", "p",
         [("turning", pt(q=0.7, p=0)), ("p<0", pt(q=-0.3, p=-0.5))],
         (-1, 1), t=4, params={"w": 1.5},
         tags={"quadratic", "separable", "even_p"}),
    sys_("inverted", "p^2/2 - q^2/2", "-(q^2 - p^2)/2", "q", "p",
         [("equilibrium", pt(q=0, p=0)), ("stable-manifold", pt(q=1, p=-1)),
          ("turning", pt(q=0.5, p=0))],
         (-1, 1), t=2, tags={"quadratic", "separable", "even_p"}),
    sys_("field", "p^2/2 + g*q", "q*g + p^2/2", "q", "p",
         [("turning", pt(q=0, p=0)), ("p<0", pt(q=1, p=-2))],
         (-2, 2), t=2, params={"g": 9.81},
         tags={"quadratic", "separable", "even_p"}),
    sys_("quartic", "p^2/2 + q^4/4", "q^4/4 + p^2/2", "q", "p",
         [("equilibrium", pt(q=0, p=0)), ("bottom", pt(q=0, p=1)),
          ("turning", pt(q=1, p=0)), ("p<0", pt(q=0, p=-1)),
          ("tiny-1e-6", pt(q=1e-6, p=0))],
         (-1.5, 1.5), t=10, tags={"separable", "even_p"}),
    sys_("sextic", "p^2/2 + q^6/6", "q^6/6 + p^2/2", "q", "p",
         [("bottom", pt(q=0, p=1)), ("turning", pt(q=1, p=0)),
          ("p<0", pt(q=-0.5, p=-0.5))],
         (-1.2, 1.2), t=10, tags={"separable", "even_p"}),
    sys_("double-well", "p^2/2 + q^4/4 - q^2/2", "(q^2-1)^2/4 + p^2/2 - 1/4",
         "q", "p",
         [("saddle", pt(q=0, p=0)), ("equilibrium-well", pt(q=1, p=0)),
          ("near-separatrix", pt(q=1e-6, p=0)),
          ("inside-well", pt(q=1, p=0.5)), ("p<0", pt(q=-1.2, p=-0.3))],
         (-1.5, 1.5), t=4, tags={"separable", "even_p"}),
    sys_("duffing", "p^2/2 + a*q^2/2 + b*q^4/4", "b*q^4/4 + p^2/2 + q^2*a/2",
         "q", "p",
         [("turning", pt(q=1, p=0)), ("bottom", pt(q=0, p=1)),
          ("tiny-1e-8", pt(q=1e-8, p=0))],
         (-1.5, 1.5), t=4, params={"a": 1, "b": 0.5},
         tags={"separable", "even_p"}),
    sys_("nonlinear-osc", "(p^2+q^2)^2/4",
         "q^4/4 + p^2*q^2/2 + p^4/4", "q", "p",
         [("equilibrium", pt(q=0, p=0)), ("turning", pt(q=1, p=0)),
          ("p<0", pt(q=-0.6, p=-0.8)), ("tiny-1e-6", pt(q=1e-6, p=0))],
         (-1.2, 1.2), t=3, tags={"even_p", "closed"}),
    sys_("position-mass", "p^2*(1+q^2)/2 + q^2/2",
         "q^2/2 + (p^2 + p^2*q^2)/2", "q", "p",
         [("equilibrium", pt(q=0, p=0)), ("turning", pt(q=1, p=0)),
          ("p<0", pt(q=0.4, p=-0.9))],
         (-1, 1), t=3, tags={"even_p"}),
    # ---- trigonometric, exponential, radical, rational: 1 dof -------------
    sys_("pendulum", "p^2/2 - cos(q)", "-cos(q) + p^2/2", "q", "p",
         [("bottom", pt(q=0, p=1.8)), ("equilibrium", pt(q=0, p=0)),
          ("tiny-1e-8", pt(q=1e-8, p=0)), ("tiny-1e-6", pt(q=1e-6, p=0)),
          ("near-separatrix", pt(q=3.14, p=0)),
          ("near-separatrix-p", pt(q=0, p=1.99)),
          ("rotation", pt(q=0, p=2.5)), ("p<0", pt(q=-1, p=-0.5)),
          ("turning", pt(q=1.3, p=0))],
         (-2.5, 2.5), t=4, tags={"separable", "even_p", "closed"}),
    sys_("pendulum-params", "p^2/(2*m*l^2) - m*gr*l*cos(q)",
         "-l*gr*m*cos(q) + p^2/(2*l^2*m)", "q", "p",
         [("turning", pt(q=1, p=0)), ("p<0", pt(q=0.2, p=-1))],
         (-1.5, 1.5), t=3, params={"m": 2, "l": 0.5, "gr": 9.81},
         tags={"separable", "even_p"}),
    sys_("relativistic-pendulum", "sqrt(1+p^2) - cos(q)",
         "-cos(q) + sqrt(p^2+1)", "q", "p",
         [("bottom", pt(q=0, p=1)), ("turning", pt(q=1, p=0)),
          ("p<0", pt(q=0.5, p=-0.5))],
         (-1.5, 1.5), t=4, tags={"separable", "even_p"}),
    sys_("morse", "p^2/2 + d*(1-exp(-a*q))^2",
         "d*(1 - 2*exp(-a*q) + exp(-2*a*q)) + p^2/2", "q", "p",
         [("equilibrium", pt(q=0, p=0)), ("bottom", pt(q=0, p=1)),
          ("turning", pt(q=-0.5, p=0)), ("tiny-1e-6", pt(q=1e-6, p=0)),
          ("p<0", pt(q=0.5, p=-0.5))],
         (-0.5, 1), t=4, params={"d": 1, "a": 1},
         tags={"separable", "even_p"}),
    sys_("softened-coulomb", "p^2/2 - 1/sqrt(q^2+e)",
         "-1/sqrt(e + q^2) + p*p/2", "q", "p",
         [("equilibrium", pt(q=0, p=0)), ("bottom", pt(q=0, p=0.8)),
          ("turning", pt(q=1, p=0)), ("p<0", pt(q=-0.5, p=-0.3))],
         {"q": (-1.5, 1.5), "p": (-0.5, 0.5)},  # E < 0: bound orbits
         t=4, params={"e": 0.5}, tags={"separable", "even_p"}),
    sys_("calogero-1", "p^2/2 + q^2/2 + c/q^2", "c/q^2 + (q^2 + p^2)/2",
         "q", "p",
         [("equilibrium", pt(q=1.189207115002721, p=0)),  # q^4 = 2c
          ("turning", pt(q=0.5, p=0)),
          ("p<0", pt(q=1.5, p=-0.5))],
         (0.6, 1.6), t=3, params={"c": 1},
         tags={"separable", "even_p"}),
    sys_("lotka-volterra", "exp(q) - 2*q + exp(p) - p",
         "exp(p) - p + exp(q) - 2*q", "q", "p",
         [("equilibrium", pt(q=0.6931471805599453, p=0)),
          ("q-axis", pt(q=1, p=0)), ("p<0", pt(q=0.3, p=-0.5))],
         (-0.8, 0.8), t=3, tags={"separable"}),
    # ---- 2 dof --------------------------------------------------------
    sys_("aniso-2d", "(px^2+py^2)/2 + (x^2+4*y^2)/2",
         "2*y^2 + py^2/2 + x^2/2 + px^2/2", "xy", ["px", "py"],
         [("equilibrium", pt(x=0, y=0, px=0, py=0)),
          ("turning", pt(x=1, y=0.5, px=0, py=0)),
          ("p<0", pt(x=0.3, y=-0.2, px=-0.5, py=-0.1))],
         (-1, 1), t=3, tags={"quadratic", "separable"}),
    sys_("coupled-osc", "(px^2+py^2)/2 + (x^2+y^2)/2 + k*x*y",
         "(py^2 + px^2 + y^2 + x^2)/2 + y*x*k", "xy", ["px", "py"],
         [("turning", pt(x=1, y=0, px=0, py=0)),
          ("p<0", pt(x=0.1, y=0.2, px=-0.3, py=-0.4))],
         (-1, 1), t=3, params={"k": 0.25}, tags={"quadratic", "separable"}),
    sys_("magnetic", "((px + b*y/2)^2 + (py - b*x/2)^2)/2",
         "px^2/2 + py^2/2 + b*y*px/2 - b*x*py/2 + b^2*(x^2+y^2)/8",
         "xy", ["px", "py"],
         [("rest", pt(x=0.5, y=0, px=0, py=0.25)),
          ("p<0", pt(x=-0.5, y=0.3, px=-0.4, py=-0.2))],
         (-1, 1), t=3, params={"b": 2}, tags={"quadratic"}),
    sys_("magnetic-trap", "((px + b*y/2)^2 + (py - b*x/2)^2)/2 + (x^2+y^2)^2/4",
         "(x^2+y^2)^2/4 + ((py - b*x/2)^2 + (px + b*y/2)^2)/2",
         "xy", ["px", "py"],
         [("origin", pt(x=0, y=0, px=0, py=0)),
          ("turning", pt(x=1, y=0, px=0, py=0)),
          ("p<0", pt(x=0.2, y=-0.4, px=-0.3, py=-0.1))],
         (-1, 1), t=3, params={"b": 1}),
    sys_("henon-heiles", "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
         "x^2*y + (x^2+y^2+px^2+py^2)/2 - y^3/3", "xy", ["px", "py"],
         [("equilibrium", pt(x=0, y=0, px=0, py=0)),
          ("turning", pt(x=0.3, y=0.2, px=0, py=0)),
          ("near-escape", pt(x=0, y=0.5, px=0.4, py=0)),
          ("p<0", pt(x=0.1, y=-0.2, px=-0.3, py=-0.25))],
         (-0.4, 0.4), t=3, tags={"separable"}),
    sys_("quartic-2d", "(px^2+py^2)/2 + (x^4+y^4)/4 + x^2*y^2",
         "x^2*y^2 + (y^4 + x^4)/4 + (py^2 + px^2)/2", "xy", ["px", "py"],
         [("equilibrium", pt(x=0, y=0, px=0, py=0)),
          ("bottom", pt(x=0, y=0, px=1, py=0.5)),
          ("turning", pt(x=1, y=0.5, px=0, py=0))],
         (-1, 1), t=5, tags={"separable"}),
    sys_("fpu-alpha-2", "(p1^2+p2^2)/2 + q1^2/2 + (q2-q1)^2/2 + q2^2/2"
         " + al*(q1^3 + (q2-q1)^3 - q2^3)/3",
         "(p2^2+p1^2)/2 + q1^2 - q1*q2 + q2^2"
         " + al*(q1^3 + q2^3 - 3*q2^2*q1 + 3*q2*q1^2 - q1^3 - q2^3)/3",
         ["q1", "q2"], ["p1", "p2"],
         [("equilibrium", pt(q1=0, q2=0, p1=0, p2=0)),
          ("turning", pt(q1=0.5, q2=-0.3, p1=0, p2=0)),
          ("p<0", pt(q1=0.1, q2=0.2, p1=-0.5, p2=-0.2))],
         (-0.6, 0.6), t=3, params={"al": 0.25}, tags={"separable"}),
    sys_("fpu-beta-2", "(p1^2+p2^2)/2 + q1^2/2 + (q2-q1)^2/2 + q2^2/2"
         " + be*(q1^4 + (q2-q1)^4 + q2^4)/4",
         "(q2-q1)^2/2 + be*((q2-q1)^4 + q2^4 + q1^4)/4 + (q2^2 + q1^2)/2"
         " + (p2^2 + p1^2)/2",
         ["q1", "q2"], ["p1", "p2"],
         [("equilibrium", pt(q1=0, q2=0, p1=0, p2=0)),
          ("bottom", pt(q1=0, q2=0, p1=1, p2=-1)),
          ("turning", pt(q1=0.8, q2=0.8, p1=0, p2=0))],
         (-1, 1), t=3, params={"be": 1}, tags={"separable"}),
    sys_("double-pendulum",
         "(p1^2 + 2*p2^2 - 2*p1*p2*cos(q1-q2))/(2*(1+sin(q1-q2)^2))"
         " - 2*cos(q1) - cos(q2)",
         "-cos(q2) - 2*cos(q1)"
         " + (2*p2^2 + p1^2 - 2*p2*p1*cos(q1-q2))/(2 + 2*sin(q1-q2)^2)",
         ["q1", "q2"], ["p1", "p2"],
         [("equilibrium", pt(q1=0, q2=0, p1=0, p2=0)),
          ("turning", pt(q1=0.5, q2=-0.5, p1=0, p2=0)),
          ("tiny-1e-6", pt(q1=1e-6, q2=0, p1=0, p2=0)),
          ("p<0", pt(q1=0.3, q2=0.1, p1=-0.5, p2=-0.2))],
         # SymPy's route to g^4 q1 is 3e4 operations, evaluated at 30
         # digits in 8 s a point (a minute and a half of CI's twenty):
         # the Lie series is checked to order 3 here, 4 on every other
         (-0.8, 0.8), t=2, lie_order=3),
    sys_("toda-2",
         "(px^2+py^2)/2 + (exp(2*y+2*" + SQ3 + "*x) + exp(2*y-2*" + SQ3
         + "*x) + exp(-4*y))/24 - 1/8",
         "(exp(-4*y) + exp(2*y-2*" + SQ3 + "*x) + exp(2*y+2*" + SQ3
         + "*x))/24 + (py^2+px^2)/2 - 1/8",
         "xy", ["px", "py"],
         [("equilibrium", pt(x=0, y=0, px=0, py=0)),
          ("turning", pt(x=0.3, y=-0.2, px=0, py=0)),
          ("p<0", pt(x=0, y=0, px=-0.3, py=-0.4))],
         (-0.5, 0.5), t=3, tags={"separable"}),
    sys_("kepler-2d", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)",
         "-1/sqrt(y^2+x^2) + (py^2+px^2)/2", "xy", ["px", "py"],
         [("circular", pt(x=1, y=0, px=0, py=1)),
          ("apocentre", pt(x=1, y=0, px=0, py=0.8)),
          ("p<0", pt(x=-1, y=0.5, px=-0.2, py=-0.7)),
          ("quadrant-3", pt(x=-0.7, y=-0.7, px=0.6, py=-0.6))],
         None, t=2, tags={"separable"},
         sampler=kepler_point(["x", "y"], ["px", "py"])),
    sys_("calogero-2", "(p1^2+p2^2)/2 + (q1^2+q2^2)/2 + c/(q1-q2)^2",
         "c/(q2-q1)^2 + (q2^2+p2^2+q1^2+p1^2)/2", ["q1", "q2"], ["p1", "p2"],
         [("equilibrium", pt(q1=0.7071067811865476, q2=-0.7071067811865476,
                             p1=0, p2=0)),  # q1 = -q2, q1^4 = c/4
          ("turning", pt(q1=1, q2=-0.5, p1=0, p2=0)),
          ("p<0", pt(q1=0.3, q2=-0.9, p1=-0.2, p2=-0.1))],
         {"q1": (0.8, 1.5), "q2": (-1.5, -0.8), "p1": (-0.3, 0.3),
          "p2": (-0.3, 0.3)}, t=2, params={"c": 1}, tags={"separable"}),
    # ---- 3 dof --------------------------------------------------------
    sys_("aniso-3d", "(px^2+py^2+pz^2)/2 + (x^2+2*y^2+3*z^2)/2",
         "3*z^2/2 + y^2 + (pz^2+py^2+px^2+x^2)/2", "xyz", ["px", "py", "pz"],
         [("equilibrium", pt(x=0, y=0, z=0, px=0, py=0, pz=0)),
          ("turning", pt(x=1, y=0.5, z=-0.5, px=0, py=0, pz=0))],
         (-1, 1), t=3, tags={"quadratic", "separable"}),
    sys_("fpu-alpha-3", "(p1^2+p2^2+p3^2)/2 + (q1^2 + (q2-q1)^2 + (q3-q2)^2"
         " + q3^2)/2 + al*(q1^3 + (q2-q1)^3 + (q3-q2)^3 - q3^3)/3",
         "al*((q3-q2)^3 + (q2-q1)^3 + q1^3 - q3^3)/3"
         " + (q3^2 + (q3-q2)^2 + (q2-q1)^2 + q1^2 + p3^2 + p2^2 + p1^2)/2",
         ["q1", "q2", "q3"], ["p1", "p2", "p3"],
         [("equilibrium", pt(q1=0, q2=0, q3=0, p1=0, p2=0, p3=0)),
          ("turning", pt(q1=0.3, q2=0, q3=-0.3, p1=0, p2=0, p3=0)),
          ("p<0", pt(q1=0.1, q2=0.1, q3=0.1, p1=-0.3, p2=-0.2, p3=-0.1))],
         (-0.5, 0.5), t=2, params={"al": 0.25}, tags={"separable"}),
    sys_("toda-3", "(p1^2+p2^2+p3^2)/2 + exp(q1-q2) + exp(q2-q3)"
         " + exp(q3-q1) - 3",
         "exp(q3-q1) + exp(q2-q3) + exp(q1-q2) + (p3^2+p2^2+p1^2)/2 - 3",
         ["q1", "q2", "q3"], ["p1", "p2", "p3"],
         [("equilibrium", pt(q1=0, q2=0, q3=0, p1=0, p2=0, p3=0)),
          ("turning", pt(q1=0.5, q2=0, q3=-0.5, p1=0, p2=0, p3=0)),
          ("p<0", pt(q1=0, q2=0.2, q3=0, p1=-0.5, p2=0.2, p3=-0.1))],
         (-0.6, 0.6), t=2, tags={"separable"}),
    sys_("kepler-3d", "(px^2+py^2+pz^2)/2 - 1/sqrt(x^2+y^2+z^2)",
         "-1/sqrt(z^2+y^2+x^2) + (pz^2+py^2+px^2)/2", "xyz",
         ["px", "py", "pz"],
         [("circular", pt(x=1, y=0, z=0, px=0, py=1, pz=0)),
          ("inclined", pt(x=1, y=0, z=0, px=0, py=0.8, pz=0.4)),
          ("p<0", pt(x=-0.5, y=0.6, z=-0.5, px=-0.3, py=-0.4, pz=-0.2))],
         None, t=2, tags={"separable"},
         sampler=kepler_point(["x", "y", "z"], ["px", "py", "pz"])),
    sys_("iso-3d", "(px^2+py^2+pz^2+x^2+y^2+z^2)/2",
         "(x^2+px^2)/2 + (y^2+py^2)/2 + (z^2+pz^2)/2", "xyz",
         ["px", "py", "pz"],
         [("equilibrium", pt(x=0, y=0, z=0, px=0, py=0, pz=0)),
          ("p<0", pt(x=0.5, y=-0.5, z=0.2, px=-0.1, py=-0.2, pz=-0.3))],
         (-1, 1), t=3, tags={"quadratic", "separable"}),
]


def variables(s):
    return s["q"] + s["p"]


def random_points(s, rng, count):
    """count points: from the system's sampler, else uniform in its box
    (one (lo, hi) for every variable, or one per variable)."""
    out = []
    for i in range(count):
        if "sampler" in s:
            point = s["sampler"](rng)
        else:
            box = s["box"]
            point = {v: rng.uniform(*(box[v] if isinstance(box, dict) else box))
                     for v in variables(s)}
        out.append(("random-%d" % i, {k: round(v, 6) for k, v in point.items()}))
    return out


def points(s, rng, count):
    return list(s["special"]) + random_points(s, rng, count)


def init_arg(point):
    return ",".join("%s=%r" % (k, float(v)) for k, v in point.items())


def common_args(s, H=None):
    args = ["-H", H or s["H"]]
    for k, v in s["params"].items():
        args += ["--param", "%s=%r" % (k, v)]
    if s["pairs"]:
        args += ["--pairs", s["pairs"]]
    return args


def by_name(name):
    for s in ZOO:
        if s["name"] == name:
            return s
    raise KeyError(name)


