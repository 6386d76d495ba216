#!/bin/bash
# Issue 15 part 6: `mpirun -np K hamlie sweep ...` spreads the members over
# the ranks and writes ONE file, the same bit for bit as the threaded run
# (cmp), with 1, 2 and 4 ranks (oversubscribed on one machine) and with
# threads in the ranks; a member that fails travels as a row (status and
# reason); mpirun interrupted mid-sweep (SIGINT: it passes SIGTERM on)
# leaves the journal and no file, and --resume under mpirun finishes it to
# the same file; the arrays (--save-every, --event) the same with 4 ranks
# (CSV sidecars) and 2 (HDF5); bad cases say so once and exit 2: the
# plugin missing, a journal left without --resume, a usage error.  Skipped (77) without mpirun or without
# the plugin (hamlie built without MPI).
# usage (from the repo root): bash tests/cli/mpi.sh path/to/hamlie
set -u
HAMLIE=${1:?usage: mpi.sh path/to/hamlie}
. "$(dirname "$0")/lib/harness.sh"

if ! command -v mpirun >/dev/null; then
    echo "SKIP: no mpirun (Debian: openmpi-bin)"
    exit 77
fi
if [ ! -e "$(dirname "$HAMLIE")/hamlie-mpi.so" ]; then
    echo "SKIP: hamlie was built without MPI (no hamlie-mpi.so beside it)"
    exit 77
fi
# as root (containers) mpirun wants to be told; one machine, more ranks than cores
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# under the sanitizers, Open MPI's own leaks (from components it unloads, so
# no suppression can name them) would fail every rank; cli/sweep checks ours
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"

PEND=(sweep -H 'p^2/2 - cos(q)' --grid 'q=-3:3:9,p=-2:2:7' --scheme stormer-verlet-kdk,rk4
      --dt 0.1,0.05 --t 20 --quiet)
# Euler on a quartic well blows up from far out: failed members among good ones
BLOW=(sweep -H 'p^2/2 + q^4' --grid 'q=0.5:6:12,p=0' --scheme euler,stormer-verlet-kdk
      --dt 0.25 --t 50 --quiet)

# mpi WANT_RC NP args...: mpirun -np NP hamlie args..., output in $tmp/out, $tmp/err
mpi() {
    local want=$1 np=$2
    shift 2
    mpirun -np "$np" "$HAMLIE" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -eq "$want" ]; then ok; else
        bad "mpirun -np $np hamlie $* exited $rc, want $want"; sed 's/^/    /' "$tmp/err" >&2
    fi
}

same() { # same FILE REF
    if cmp -s "$1" "$2"; then ok; else bad "$1 differs from $2"; cmp "$1" "$2" | head -2 >&2; fi
}

# ---- the same file with threads and with 1, 2, 4 ranks ---------------------
run 0 "${PEND[@]}" --threads 1 --out "$tmp/ref.csv"
run 0 "${PEND[@]}" --threads 2 --out "$tmp/t2.csv"
same "$tmp/t2.csv" "$tmp/ref.csv"
for np in 1 2 4; do
    mpi 0 "$np" "${PEND[@]}" --threads 1 --out "$tmp/np$np.csv"
    same "$tmp/np$np.csv" "$tmp/ref.csv"
done
mpi 0 2 "${PEND[@]}" --threads 2 --out "$tmp/np2t2.csv"
same "$tmp/np2t2.csv" "$tmp/ref.csv"
# the file has every member: 9 x 7 points, 2 schemes, 2 steps
if [ "$(wc -l <"$tmp/ref.csv")" -eq $((9 * 7 * 2 * 2 + 1)) ]; then ok; else
    bad "ref.csv: $(wc -l <"$tmp/ref.csv") lines, want $((9 * 7 * 2 * 2 + 1))"; fi
# --mpi forces the plugin without a launcher (Open MPI's singleton)
run 0 "${PEND[@]}" --mpi --threads 1 --out "$tmp/single.csv"
same "$tmp/single.csv" "$tmp/ref.csv"

# ---- the arrays (--save-every, --event): the same sidecars -----------------
ARR=(--save-every 50 --event 'q = 0' --direction up)
run 0 "${PEND[@]}" "${ARR[@]}" --threads 1 --out "$tmp/arr.csv"
mpi 0 4 "${PEND[@]}" "${ARR[@]}" --threads 1 --out "$tmp/arr4.csv"
for f in arr4.csv arr4-traj.csv arr4-cross.csv; do same "$tmp/$f" "$tmp/arr${f#arr4}"; done
if [ "$(wc -l <"$tmp/arr-cross.csv")" -gt 100 ]; then ok; else bad "few crossings in arr-cross.csv"; fi

# ---- a usage error is said once, by rank 0, with every rank's status ------
mpi 2 2 "${PEND[@]}" --save-every 0 --out "$tmp/usage.csv"
if [ "$(grep -c "save-every" "$tmp/err")" -eq 1 ]; then ok; else
    bad "want the usage error once"; sed 's/^/    /' "$tmp/err" >&2; fi

# ---- failed members are rows, with their reasons --------------------------
run 1 "${BLOW[@]}" --threads 1 --out "$tmp/blow-ref.csv"
grep -q "failed" "$tmp/err" && ok || bad "the threaded run names no failed member"
mpi 1 4 "${BLOW[@]}" --threads 1 --out "$tmp/blow4.csv"
same "$tmp/blow4.csv" "$tmp/blow-ref.csv"
if [ "$(grep -c "failed" "$tmp/err")" -ge 1 ]; then ok; else bad "no failed member named"; fi

# ---- mpirun interrupted, then --resume under mpirun ------------------------
# long enough (~3 s of CPU) that the interrupt comes mid-sweep on an idle machine
LONG=(sweep -H 'p^2/2 - cos(q)' --grid 'q=-3:3:24,p=-2:2:20' --scheme stormer-verlet-kdk,rk4
      --dt 0.001,0.0005 --t 20 --quiet)

# interrupted_resume EXT: the LONG sweep to long.EXT under mpirun -np 3,
# interrupted (SIGINT to mpirun) once results are in the journal; then a
# fresh start is refused (said once, by rank 0) and --resume under
# mpirun -np 2 finishes the same file as the threaded run
interrupted_resume() {
    local ext=$1 out=$tmp/long.$1 i
    run 0 "${LONG[@]}" --threads 2 --out "$tmp/long-ref.$ext"
    # a script's background job starts with SIGINT ignored: env gives the default
    env --default-signal=INT mpirun -np 3 "$HAMLIE" "${LONG[@]}" --threads 1 --out "$out" \
        >"$tmp/out" 2>"$tmp/err" &
    local pid=$!
    for i in $(seq 600); do # a result in (the header is 24 bytes)
        [ "$(stat -c %s "$out.journal" 2>/dev/null || echo 0)" -gt 200 ] && break
        sleep 0.05
    done
    kill -INT "$pid" 2>/dev/null
    for i in $(seq 300); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null
    wait "$pid"
    local rc=$?
    if [ "$rc" -ne 0 ]; then ok; else bad "$ext: mpirun interrupted exited 0 (finished?)"; fi
    if [ ! -e "$out" ] && [ -s "$out.journal" ]; then ok; else
        bad "$ext interrupted: want the journal and no file ($(ls "$tmp"))"
        sed 's/^/    /' "$tmp/err" >&2
    fi
    if ls "$tmp" | grep -q "^long\.$ext..*tmp"; then bad "a temporary file left: $(ls "$tmp")"
    else ok; fi
    mpi 2 2 "${LONG[@]}" --threads 1 --out "$out"
    if [ "$(grep -c "journal" "$tmp/err")" -eq 1 ]; then ok; else
        bad "want one message naming the journal"; sed 's/^/    /' "$tmp/err" >&2; fi
    mpi 0 2 "${LONG[@]}" --threads 1 --out "$out" --resume
    same "$out" "$tmp/long-ref.$ext"
    if [ ! -e "$out.journal" ]; then ok; else bad "the journal outlived the finished sweep"; fi
}
interrupted_resume csv

# ---- HDF5 (when this hamlie writes it): the same bytes too ----------------
if "$HAMLIE" "${PEND[@]}" --threads 2 --out "$tmp/ref.h5" 2>"$tmp/h5err"; then
    for np in 1 4; do
        mpi 0 $np "${PEND[@]}" --threads 1 --out "$tmp/np$np.h5"
        same "$tmp/np$np.h5" "$tmp/ref.h5"
    done
    run 0 "${PEND[@]}" "${ARR[@]}" --threads 2 --out "$tmp/arr.h5"
    mpi 0 2 "${PEND[@]}" "${ARR[@]}" --threads 1 --out "$tmp/arr2.h5"
    same "$tmp/arr2.h5" "$tmp/arr.h5"
    interrupted_resume h5
else
    echo "note: no HDF5 sweep files here: $(head -1 "$tmp/h5err")"
fi

# ---- the plugin missing: a clear error, nothing written ---------------------
HAMLIE_MPI_PLUGIN=/nonexistent/hamlie-mpi.so run 2 "${PEND[@]}" --mpi --out "$tmp/none.csv"
err_has "hamlie-mpi.so"
if [ ! -e "$tmp/none.csv" ]; then ok; else bad "a file written without the plugin"; fi

# ---- not under MPI, the sweep loads no libmpi -------------------------------
LD_DEBUG=libs "$HAMLIE" "${PEND[@]}" --threads 1 --out "$tmp/plain.csv" 2>"$tmp/ld" >/dev/null
if grep -q "libmpi" "$tmp/ld"; then bad "a sweep outside mpirun loaded libmpi"; else ok; fi

finish
