#!/bin/bash
# The differential-testing harness of issue 13 (tests/zoo/): every engine
# against an independent route on the zoo of Hamiltonians and on random
# ones. Smaller under the sanitizers (a build directory named *asan*).
# usage (from the repo root): bash tests/cli/zoo.sh path/to/hamlie [driver options]
set -u
HAMLIE=${1:?usage: zoo.sh path/to/hamlie [driver options]}
shift
exec python3 "$(dirname "$0")/../zoo/driver.py" "$HAMLIE" "$@"
