#!/usr/bin/env bash
# hamlie's main job on its defaults: install what is needed, build, then
# `hamlie reproduce`, which regenerates the paper's 14 figures and every
# formula, says where the paper's print is right and where it is not, and
# writes the report to out/paper/.  Any arguments are passed to it
# (e.g. --out DIR --format png).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target hamlie_cli >/dev/null

# Exit 1 would mean a figure's data failed its closed-form check: report it.
rc=0
build/hamlie reproduce "$@" || rc=$?
if [ "$rc" -ne 0 ]; then
  echo "hamlie reproduce exited $rc" >&2
  exit "$rc"
fi
