#!/bin/bash
# Bad input: each case must exit 2, print NOTHING on stdout, and say what is
# wrong on stderr ("hamlie: error: ..." or "hamlie CMD: error: ..."); for an
# error inside a formula, the formula is echoed and a caret stands under the
# offending character (column given in the table, counted from 0).
# usage (from the repo root): bash tests/cli/errors.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: errors.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"
KEPLER='(px^2+py^2)/2 - 1/sqrt(x^2+y^2)'

# case NAME CARET_COLUMN|- MESSAGE_PIECE -- args...
case_() {
    local name=$1 col=$2 piece=$3
    shift 4
    "$HAMLIE" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$? why=""
    [ "$rc" -eq 2 ] || why="exit $rc, want 2"
    [ -s "$tmp/out" ] && why="$why; stdout not empty"
    head -1 "$tmp/err" | grep -Eq '^hamlie( [a-z]+)?: error: ' || why="$why; no 'hamlie: error:' line"
    grep -qF -- "$piece" "$tmp/err" || why="$why; message lacks '$piece'"
    if [ "$col" != "-" ]; then
        # line 2 is "  <formula>", line 3 is "  <col spaces>^"
        local want
        want="$(printf '  %*s^' "$col" '')"
        sed -n 3p "$tmp/err" | grep -q "^$(printf '%s' "$want" | sed 's/\^/\\^/')" ||
            why="$why; caret not at column $col"
    fi
    if [ -z "$why" ]; then pass=$((pass + 1)); else
        fail=$((fail + 1))
        echo "FAIL: $name: $why" >&2
        sed 's/^/    stderr: /' "$tmp/err" >&2
        sed 's/^/    stdout: /' "$tmp/out" >&2
    fi
}

case_ "unclosed parenthesis"   10 "')'"                 -- generator -H '(p^2+x^2/2'
case_ "operator without operand" 4 "expected"           -- generator -H 'p^2+*x'
case_ "empty formula"           0 "empty formula"            -- generator -H ''
case_ "unknown function"        6 "unknown function 'foo'" -- generator -H 'p^2 + foo(x)'
case_ "momentum without coordinate (pairs)" 2 "momentum missing" -- generator --pairs 'x:' -H 'p^2/2'
case_ "pairing not inferable"   0 "--pairs"             -- generator -H 'p^2/2'
case_ "name used twice"         4 "used twice"          -- generator --pairs 'x:p,x:q' -H 'p^2+x^2'
case_ "unknown symbol in --integral" 7 "unknown symbol 'z'" -- check -H "$KEPLER" --integral 'x*py - z*px'
case_ "unknown symbol in --of"  6 "unknown symbol 'k'"  -- lie -H '(p^2+x^2)/2' --of 'x^2 - k'
case_ "unknown symbol in bracket" 0 "unknown symbol 'w'" -- bracket -H '(p^2+x^2)/2' 'w*x' 'p'
case_ "unknown symbol in a map" 15 "unknown symbol 'z'" -- canonical -H '(p^2+x^2)/2' --map 'X = x; P = p + z'
case_ "1/0 in a constant"       10 "division by zero"    -- generator -H 'p^2/2 + 1/0*x'
case_ "1/0 in --param"          - "division by zero"    -- generator -H 'p^2/2 + k*x' --param 'k=1/0'
case_ "param not constant"      2 "not a constant"      -- generator -H 'p^2/2 + k*x' --param 'k=x'
case_ "param not in system"     0 "no symbol 'j'"       -- generator -H 'p^2/2 + k*x' --param 'j=2'
case_ "H in a map without -H"   4 "'H'"                 -- canonical --map 'X = H; P = p + x'
case_ "map left side"           7 "left side"           -- canonical --map 'X = x; Z = p'
case_ "map count"               - "2 phase variables"   -- canonical --map 'X = x + D*p'
case_ "order too large"         - "200"                 -- lie -H 'p^2/2 - cos(q)' --order 100000
case_ "order negative"          - "at least 0"          -- lie -H 'p^2/2 - cos(q)' --order -1
case_ "order not a number"      - "whole number"        -- lie -H 'p^2/2 - cos(q)' --order six
case_ "missing -H (generator)"  - "missing -H"          -- generator
case_ "missing -H (check)"      - "missing -H"          -- check --integral 'x*p'
case_ "missing -H (lie)"        - "missing -H"          -- lie --order 3
case_ "missing --integral"      - "--integral"          -- check -H '(p^2+x^2)/2'
case_ "missing --map"           - "missing --map"       -- canonical
case_ "bracket one argument"    - "two functions"       -- bracket -H '(p^2+x^2)/2' 'x'
case_ "json and latex"          - "together"            -- generator -H '(p^2+x^2)/2' --json --latex
case_ "unknown option"          - "unknown option"      -- generator -H '(p^2+x^2)/2' --colour
case_ "option missing value"    - "needs a value"       -- generator -H
case_ "option of another command" - "does not apply"    -- generator -H '(p^2+x^2)/2' --order 3
case_ "unknown command"         - "unknown command"     -- frobnicate
case_ "no command"              - "usage"               --

finish
