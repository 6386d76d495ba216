#!/bin/bash
# What a command does not use it does not load (issue 17).  The executable
# is a launcher linked with libc alone: --version and --help load no FLINT
# (ld.so's own trace, LD_DEBUG=files, says what was loaded); a command loads
# the module hamlie-cli.so and FLINT but neither libgccjit nor PLplot; a
# long run loads libgccjit.  Without libgccjit (HAMLIE_GCCJIT_LIB pointing
# nowhere) the run prints the same numbers and a note; without PLplot a plot
# fails with exit 2, the reason, and no file or folder left behind.
# usage (from the repo root): bash tests/cli/startup.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: startup.sh path/to/hamlie}
case $HAMLIE in /*) ;; *) HAMLIE=$PWD/$HAMLIE ;; esac # the work is done in $tmp
. "$(dirname "$0")/lib/harness.sh"
cd "$tmp" || exit 2

# loaded NAME-REGEX: did the last traced run (LD_DEBUG_OUTPUT=$tmp/ld) load it?
loaded() { cat "$tmp"/ld.* 2>/dev/null | grep -E 'file=[^ ]*('"$1"')[^ ]* +\[0\]; +(needed|dynamically loaded)' -q; }
traced() { rm -f "$tmp"/ld.*; LD_DEBUG=files LD_DEBUG_OUTPUT=$tmp/ld run "$@"; }
yes_loaded() { if loaded "$1"; then ok; else bad "$2 did not load $1"; fi; }
not_loaded() { if loaded "$1"; then bad "$2 loaded $1"; else ok; fi; }

# ---- link lines: the launcher names none of the heavy libraries ----
if ldd "$HAMLIE" | grep -Eq 'libgccjit|libplplot|libflint'; then
    bad "ldd $HAMLIE names a heavy library:"; ldd "$HAMLIE" | sed 's/^/    /' >&2
else ok; fi
MODULE=$(dirname "$HAMLIE")/hamlie-cli.so
if [ -f "$MODULE" ] && ! ldd "$MODULE" | grep -Eq 'libgccjit|libplplot'; then ok; else
    bad "$MODULE missing or linked with libgccjit/libplplot"; fi

# ---- the questions about hamlie load no FLINT; a command does ----
traced 0 --version
has_text "hamlie "
not_loaded 'libflint' "--version"
traced 0 --help
has_text "Commands:"
not_loaded 'libflint' "--help"
traced 0 help run
has_text "usage: hamlie run"
not_loaded 'libflint' "help run"
traced 0 generator -H 'p^2/2+q^2/2'
yes_loaded 'libflint' "generator" # the trace works
not_loaded 'libgccjit|libplplot' "generator"

# ---- the launcher alone answers --version, and says what is missing ----
mkdir alone && cp "$HAMLIE" alone/hamlie
"$HAMLIE" --version >want.txt
run 0 --version
HAMLIE_SAVED=$HAMLIE HAMLIE=$tmp/alone/hamlie
run 0 --version
if cmp -s "$tmp/out" want.txt; then ok; else bad "the launcher alone printed another version"; fi
run 2 generator -H 'p^2/2'
err_has "cannot find the commands' module"
HAMLIE=$HAMLIE_SAVED

# ---- a long run compiles (libgccjit loaded then); without it, same numbers ----
RUN=(run -H '(p^2+x^2)/2' --scheme verlet --dt 0.001 --t 1000 --init x=1,p=0 --no-reference --json --quiet)
# only where libgccjit is installed and built in; the trace shows it
gccjit_here=0
ldconfig -p 2>/dev/null | grep -q 'libgccjit\.so\.0' &&
    ! grep -qs 'HAMLIE_GCCJIT:BOOL=OFF' "$(dirname "$HAMLIE")/CMakeCache.txt" && gccjit_here=1
# an empty cache of compiled code (docs/architecture.md): the first run compiles
export HAMLIE_CACHE_DIR=$tmp/jit-cache
traced 0 "${RUN[@]}"
grep -v '"wall_time_s"' "$tmp/out" >native.json
if [ $gccjit_here = 1 ]; then
    yes_loaded 'libgccjit' "a run of 10^6 steps"
    if grep -q 'note:' "$tmp/err"; then bad "a note with libgccjit installed: $(cat "$tmp/err")"; else ok; fi
    # the second run finds the code in the cache: libgccjit is not loaded at all
    traced 0 "${RUN[@]}"
    not_loaded 'libgccjit' "a second run of 10^6 steps (cache warm)"
    grep -v '"wall_time_s"' "$tmp/out" >warm.json
    cmp -s native.json warm.json && ok || bad "the warm run printed other numbers"
fi
# without libgccjit (and without the cache, which would not need it)
HAMLIE_CACHE=off HAMLIE_GCCJIT_LIB=/nonexistent/libgccjit.so.0 run 0 "${RUN[@]}"
grep -v '"wall_time_s"' "$tmp/out" >interpreted.json
if [ -s native.json ] && cmp -s native.json interpreted.json; then ok; else
    bad "without libgccjit the run printed other numbers:"; diff native.json interpreted.json | head >&2; fi
err_has "hamlie: note: /nonexistent/libgccjit.so.0 not found: install libgccjit0"
err_has "running interpreted"

# ---- without PLplot: exit 2, the reason, nothing written ----
"$HAMLIE" run -H '(p^2+x^2)/2' --scheme verlet --dt 0.1 --t 1 --init x=1,p=0 --out osc.csv >/dev/null
HAMLIE_PLPLOT_LIB=/nonexistent/libplplot.so.17 run 2 plot osc.csv --out figs
err_has "/nonexistent/libplplot.so.17 not found: install libplplot17"
if [ -e figs ]; then bad "a failed plot left figs/: $(ls -A figs)"; else ok; fi
HAMLIE_PLPLOT_LIB=/nonexistent/libplplot.so.17 run 2 run -H '(p^2+x^2)/2' --scheme verlet \
    --dt 0.1 --t 1 --init x=1,p=0 --out osc2.csv --plot figs2
err_has "not found: install libplplot17"
if [ -e figs2 ] || [ -e osc2.csv ]; then bad "a failed run --plot left figs2/ or osc2.csv"; else ok; fi
traced 0 plot osc.csv --out figs3 # and with PLplot: loaded, drawn
yes_loaded 'libplplot' "plot"
if [ -s figs3/phase-x-p.png ]; then ok; else bad "plot wrote no figs3/phase-x-p.png"; fi

finish
