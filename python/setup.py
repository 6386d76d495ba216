"""Builds hamlie's extension (_hamlie) for pip: against the build tree's
libhamlie.so (../build or $HAMLIE_BUILD_DIR, headers from ../include) or,
failing that, an installed hamlie (pkg-config hamlie).  The library is linked
as a shared object with its directory as the run path, so the module finds it
without LD_LIBRARY_PATH."""
import os
import shlex
import subprocess

import numpy
from setuptools import Extension, setup

HERE = os.path.dirname(os.path.abspath(__file__))
# the clone: python/.. (or $HAMLIE_SOURCE_DIR when python/ was copied elsewhere)
ROOT = os.environ.get("HAMLIE_SOURCE_DIR", os.path.dirname(HERE))


def build_tree():
    """(include dirs, library dir) of a build tree with libhamlie.so, or None."""
    build = os.environ.get("HAMLIE_BUILD_DIR", os.path.join(ROOT, "build"))
    if os.path.exists(os.path.join(build, "libhamlie.so")) and \
            os.path.isdir(os.path.join(ROOT, "include", "hamlie")):
        return [os.path.join(ROOT, "include")], os.path.abspath(build)
    return None


def installed():
    """(include dirs, library dir) of an installed hamlie (pkg-config)."""
    try:
        cflags = subprocess.check_output(["pkg-config", "--cflags", "hamlie"], text=True)
        libdir = subprocess.check_output(["pkg-config", "--variable=libdir", "hamlie"],
                                         text=True).strip()
    except (OSError, subprocess.CalledProcessError):
        raise SystemExit("hamlie: no libhamlie found: build it first (cmake --build build) "
                         "or install it (cmake --install build) so pkg-config finds it, "
                         "or set HAMLIE_BUILD_DIR")
    incs = [f[2:] for f in shlex.split(cflags) if f.startswith("-I")]
    return incs, os.path.abspath(libdir)


incs, libdir = build_tree() or installed()
# arb.h is in /usr/include on Debian, in include/flint with FLINT 3
incs += [d for d in ("/usr/include/flint",) if os.path.exists(os.path.join(d, "arb.h"))]

ext = Extension(
    "hamlie._hamlie",
    sources=[os.path.join("src", f) for f in ("module.c", "system.c", "analysis.c", "run.c")],
    include_dirs=incs + [numpy.get_include()],
    library_dirs=[libdir],
    runtime_library_dirs=[libdir],
    libraries=["hamlie"],
    extra_compile_args=["-std=gnu17"],
)

setup(ext_modules=[ext])
