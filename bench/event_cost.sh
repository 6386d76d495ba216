#!/bin/bash
# Benchmark (issue 15 parts 1 and 3): what locating crossings costs the
# adaptive Taylor run.  Henon-Heiles at E = 1/8 from x = 0, y = 0.1, to
# t = 2000 at tol 1e-13 (1001 rows), without an event and with x = 0
# upwards; instructions counted by callgrind (the machine is shared: wall
# times are noise), after a first run that fills the compiled-code cache.
# usage: bash bench/event_cost.sh path/to/hamlie [another/hamlie ...]
set -u
HH='(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3'
RUN=(run -H "$HH" --scheme lie --tol 1e-13 --t 2000
     --init x=0,y=0.1,px=0.49057789051960615,py=0 --out /dev/null)
instr() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null |
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
for h in "$@"; do
    "$h" "${RUN[@]}" >/dev/null 2>&1
    "$h" "${RUN[@]}" --event x --direction up >/dev/null 2>&1
    a=$(instr "$h" "${RUN[@]}")
    b=$(instr "$h" "${RUN[@]}" --event x --direction up)
    echo "$h: no event $a instructions, with x = 0 up $b: +$(( (b - a) * 1000 / a / 10 )).$(( (b - a) * 1000 / a % 10 )) %"
done
