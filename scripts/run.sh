#!/usr/bin/env bash
# hamlie's main job on its defaults: install what is needed, build, run.
# Until `hamlie reproduce` exists (issue 7) this runs the §2 demonstration:
# the generator, brackets, integrals, canonicity and Lie series of the paper's
# oscillator and of the systems beyond it.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target hamlie_cli >/dev/null
hamlie=build/hamlie

# Echo a command as a user would type it: quote only what the shell needs quoted.
show() {
  printf '\n$ hamlie'
  for a in "$@"; do
    if [[ $a =~ ^[-A-Za-z0-9_.,:=/+]+$ ]]; then printf ' %s' "$a"; else printf " '%s'" "$a"; fi
  done
  printf '\n'
  "$hamlie" "$@" || true   # exit 1 means "a checked property fails": part of the demo
}

show generator -H '(p^2+x^2)/2'
show generator -H '(px^2+py^2)/2 - 1/sqrt(x^2+y^2)' --latex
show bracket -H '(px^2+py^2)/2 - 1/sqrt(x^2+y^2)' 'x*py - y*px' 'H'
show check -H '(px^2+py^2)/2 - 1/sqrt(x^2+y^2)' --integral 'x*py-y*px' --integral 'py*(x*py-y*px) - x/sqrt(x^2+y^2)'
show canonical --map 'X = x + D*p; P = p - D*x'
show lie -H 'p^2/2 - cos(q)' --order 6
show lie -H '(p^2+x^2)/2' --order 8 --of 'x^2 - p'
