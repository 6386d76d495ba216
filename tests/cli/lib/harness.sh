# Shared by the CLI test scripts (sourced, not a test itself: CTest runs
# tests/cli/*.sh only).  The caller sets HAMLIE first.
#   run WANT_RC args...   run hamlie; stdout in $tmp/out, stderr in $tmp/err
#   has_line / has_text   an exact line / a substring in the last stdout
#   err_has TEXT          a substring in the last stderr
#   py CODE               python on the last stdout as JSON: d, S() sympifies
#                         with the system's symbols, same(a, b) compares
#   pyjson CODE           the same without SymPy: d only
#   finish                print "N passed, N failed" and set the exit status
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# python3 is the interpreter PATH names, found once: a version manager's
# shim (pyenv's) costs 0.35 s a call, and a script calls it dozens of times
HL_PYTHON=$(command python3 -c 'import sys; print(sys.executable)' 2>/dev/null) || HL_PYTHON=
[ -x "$HL_PYTHON" ] || HL_PYTHON=$(command -v python3)
python3() { command "$HL_PYTHON" "$@"; }
pass=0
fail=0

ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }

# run WANT_RC args...: output in $tmp/out, $tmp/err
run() {
    local want=$1
    shift
    "$HAMLIE" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -eq "$want" ]; then ok; else
        bad "hamlie $* exited $rc, want $want"; sed 's/^/    /' "$tmp/err" >&2
    fi
}

has_line() {
    if grep -qxF -- "$1" "$tmp/out"; then ok; else
        bad "no line '$1' in the output of the last command:"; sed 's/^/    /' "$tmp/out" >&2
    fi
}

has_text() {
    if grep -qF -- "$1" "$tmp/out"; then ok; else
        bad "no '$1' in the output of the last command:"; sed 's/^/    /' "$tmp/out" >&2
    fi
}

# py CODE: run python with `d` = the JSON output of the last command and
# `S(expr)` = sympify with the system's symbols; CODE asserts.
py() {
    if python3 - "$tmp/out" "$1" <<'PYEOF' >"$tmp/py" 2>&1; then ok; else bad "python check: $1"; sed 's/^/    /' "$tmp/py" >&2; fi
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
exec(sys.argv[2])
PYEOF
}

# pyjson CODE: py without SymPy (its import, 0.5 s, is most of a check
# that only reads fields): d is the last stdout as JSON; CODE asserts
pyjson() {
    if python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); exec(sys.argv[2])' \
        "$tmp/out" "$1" >"$tmp/py" 2>&1; then ok; else
        bad "python check: $1"
        sed 's/^/    /' "$tmp/py" >&2
    fi
}

err_has() {
    if grep -qF -- "$1" "$tmp/err"; then ok; else
        bad "no '$1' in stderr:"; sed 's/^/    /' "$tmp/err" >&2
    fi
}

finish() {
    echo "$pass passed, $fail failed"
    [ "$fail" -eq 0 ]
}
