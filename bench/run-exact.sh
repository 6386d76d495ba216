#!/usr/bin/env bash
# Exact-scheme benchmark (issue 6): one exact pendulum step, its set-up, and
# one step of the Taylor (Lie-series) integrator to the same accuracy.
# Usage: bench/run-exact.sh [build-dir]   (a Release build; default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
cmake --build "$build" --target bench-exact_step >/dev/null
"$build/bench-exact_step"
