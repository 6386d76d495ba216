"""The queued `py` checks of a CLI test script (harness.sh), run in one
Python: SymPy is imported once (0.9 s a process, most of what a check cost
when each had its own), and each check runs in a namespace of its own, as
in its own process before.

usage: py_checks.py [--only-json] QUEUE_DIR COUNT SCRIPT
QUEUE_DIR holds N.json (the stdout the check reads), N.code (the check)
and N.line (where the script called py), N = 1..COUNT.  Prints each
failure to stderr, and "PASSED FAILED" on stdout.  --only-json (the
sanitizer build): the prelude alone, the JSON read; the checks' own
mathematics is the normal build's, and SymPy is not imported."""

import contextlib
import io
import os
import sys
import traceback

# What each check had in scope when it was a process of its own
PRELUDE = '''
import json, sys, sympy
from sympy import Symbol, sympify, simplify, sin, cos, sqrt, Rational, factorial, series
d = json.load(open(sys.argv[1]))
sy = d["symbols"]
names = sy["coordinates"] + sy["momenta"] + sy["parameters"] + [sy["step"]]
loc = {n: Symbol(n) for n in names}
def S(s):
    return sympify(s, locals=loc)
def same(a, b):
    return simplify(S(a) - S(b)) == 0 if isinstance(a, str) or isinstance(b, str) else simplify(a - b) == 0
def every_string(x):
    if isinstance(x, dict):
        for v in x.values(): yield from every_string(v)
    elif isinstance(x, list):
        for v in x: yield from every_string(v)
    elif isinstance(x, str):
        yield x
assert isinstance(d["numeric_zero_test"], bool)
'''


# The prelude's reading of the JSON, without SymPy (--only-json)
JSON_PRELUDE = '''
import json, sys
d = json.load(open(sys.argv[1]))
sy = d["symbols"]
names = sy["coordinates"] + sy["momenta"] + sy["parameters"] + [sy["step"]]
assert isinstance(d["numeric_zero_test"], bool)
'''


def run_check(json_path, code):
    """None when the check passes, else what it printed and its traceback.
    code None: the prelude alone, without SymPy."""
    said = io.StringIO()
    sys.argv = ["-", json_path, code]
    scope = {"__name__": "__main__", "__builtins__": __builtins__}
    try:
        with contextlib.redirect_stdout(said), contextlib.redirect_stderr(said):
            if code is None:
                exec(compile(JSON_PRELUDE, "<py prelude>", "exec"), scope)
                return None
            exec(compile(PRELUDE, "<py prelude>", "exec"), scope)
            exec(compile(code, "<py check>", "exec"), scope)
    except SystemExit as e:  # exit(0) passed, as the process's status did
        if e.code in (None, 0):
            return None
        return said.getvalue() + traceback.format_exc()
    except BaseException:  # an assert, an error, or the check's own exit
        return said.getvalue() + traceback.format_exc()
    return None


def main():
    args = sys.argv[1:]
    only_json = args[:1] == ["--only-json"]
    queue, count, script = args[-3], int(args[-2]), args[-1]
    if only_json:
        print("%s: sanitizer build: its %d SymPy checks read their JSON only "
              "(the normal build runs them)" % (script, count), file=sys.stderr)
    passed = failed = 0
    for n in range(1, count + 1):
        base = os.path.join(queue, str(n))
        code = open(base + ".code").read()
        line = open(base + ".line").read().strip()
        why = run_check(base + ".json", None if only_json else code)
        if why is None:
            passed += 1
            continue
        failed += 1
        print("FAIL: python check (%s line %s): %s" % (script, line, code),
              file=sys.stderr)
        print("".join("    " + l + "\n" for l in why.splitlines()),
              end="", file=sys.stderr)
    print(passed, failed)


if __name__ == "__main__":
    main()
