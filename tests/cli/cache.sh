#!/bin/bash
# The disk cache of compiled code, through hamlie run (Kepler, the adaptive
# Taylor integrator): a cold run compiles and keeps the recursion, a warm
# run loads it (HAMLIE_JIT_VERBOSE says which; no compilation) and prints
# the same bytes, also for a run far too short to compile on its own; the
# interpreter (HAMLIE_CACHE=off) prints them too.  A truncated, zeroed or
# foreign object and a key file that differs: recompiled, same output.
# Two processes on an empty cache: both right.  A directory that cannot be
# made: the run works, one notice.  All in a temporary HAMLIE_CACHE_DIR.
# Kept code is not loaded for a run of a few steps, whose load would cost
# more than it saves.
# `hamlie cache`: the directory, entries and size (counted against ls and
# stat); --clear removes hamlie's files only, leaves a temporary of a
# running writer, and a run after it compiles again with the same bytes.
# usage (from the repo root): bash tests/cli/cache.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: cache.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

export HAMLIE_CACHE_DIR=$tmp/cache HAMLIE_JIT_VERBOSE=1
unset HAMLIE_CACHE HL_JIT_FLAGS HL_CC
KEPLER=(-H '(px^2+py^2)/2-1/sqrt(x^2+y^2)' --init 'x=0.5,y=0,px=0,py=sqrt(3)'
        --scheme lie --tol 1e-15)
# 110 000 Taylor steps: enough to compile on a first run with a cache
LONG=(--t 2e4 --dt 2000)
# 2 700 steps: far too few to compile for, but past the flow's probe of
# 1000 steps (flow.h: HL_FLOW_NATIVE_PROBE), after which it decides
SHORT=(--t 500 --dt 50)

same_as() { # same_as FILE: the last stdout is FILE's bytes
    if cmp -s "$tmp/out" "$1"; then ok; else bad "output differs from $1"; fi
}
no_err() { # no_err TEXT
    if grep -qF -- "$1" "$tmp/err"; then bad "'$1' in stderr:"; sed 's/^/    /' "$tmp/err" >&2; else ok; fi
}
count() { ls "$HAMLIE_CACHE_DIR" 2>/dev/null | grep -c -- "$1"; }

# ---- the interpreter's output, the reference --------------------------------
HAMLIE_CACHE=off run 0 run "${KEPLER[@]}" "${SHORT[@]}"
cp "$tmp/out" "$tmp/short.csv"
no_err "jit:"
[ ! -e "$HAMLIE_CACHE_DIR" ] && ok || bad "HAMLIE_CACHE=off made $HAMLIE_CACHE_DIR"
HAMLIE_CACHE=off run 0 run "${KEPLER[@]}" "${LONG[@]}"
cp "$tmp/out" "$tmp/long.csv"

# ---- cold, then warm ------------------------------------------------------------
run 0 run "${KEPLER[@]}" "${LONG[@]}"
same_as "$tmp/long.csv"
err_has "the recursion: compiled"
[ "$(count '\.so$')" = 1 ] && [ "$(count '\.key$')" = 1 ] && ok || bad "not one entry: $(ls "$HAMLIE_CACHE_DIR")"
[ "$(count tmp)" = 0 ] && ok || bad "temporary files left: $(ls "$HAMLIE_CACHE_DIR")"
run 0 run "${KEPLER[@]}" "${LONG[@]}"
same_as "$tmp/long.csv"
err_has "the recursion: loaded from the cache"
no_err "compiled"
# a short run: native from the cache too, the interpreter's bytes
run 0 run "${KEPLER[@]}" "${SHORT[@]}"
same_as "$tmp/short.csv"
err_has "the recursion: loaded from the cache"

# 57 steps: the load would cost more than it saves, interpreted (the load
# of a run shorter than the probe: flow/t-flow)
HAMLIE_CACHE=off run 0 run "${KEPLER[@]}" --t 3 --dt 1
cp "$tmp/out" "$tmp/tiny.csv"
run 0 run "${KEPLER[@]}" --t 3 --dt 1
same_as "$tmp/tiny.csv"
no_err "jit:"

# ---- hamlie cache: what it holds ---------------------------------------------
hamlie_bytes() { # the size of hamlie's files in the cache, by stat
    find "$HAMLIE_CACHE_DIR" -maxdepth 1 -type f -regextype posix-extended \
        -regex '.*/[0-9a-f]{16}\.(key|so)(\.tmp[0-9]+\..{6})?' -printf '%s\n' |
        awk '{s += $1} END {print s + 0}'
}
run 0 cache
has_line "directory: $HAMLIE_CACHE_DIR"
has_text "entries: 1 entry, 2 files, "
run 0 cache --json
want_bytes=$(hamlie_bytes)
python3 - "$tmp/out" "$HAMLIE_CACHE_DIR" "$want_bytes" <<'PY' && ok || bad "cache --json: $(cat "$tmp/out")"
import json, sys
d = json.load(open(sys.argv[1]))
assert d == {"command": "cache", "directory": sys.argv[2], "exists": True, "cleared": False,
             "entries": 1, "files": 2, "bytes": int(sys.argv[3])}, d
PY
HAMLIE_CACHE=off run 0 cache --json
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["directory"] is None and d["entries"] == 0' "$tmp/out" && ok || bad "cache off: $(cat "$tmp/out")"
HAMLIE_CACHE_DIR=$tmp/none run 0 cache
has_line "directory: $tmp/none (not made yet)"
[ ! -e "$tmp/none" ] && ok || bad "hamlie cache made the directory"
run 2 cache --latex
run 2 cache extra
run 2 cache -H 'p^2/2'

# ---- hamlie cache --clear: hamlie's files only --------------------------------
so1=$(ls "$HAMLIE_CACHE_DIR"/*.so)
echo mine >"$HAMLIE_CACHE_DIR/notes.txt"
: >"$HAMLIE_CACHE_DIR/0123456789abcdef.txt"
sleep 1000 &
writer=$!
: >"$HAMLIE_CACHE_DIR/0123456789abcdef.so.tmp$writer.AbC123" # a running writer's
: >"$HAMLIE_CACHE_DIR/0123456789abcdef.so.tmp999999999.XyZ789" # a writer long gone
want_bytes=$(hamlie_bytes) # the temporaries are empty
run 0 cache --clear --json
python3 - "$tmp/out" "$want_bytes" <<'PY' && ok || bad "cache --clear --json: $(cat "$tmp/out")"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["cleared"] is True and d["entries"] == 1 and d["files"] == 3, d
assert d["bytes"] == int(sys.argv[2]), d
PY
[ ! -e "$so1" ] && [ "$(count '\.key$')" = 0 ] && ok || bad "entry left: $(ls "$HAMLIE_CACHE_DIR")"
[ -e "$HAMLIE_CACHE_DIR/notes.txt" ] && [ -e "$HAMLIE_CACHE_DIR/0123456789abcdef.txt" ] && ok || bad "a file not hamlie's was removed"
[ -e "$HAMLIE_CACHE_DIR/0123456789abcdef.so.tmp$writer.AbC123" ] && ok || bad "a running writer's temporary was removed"
[ ! -e "$HAMLIE_CACHE_DIR/0123456789abcdef.so.tmp999999999.XyZ789" ] && ok || bad "a dead writer's temporary was left"
kill $writer
wait $writer 2>/dev/null
run 0 cache
has_text "entries: 0 entries, 1 file, 0 bytes" # its writer gone: stale
run 0 cache --clear
has_text "removed: 0 entries, 1 file, 0 bytes"
rm -f "$HAMLIE_CACHE_DIR/notes.txt" "$HAMLIE_CACHE_DIR/0123456789abcdef.txt"
run 0 cache
has_text "entries: 0 entries, 0 files, 0 bytes"
# after --clear: compiled again, the same bytes
run 0 run "${KEPLER[@]}" "${LONG[@]}"
same_as "$tmp/long.csv"
err_has "the recursion: compiled"
# a clear while a run compiles: the run ends right, whichever wins
rm -rf "$HAMLIE_CACHE_DIR"
"$HAMLIE" run "${KEPLER[@]}" "${LONG[@]}" >"$tmp/c.csv" 2>"$tmp/c.err" &
pc=$!
for _ in 1 2 3 4 5 6 7 8 9 10; do "$HAMLIE" cache --clear >/dev/null 2>&1; sleep 0.05; done
wait $pc && ok || bad "a run during --clear failed: $(cat "$tmp/c.err")"
cmp -s "$tmp/c.csv" "$tmp/long.csv" && ok || bad "a run during --clear printed other bytes"
run 0 run "${KEPLER[@]}" "${LONG[@]}"
same_as "$tmp/long.csv"

# ---- damaged entries: recompiled, same output --------------------------------
so=$(ls "$HAMLIE_CACHE_DIR"/*.so)
key=$(ls "$HAMLIE_CACHE_DIR"/*.key)
damage() { # damage HOW: the entry's object or key spoilt
    case $1 in
    truncated) truncate -s 4000 "$so" ;;
    zeroed) size=$(stat -c %s "$so"); head -c "$size" /dev/zero >"$so" ;;
    foreign) cp "$(ls /usr/lib/x86_64-linux-gnu/libm.so.6 /lib*/libm.so.6 2>/dev/null | head -1)" "$so" ;;
    key) sed -i '1s/.*/hamlie jit cache 0/' "$key" ;;
    esac
}
for how in truncated zeroed foreign key; do
    damage $how
    run 0 run "${KEPLER[@]}" "${LONG[@]}" # long: a changed key is a miss
    same_as "$tmp/long.csv"
    err_has "the recursion: compiled"
    run 0 run "${KEPLER[@]}" "${SHORT[@]}" # repaired
    err_has "the recursion: loaded from the cache"
done

# ---- two processes on an empty cache ----------------------------------------
rm -rf "$HAMLIE_CACHE_DIR"
"$HAMLIE" run "${KEPLER[@]}" "${LONG[@]}" >"$tmp/a.csv" 2>"$tmp/a.err" &
pa=$!
"$HAMLIE" run "${KEPLER[@]}" "${LONG[@]}" >"$tmp/b.csv" 2>"$tmp/b.err" &
pb=$!
wait $pa && ok || bad "first concurrent run failed: $(cat "$tmp/a.err")"
wait $pb && ok || bad "second concurrent run failed: $(cat "$tmp/b.err")"
cmp -s "$tmp/a.csv" "$tmp/long.csv" && cmp -s "$tmp/b.csv" "$tmp/long.csv" && ok || bad "concurrent outputs differ"
[ "$(count tmp)" = 0 ] && ok || bad "temporary files left: $(ls "$HAMLIE_CACHE_DIR")"
run 0 run "${KEPLER[@]}" "${SHORT[@]}"
err_has "the recursion: loaded from the cache"

# ---- a directory that cannot be made: runs, says so once ----------------------
: >"$tmp/file"
HAMLIE_CACHE_DIR=$tmp/file/cache run 0 run "${KEPLER[@]}" "${LONG[@]}"
same_as "$tmp/long.csv"
err_has "cannot use the cache directory $tmp/file/cache"
[ "$(grep -c 'cannot use the cache' "$tmp/err")" = 1 ] && ok || bad "the notice not once"

finish
