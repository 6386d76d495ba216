#!/usr/bin/env bash
# Install the Debian packages hamlie needs to build, test, plot and benchmark.
# Safe to run again; needs root (or sudo) on Debian 12 or later.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libflint-dev libflint-arb-dev libgmp-dev libmpfr-dev   # exact and high-precision arithmetic
  libplplot-dev plplot-driver-cairo                     # figures (PNG, SVG, PDF)
  python3 python3-sympy                                 # the peer in bench/ (not needed to build)
  libgsl-dev                                            # the peer integrator in bench/
  libgccjit-12-dev                                      # optional: tapes compiled to machine code (hl_tape_jit)
  libhdf5-dev                                           # HDF5 result files (section, sweep); loaded on first use
  python3-dev python3-numpy python3-mpmath python3-pytest  # the Python binding (python/) and its tests
  python3-nbclient python3-ipykernel python3-matplotlib  # the notebook docs/notebooks/tour.ipynb, run headless
  libopenmpi-dev openmpi-bin                            # optional: `mpirun hamlie sweep` (the plugin hamlie-mpi.so)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; fi
echo "installing: ${missing[*]}" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
