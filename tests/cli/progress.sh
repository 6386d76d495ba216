#!/bin/bash
# Issue 13, defect 12: long jobs say what they will do, show their progress
# on stderr (--progress forces it, --quiet silences it), and an interrupt
# (SIGINT, as Ctrl-C sends) stops them with their output whole: the CSV
# complete to its last row, the JSON closed with "interrupted": true, exit
# status 130.
# usage (from the repo root): bash tests/cli/progress.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: progress.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

PEND='p^2/2 - cos(q)'
LONG=(run -H "$PEND" --scheme rk4 --dt 0.1 --t 1e9 --init q=1,p=0)

# interrupted WANT_RC SECONDS args...: hamlie stopped by SIGINT SECONDS after
# its job started (with --progress it says so on stderr first; without, the
# SECONDS count from its start), killed 30 s later if SIGINT did not stop it
# (SIGINT waits while libgccjit compiles, seconds on a loaded machine under
# ASan: the check is that it stops cleanly, not how fast)
interrupted() {
    local want=$1 after=$2
    shift 2
    # a background job of a script starts with SIGINT ignored, and hamlie
    # keeps it so (as for nohup): env gives it the default disposition
    env --default-signal=INT "$HAMLIE" "$@" >"$tmp/out" 2>"$tmp/err" &
    local pid=$! i
    case " $* " in *" --progress "*)
        for i in $(seq 300); do grep -q "^hamlie [a-z]*: " "$tmp/err" && break; sleep 0.1; done ;;
    esac
    sleep "$after"
    kill -INT "$pid" 2>/dev/null
    for i in $(seq 300); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null
    wait "$pid"
    local rc=$?
    if [ "$rc" -eq "$want" ]; then ok; else
        bad "hamlie $* interrupted: exit $rc, want $want"; sed 's/^/    /' "$tmp/err" >&2
    fi
}

# check_csv FILE: every line whole, rows at t = k dt; prints the last k
check_csv() {
    python3 - "$1" "$tmp/err" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "interrupted CSV $1"; cat "$tmp/py" >&2; }
import math, re, sys
text = open(sys.argv[1]).read()
assert text.endswith("\n"), "the last line is not whole"
lines = text.splitlines()
assert lines[0] == "t,q,p,H,sigma", lines[0]
rows = [[float(v) for v in l.split(",")] for l in lines[1:]]
assert len(rows) > 10 and all(len(r) == 5 for r in rows)
for k, r in enumerate(rows):
    assert abs(r[0] - k * 0.1) <= 1e-9 * max(1, k), (k, r)
    assert abs(r[3] - (r[2] ** 2 / 2 - math.cos(r[1]))) <= 1e-12, r   # H of the row
# stderr names the step of the last row
m = re.search(r"interrupted after step (\d+) of 10000000000 ", open(sys.argv[2]).read())
assert m and int(m.group(1)) == len(rows) - 1, (m and m.group(1), len(rows))
PYEOF
}

# ---- SIGINT, --json: a closed document that says so ------------------------
interrupted 130 0.5 "${LONG[@]}" --json --progress
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "interrupted --json"; cat "$tmp/py" >&2; }
import json, math, sys
d = json.load(open(sys.argv[1]))
assert d["interrupted"] is True
k = d["steps"]
assert 0 < k < 10**10, k
assert abs(d["final_t"] - 0.1 * k) <= 1e-9 * k
z = d["final_state"]
assert abs(d["H_final"] - (z["p"] ** 2 / 2 - math.cos(z["q"]))) <= 1e-12   # H of that state
assert abs(d["H0"] + math.cos(1)) <= 1e-15                                  # H(q=1, p=0)
PYEOF
err_has "10000000000 steps (1e+10) of rk4 at dt = 0.1"  # said before it starts
err_has "interrupted after step"

# the compiled loop (no reference, rows sparse) stops as well
interrupted 130 0.5 run -H "$PEND" --scheme stormer-verlet-kdk --dt 0.1 --t 1e11 --init q=1,p=0 --json --no-reference --progress
python3 -c "import json,sys; d=json.load(open('$tmp/out')); assert d['interrupted'] and d['steps'] > 0" && ok || bad "compiled loop"

# ---- SIGINT, CSV on stdout and in --out: complete to the last row -----------
interrupted 130 0.5 "${LONG[@]}" --progress
check_csv "$tmp/out"
rm -f "$tmp/r.csv"*
interrupted 130 0.5 "${LONG[@]}" --out "$tmp/r.csv" --progress
if [ -f "$tmp/r.csv.partial" ] && [ ! -e "$tmp/r.csv" ] && [ ! -e "$tmp/r.csv.tmp" ]; then ok; else
    bad "--out: want only r.csv.partial, have: $(ls "$tmp" | grep r.csv)"; fi
check_csv "$tmp/r.csv.partial"
err_has "are kept in '$tmp/r.csv.partial'"

# ---- SIGINT while libgccjit compiles (an empty cache each time) -------------
# GCC's driver probes the signals' dispositions by setting SIG_IGN, which
# discarded a Ctrl-C held back meanwhile: the run went on (exit 137 here).
for after in 0.1 0.2 0.3 0.45; do
    HAMLIE_CACHE_DIR=$(mktemp -d "$tmp/cold.XXXXXX") interrupted 130 "$after" "${LONG[@]}" --json
done

# ---- the adaptive integrator, in double and in Arb ---------------------------
interrupted 130 0.5 run -H "$PEND" --scheme lie --tol 1e-12 --dt 1 --t 1e9 --init q=1,p=0 --json --progress
python3 -c "import json,sys; d=json.load(open('$tmp/out')); assert d['interrupted'] and d['steps'] > 0" && ok || bad "adaptive --json"
# rows 10^9 apart (hours each): stopped between two rows all the same
interrupted 130 0.5 run -H "$PEND" --scheme lie --tol 1e-15 --t 1e12 --init q=1,p=0 --json --progress
python3 -c "import json,sys; d=json.load(open('$tmp/out')); assert d['interrupted'] and d['steps'] == 0 and d['taylor_steps'] > 1000" && ok || bad "adaptive, rows far apart"
interrupted 130 0.5 run -H "$PEND" --scheme lie --digits 30 --dt 1 --t 1e6 --init q=1,p=0 --json --progress
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "--digits --json"; cat "$tmp/py" >&2; }
import json, sys
d = json.load(open(sys.argv[1]))
assert d["interrupted"] is True and 0 < d["outputs"] < 10**6
assert float(d["final_t"]) == d["outputs"]          # rows at t = 1, 2, ...
PYEOF
# --orders: the steps done before the interrupt
interrupted 130 2 run -H "$PEND" --scheme rk4 --orders 0.1,0.05,0.00000001 --t 10 --init q=1,p=0 --json --progress
python3 - "$tmp/out" <<'PYEOF' >"$tmp/py" 2>&1 && ok || { bad "--orders interrupted"; cat "$tmp/py" >&2; }
import json, sys
d = json.load(open(sys.argv[1]))
assert d["interrupted"] is True
assert [o["dt"] for o in d["orders"]] == [0.1, 0.05], d["orders"]
assert abs(d["orders"][1]["order"] - 4) < 0.1, d["orders"]    # RK4: 3.97
PYEOF

# ---- lie: nothing half-written -------------------------------------------------
interrupted 130 0.5 lie -H "$PEND" --order 200 --json --progress
if [ -s "$tmp/out" ]; then bad "lie interrupted printed something"; else ok; fi
err_has "interrupted"

# ---- --progress, --quiet -------------------------------------------------------
run 0 run -H "$PEND" --scheme rk4 --dt 0.1 --t 100 --init q=1,p=0 --json --progress
err_has "hamlie run: 1000 steps (1e+03) of rk4 at dt = 0.1 to t = 100"
err_has "hamlie run: step "
run 0 run -H "$PEND" --scheme rk4 --dt 0.1 --t 100 --init q=1,p=0 --json --quiet
if [ -s "$tmp/err" ]; then bad "--quiet wrote to stderr"; cat "$tmp/err" >&2; else ok; fi
# without either, a short run says nothing
run 0 run -H "$PEND" --scheme rk4 --dt 0.1 --t 100 --init q=1,p=0 --json
if [ -s "$tmp/err" ]; then bad "a short run wrote to stderr"; cat "$tmp/err" >&2; else ok; fi
interrupted 130 1 "${LONG[@]}" --json --quiet
if grep -q "steps (1e+10)\|%)" "$tmp/err"; then bad "--quiet said progress"; cat "$tmp/err" >&2; else ok; fi
run 0 lie -H "$PEND" --order 5 --progress
err_has "hamlie lie: order 1 of 5"
run 0 lie -H "$PEND" --order 5 --quiet
if [ -s "$tmp/err" ]; then bad "lie --quiet wrote to stderr"; else ok; fi
run 2 run -H "$PEND" --scheme rk4 --dt 0.1 --t 1 --init q=1,p=0 --progress --quiet
err_has "--progress and --quiet cannot be used together"
run 2 generator -H "$PEND" --progress
err_has "does not apply"

finish
