#!/bin/bash
# Build hamlie's fuzz targets with clang and libFuzzer (ASan and UBSan on)
# and run each for a number of executions; print each target's executions
# and the crashes found.  A crash's input is left in build-fuzz/crashes/.
#   usage: scripts/fuzz.sh [RUNS] [TARGET...]   (default 1000000, every target)
#   FUZZ_SECONDS=N stops each target after N seconds as well (0: no limit).
# The corpus in fuzz/corpus/<target> seeds each run; new inputs go to a
# scratch copy.  To fold useful ones back, minimised:
#   build-fuzz/fuzz_<t> -merge=1 fuzz/corpus/<t>.new fuzz/corpus/<t> <scratch>
set -eu
cd "$(dirname "$0")/.."
runs=${1:-1000000}
shift || true
build=build-fuzz
CC=clang cmake -S . -B "$build" -DHAMLIE_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    for f in fuzz/fuzz_*.c; do t=$(basename "$f" .c); targets+=("${t#fuzz_}"); done
fi
cmake --build "$build" -j2 --target "${targets[@]/#/fuzz_}" >/dev/null
mkdir -p "$build/crashes"
status=0
for t in "${targets[@]}"; do
    scratch="$build/corpus-$t"
    mkdir -p "$scratch"
    cp -n fuzz/corpus/"$t"/* "$scratch"/ 2>/dev/null || true
    log="$build/fuzz-$t.log"
    # in-process, so one core (-jobs=1 would do the same in a child writing
    # fuzz-0.log to the current directory); inputs up to 4 KiB, 10 s an
    # input, 2 GiB of memory
    if ! "$build/fuzz_$t" "$scratch" -runs="$runs" -max_len=4096 -timeout=10 \
        -rss_limit_mb=2048 -max_total_time="${FUZZ_SECONDS:-0}" -print_final_stats=1 \
        -artifact_prefix="$build/crashes/$t-" >"$log" 2>&1; then
        status=1
    fi
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
    crashes=$(ls "$build/crashes" | grep -c "^$t-" || true)
    echo "$t: $execs executions, $crashes crash inputs (log $log)"
done
exit $status
