"""run(): NumPy arrays against closed forms (the oscillator: RK4 and Euler
are powers of a known matrix, the exact flow is a rotation), the command
line's CSV and JSON for the same input, mpmath at 40 digits, bad input."""
import csv
import io
import math
import threading

import mpmath
import numpy as np
import pytest

import hamlie
from conftest import cli

OSC = "(p^2+x^2)/2"


def rk4_matrix(h):
    """The RK4 step on z' = J z: sum_{k<=4} (h J)^k / k!"""
    J = np.array([[0.0, 1.0], [-1.0, 0.0]])
    M, term = np.eye(2), np.eye(2)
    for k in range(1, 5):
        term = term @ (h * J) / k
        M = M + term
    return M


def test_rk4_oscillator_closed_form():
    dt, T = 0.1, 20.0
    r = hamlie.System(OSC).run("rk4", dt=dt, t=T, init={"x": 1.0, "p": 0.0})
    n = round(T / dt)
    assert len(r) == n + 1 and r.z.shape == (n + 1, 2)
    M, z = rk4_matrix(dt), np.array([1.0, 0.0])
    expect = [z]
    for _ in range(n):
        z = M @ z
        expect.append(z)
    expect = np.array(expect)
    assert np.allclose(r.x, expect[:, 0], rtol=0, atol=1e-13)
    assert np.allclose(r.p, expect[:, 1], rtol=0, atol=1e-13)
    assert np.allclose(r.t, dt * np.arange(n + 1), rtol=0, atol=1e-12)
    assert np.allclose(r.H, (r.x ** 2 + r.p ** 2) / 2, rtol=1e-15, atol=0)
    # sigma: squared distance to the exact rotation
    exact = np.stack([np.cos(r.t), -np.sin(r.t)], axis=1)
    assert np.allclose(r.sigma, ((r.z - exact) ** 2).sum(axis=1), rtol=1e-6, atol=1e-28)
    assert r.summary["steps"] == n and r.summary["failed"] is False


def test_user_map_is_euler():
    dt, T = 0.05, 2.0
    r = hamlie.System(OSC).run(map="X = x + D*p; P = p - D*x", dt=dt, t=T,
                               init={"x": 0.5, "p": 0.25}, reference=False)
    M = np.array([[1.0, dt], [-dt, 1.0]])
    z = np.array([0.5, 0.25])
    for _ in range(round(T / dt)):
        z = M @ z
    assert np.allclose(r.z[-1], z, rtol=1e-14, atol=0)
    assert np.isnan(r.sigma).all()


def test_bits_match_cli_csv():
    H, args = "p^2/2 - cos(q)", dict(dt=0.05, t=10.0, every=7)
    r = hamlie.System(H).run("stormer-verlet-kdk", init={"q": 1.3, "p": 0}, observe=["q*p"],
                             **args)
    text = cli("run", "-H", H, "--scheme", "stormer-verlet-kdk", "--dt", "0.05", "--t", "10",
               "--every", "7", "--init", "q=1.3,p=0", "--observe", "q*p", json_out=False)
    rows = list(csv.reader(io.StringIO(text)))
    assert rows[0][:5] == ["t", "q", "p", "H", "sigma"]
    table = np.array([[float(v) for v in row] for row in rows[1:]])
    assert table.shape[0] == len(r)
    for col, arr in zip(range(5), (r.t, r.q, r.p, r.H, r.sigma)):
        assert np.array_equal(table[:, col], arr), rows[0][col]
    assert np.array_equal(table[:, 5], r["q*p"])
    assert np.allclose(r["q*p"], r.q * r.p, rtol=1e-15, atol=1e-300)


def test_summary_matches_cli_json():
    H = "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3"
    r = hamlie.System(H).run("gauss2", dt=0.1, t=5, init={"x": 0.1, "y": 0.2, "px": 0.3,
                                                          "py": 0.1})
    j = cli("run", "-H", H, "--scheme", "gauss2", "--dt", "0.1", "--t", "5",
            "--init", "x=0.1,y=0.2,px=0.3,py=0.1")
    names = ["x", "y", "px", "py"]
    assert r.summary["final_state"] == [j["final_state"][n] for n in names]
    assert r.summary["max_dH"] == j["max_abs_dH"]
    assert r.summary["sigma"] == j["sigma_final"]
    assert r.summary["max_error"] == j["max_error"]


def test_adaptive_lie_against_cos():
    r = hamlie.System(OSC).run("lie", tol=1e-15, dt=0.5, t=50, init={"x": 1, "p": 0})
    assert np.allclose(r.x, np.cos(r.t), rtol=0, atol=5e-13)
    assert np.allclose(r.p, -np.sin(r.t), rtol=0, atol=5e-13)
    assert r.summary["integrator"] == "adaptive-taylor"


def test_digits_mpmath():
    r = hamlie.System(OSC).run("lie", tol=1e-15, t="1", dt=0.25, init={"x": 1, "p": 0},
                               digits=40)
    assert isinstance(r.x[-1], mpmath.mpf)
    with mpmath.workdps(45):
        assert abs(r.x[-1] - mpmath.cos(1)) < mpmath.mpf("1e-35")
        assert abs(r.p[-1] + mpmath.sin(1)) < mpmath.mpf("1e-35")
        assert abs(r.t[2] - mpmath.mpf("0.5")) < mpmath.mpf("1e-38")


def test_every_and_rows():
    r = hamlie.System(OSC).run("euler", dt=0.1, t=10, every=30, init="x=1,p=0")
    assert list(np.round(r.t / 0.1).astype(int)) == [0, 30, 60, 90, 100]


def test_threads_give_the_serial_results():
    H = "p^2/2 - cos(q)"
    inits = [{"q": 0.5 + 0.1 * i, "p": 0} for i in range(4)]
    serial = [hamlie.System(H).run("rk4", dt=0.01, t=50, init=z).z for z in inits]
    out = [None] * 4

    def work(i):
        out[i] = hamlie.System(H).run("rk4", dt=0.01, t=50, init=inits[i]).z
    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for a, b in zip(serial, out):
        assert np.array_equal(a, b)


def test_one_system_shared_by_threads():
    s = hamlie.System("p^2/2 - cos(q)")
    out = {}

    def work(i):
        out[i] = (s.run("rk4", dt=0.01, t=10, init={"q": 1, "p": 0}).z[-1],
                  s.bracket("q*p", "H"))
    threads = [threading.Thread(target=work, args=(i,)) for i in range(3)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert all(np.array_equal(out[0][0], out[i][0]) and out[0][1] == out[i][1] for i in out)


@pytest.mark.parametrize("kw,exc", [
    (dict(scheme="rk4", dt=0.1, t=1, init={"x": math.nan, "p": 0}), ValueError),
    (dict(scheme="rk4", dt=0.1, t=1, init={"x": math.inf, "p": 0}), ValueError),
    (dict(scheme="rk4", dt=0.1, t=1, init="x=1/0,p=0"), hamlie.Error),
    (dict(scheme="rk4", dt=0.1, t=1, init={"x": 1}), hamlie.Error),
    (dict(scheme="rk4", dt=0.1, t=1, init={"x": 1, "p": 0, "z": 2}), hamlie.Error),
    (dict(scheme="rk4", dt=0.3, t=1, init={"x": 1, "p": 0}), hamlie.Error),
    (dict(scheme="rk4", dt=-0.1, t=1, init={"x": 1, "p": 0}), ValueError),
    (dict(scheme="rk4", dt=math.nan, t=1, init={"x": 1, "p": 0}), ValueError),
    (dict(scheme="rk4", dt="0.1", t=1, init={"x": 1, "p": 0}), TypeError),
    (dict(scheme="rk4", dt=0.1, t=1, init=[1, 0]), TypeError),
    (dict(scheme="warp-drive", dt=0.1, t=1, init={"x": 1, "p": 0}), hamlie.Error),
    (dict(scheme=None, dt=0.1, t=1, init={"x": 1, "p": 0}), TypeError),
    (dict(scheme="rk4", dt=0.1, t=1, init={"x": 1, "p": 0}, observe=["x+"]), hamlie.Error),
    (dict(scheme="rk4", dt=0.1, t=1, init={"x": 1, "p": 0}, digits=30), ValueError),
    (dict(map="X = x + D*p; P = p - D*", dt=0.1, t=1, init={"x": 1, "p": 0}), hamlie.Error),
    (dict(scheme="rk4", dt=0.1, init={"x": 1, "p": 0}), TypeError),
])
def test_bad_input(kw, exc):
    with pytest.raises(exc):
        hamlie.System(OSC).run(**kw)


def test_blow_up_is_an_error_not_nan():
    with pytest.raises(hamlie.Error, match="step|finite|blow"):
        hamlie.System("p^2/2 - q^4/4").run("euler", dt=0.5, t=200, init={"q": 3, "p": 0})


def test_outside_domain():
    with pytest.raises(hamlie.Error, match="domain"):
        hamlie.System("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)").run(
            "rk4", dt=0.1, t=1, init={"x": 0, "y": 0, "px": 0, "py": 1})


def test_repr_and_plot(tmp_path):
    r = hamlie.System(OSC).run("rk4", dt=0.1, t=5, init={"x": 1, "p": 0})
    assert "rk4" in repr(r) and r._repr_latex_().startswith("$")
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    fig = r.plot()
    fig.savefig(tmp_path / "run.png")
    assert (tmp_path / "run.png").stat().st_size > 1000


def test_lie_fixed_step_is_truncated_series():
    """scheme "lie" with dt alone and order=3: z -> sum_{k<=3} (D J)^k/k! z"""
    dt = 0.1
    r = hamlie.System(OSC).run("lie", dt=dt, t=1, order=3, init={"x": 1, "p": 0})
    J = np.array([[0.0, 1.0], [-1.0, 0.0]])
    M = np.eye(2) + dt * J + (dt * J) @ (dt * J) / 2 + (dt * J) @ (dt * J) @ (dt * J) / 6
    z = np.array([1.0, 0.0])
    for _ in range(10):
        z = M @ z
    assert np.allclose(r.z[-1], z, rtol=0, atol=1e-15)
    assert r.summary["integrator"] == "fixed-step"


def test_exact_flow_of_the_pendulum():
    r = hamlie.System("p^2/2 - cos(q)").run("exact", dt=0.1, t=1, init={"q": 1, "p": 0})
    assert r.sigma.max() < 1e-25
    assert np.ptp(r.H) < 1e-14


def test_ctrl_c_stops_a_run():
    """SIGINT to the main thread, as a terminal's Ctrl-C reaches a Python
    without other threads.  (Sent to the process from another thread, it may
    land in that thread while libgccjit compiles with GCC's own handler in
    place, which kills the process: src/tape/jit_common.c blocks the signal
    in the compiling thread only.)"""
    import signal
    main = threading.main_thread().ident
    timer = threading.Timer(0.5, lambda: signal.pthread_kill(main, signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            hamlie.System("p^2/2 - cos(q)").run("rk4", dt=1e-4, t=1e6, every=10 ** 6,
                                                init={"q": 1, "p": 0})
    finally:
        timer.cancel()
