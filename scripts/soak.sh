#!/usr/bin/env bash
# The harness of tests/zoo with many more random Hamiltonians and initial
# points, every applicable scheme on every system, and mpmath's ODE solver
# as one more truth, for a given time; prints the counts (systems, cases,
# cross-checks passed and failed, crashes, hangs). Each run draws a new
# seed unless one is given; a failure prints the command that reproduces it.
# usage: scripts/soak.sh [minutes (default 30)] [seed] [build dir (default build)]
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-30}
seed=${2:-$(date +%s)}
build=${3:-build}
if [ ! -x "$build/hamlie" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build "$build" -j"$(nproc 2>/dev/null || echo 2)" --target hamlie_cli
fi
echo "soak: $minutes minutes, seed $seed, $build/hamlie"
exec python3 tests/zoo/driver.py "$build/hamlie" --seed "$seed" \
  --minutes "$minutes" --points 6 --random 1000000 --all-schemes --ode \
  --run-known-hangs
