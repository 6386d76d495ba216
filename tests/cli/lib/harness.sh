# Shared by the CLI test scripts (sourced, not a test itself: CTest runs
# tests/cli/*.sh only).  The caller sets HAMLIE first.
#   run WANT_RC args...   run hamlie; stdout in $tmp/out, stderr in $tmp/err
#   has_line / has_text   an exact line / a substring in the last stdout
#   err_has TEXT          a substring in the last stderr
#   py CODE               python on the last stdout as JSON: d, S() sympifies
#                         with the system's symbols, same(a, b) compares;
#                         queued, run at finish in one Python
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

# A sanitizer build (CI's second run) makes the same calls, for memory and
# UB errors; the mathematics of their output is the normal build's to check.
# There the queued SymPy checks only read their JSON (py below), and a
# script may leave out another costly check in pure Python: HL_SANITIZED=1.
HL_SANITIZED=0
ldd "$HAMLIE" 2>/dev/null | grep -q libasan && HL_SANITIZED=1

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

# py CODE: a check of the last stdout as JSON, with `d` = that JSON and
# `S(expr)` = sympify with the system's symbols, same(a, b); CODE asserts.
# The checks are queued and run at finish, in order, in one Python
# (lib/py_checks.py): SymPy's import, 0.9 s, was most of a check's cost.
# A check reads its own copy of the stdout, and any other file it opens
# must stay as it is until finish; the shell cannot wait on its result
# (use pyjson for that).  Under the sanitizers each only reads
# its JSON (the prelude: symbols, numeric_zero_test), as said at finish.
hl_py_count=0
py() {
    hl_py_count=$((hl_py_count + 1))
    local base="$tmp/pyq/$hl_py_count"
    mkdir -p "$tmp/pyq"
    cp "$tmp/out" "$base.json"
    printf '%s' "$1" >"$base.code"
    printf '%s' "${BASH_LINENO[0]}" >"$base.line"
}

# run_queued_py: the queued checks, counted as passed or failed
run_queued_py() {
    [ "$hl_py_count" -gt 0 ] || return 0
    local counts
    local only_json=
    [ "$HL_SANITIZED" = 1 ] && only_json=--only-json
    counts=$(python3 "$(dirname "${BASH_SOURCE[0]}")/py_checks.py" $only_json "$tmp/pyq" \
        "$hl_py_count" "$(basename "$0")")
    if [[ $counts =~ ^([0-9]+)\ ([0-9]+)$ ]] &&
        [ $((BASH_REMATCH[1] + BASH_REMATCH[2])) -eq "$hl_py_count" ]; then
        pass=$((pass + BASH_REMATCH[1]))
        fail=$((fail + BASH_REMATCH[2]))
    else
        fail=$((fail + hl_py_count))
        echo "FAIL: the $hl_py_count python checks did not run (lib/py_checks.py said '$counts')" >&2
    fi
    hl_py_count=0
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
    run_queued_py
    echo "$pass passed, $fail failed"
    [ "$fail" -eq 0 ]
}
