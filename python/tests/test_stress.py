"""10^5 calls into the extension, good and bad, and the resident memory does
not grow: every string, array, error and library object is released.  The
calls go to _hamlie directly (the SymPy layer would only slow them down);
the RSS is read from /proc/self/statm after a warm-up and at the end."""
import os

import hamlie
from hamlie import _hamlie

PAGE = os.sysconf("SC_PAGE_SIZE")


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * PAGE


def one_round(s, i):
    """25 calls of every kind"""
    for _ in range(5):
        s.bracket("p*cos(q)", "H")
        s.generator()
    for _ in range(5):
        _hamlie.System("p^2/2 - cos(q) + k*q", params="k=1/3").info()
    for _ in range(4):
        try:
            s.bracket("q+", "p")
        except hamlie.Error:
            pass
    try:
        s.run(scheme="rk4", dt=0.1, t=1, init="q=nan,p=0")
    except hamlie.Error:
        pass
    r = s.run(scheme="rk4", dt=0.1, t=0.5, init="q=1,p=0", observe=["q*p"])
    assert r["z"].shape == (6, 2)
    if i % 8 == 0:
        s.errors(scheme="euler", order=3)
    s.check(["H", "q"])
    s.lie_terms("q", 3)


def test_no_memory_growth():
    s = _hamlie.System("p^2/2 - cos(q)")
    rounds = 4000  # 25 calls each: 10^5
    warm = rounds // 10
    for i in range(warm):
        one_round(s, i)
    before = rss_bytes()
    for i in range(warm, rounds):
        one_round(s, i)
    grown = rss_bytes() - before
    # a leak of even 16 bytes a call would be 1.4 MB here
    assert grown < 1 << 20, f"RSS grew by {grown / 1e6:.2f} MB over {(rounds - warm) * 25} calls"
