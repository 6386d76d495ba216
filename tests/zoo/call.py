"""Running the hamlie binary: one call with a time budget, its outcome
classified (done, refused, crashed, hung), and the JSON it printed scanned
for values that are not finite."""

import json
import math
import resource
import shlex
import signal
import subprocess
import threading
import time
from contextlib import contextmanager

SANITIZER_MARKS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer",
                   "runtime error:", "SUMMARY: UndefinedBehaviorSanitizer")


class Outcome:
    """What one call did: rc (None when it hung), stdout, stderr, the JSON
    (None when stdout is not JSON), the seconds it took, and the command
    line to reproduce it."""

    def __init__(self, argv, rc, out, err, seconds):
        self.argv, self.rc, self.out, self.err = argv, rc, out, err
        self.seconds = seconds
        self.json = None
        if rc == 0 and out.lstrip().startswith("{"):
            try:
                self.json = json.loads(out)
            except ValueError:
                self.json = None

    @property
    def hung(self):
        """Out of its CPU budget (SIGXCPU) or of the wall-clock backstop."""
        return self.rc is None or self.rc == -signal.SIGXCPU

    @property
    def crashed(self):
        """A signal, an exit status of 128 or more, or a sanitizer report."""
        if self.hung:
            return False
        return (self.rc < 0 or self.rc >= 128
                or any(m in self.err for m in SANITIZER_MARKS))

    @property
    def ok(self):
        return self.rc == 0 and not self.crashed

    def repro(self):
        return "hamlie " + " ".join(shlex.quote(a) for a in self.argv[1:])

    def why(self):
        if self.hung:
            return "no answer within the budget (%.0f s wall)" % self.seconds
        if self.crashed:
            return "crashed (exit %s): %s" % (self.rc, last_line(self.err))
        return "exit %s: %s" % (self.rc, last_line(self.err))


def last_line(text):
    """The first line that says "error", else the last line."""
    lines = [l for l in text.strip().splitlines() if l.strip()]
    said = [l for l in lines if "error" in l.lower()]
    return (said or lines or [""])[0 if said else -1][:200]


class OneAtATime:
    """The zoo's threads overlap hamlie's processes, never their own Python.
    mpmath's working precision (mp.prec) is one global, and SymPy sets it to
    2 bits for a moment whenever it asks the sign of a function
    (Expr._eval_is_extended_positive_negative calls _eval_evalf(2), under
    mpmath.workprec); a conversion to mpf in another thread in that moment
    keeps 2 bits (CI once read v_3 = 5.77242 as 6). So a worker holds this
    lock whenever it runs, and lets go only while it waits for hamlie."""

    def __init__(self):
        self._lock = threading.Lock()
        self._mine = threading.local()

    @contextmanager
    def held(self):
        with self._lock:
            self._mine.held = True
            try:
                yield
            finally:
                self._mine.held = False

    @contextmanager
    def released(self):
        if not getattr(self._mine, "held", False):
            yield
            return
        self._mine.held = False
        self._lock.release()
        try:
            yield
        finally:
            self._lock.acquire()
            self._mine.held = True


PYTHON = OneAtATime()


class Hamlie:
    """The binary, the budget of a call, and a count of the calls. The
    budget is CPU seconds (RLIMIT_CPU), so that a loaded machine does not
    turn a slow answer into a hang; the wall clock stops a call that waits
    (a deadlock, a sleep) at WALL_FACTOR times the budget."""

    WALL_FACTOR = 6

    def __init__(self, path, cpu_seconds):
        self.path, self.cpu_seconds = path, cpu_seconds
        self.calls = 0

    def __call__(self, *args):
        argv = [self.path] + [str(a) for a in args]
        limit = self.cpu_seconds * self.WALL_FACTOR
        budget = int(math.ceil(self.cpu_seconds))
        self.calls += 1
        with PYTHON.released():
            return self._run(argv, limit, budget)

    @staticmethod
    def _run(argv, limit, budget):
        start = time.monotonic()
        # NOTE: prlimit after the start, not preexec_fn (unsafe with threads);
        # the child has used next to no CPU by then
        p = subprocess.Popen(argv, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                             text=True)
        try:
            resource.prlimit(p.pid, resource.RLIMIT_CPU, (budget, budget + 1))
        except (ProcessLookupError, OSError):
            pass
        try:
            out, err = p.communicate(timeout=limit)
            return Outcome(argv, p.returncode, out, err,
                           time.monotonic() - start)
        except subprocess.TimeoutExpired:
            p.kill()
            out, err = p.communicate()
            return Outcome(argv, None, out, err, limit)



def non_finite_paths(value, path="", allow_null=()):
    """The places in a JSON value holding NaN or an infinity (JSON has no
    such numbers, but Python's reader takes the tokens NaN and Infinity),
    null where a number is promised (every key not in allow_null), or a
    sympy string that is not finite (nan, zoo, oo)."""
    found = []
    if isinstance(value, dict):
        for k, v in value.items():
            if v is None and k not in allow_null:
                found.append(path + "/" + k + " = null")
            else:
                found += non_finite_paths(v, path + "/" + k, allow_null)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            found += non_finite_paths(v, "%s[%d]" % (path, i), allow_null)
    elif isinstance(value, float):
        if not math.isfinite(value):
            found.append(path + " = " + repr(value))
    elif isinstance(value, str):
        if _sympy_not_finite(value):
            found.append(path + " = " + value[:60])
    return found


def _sympy_not_finite(text):
    tokens = set(text.replace("(", " ").replace(")", " ").replace("*", " ")
                 .replace("+", " ").replace("-", " ").replace("/", " ")
                 .split())
    return bool(tokens & {"nan", "zoo", "oo", "NaN", "inf", "Infinity"})
