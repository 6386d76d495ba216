"""`pip install --no-build-isolation` of python/ into a fresh virtual
environment (with Debian's site packages: NumPy, SymPy; no network) builds
the extension against the build tree's libhamlie.so, and the installed
package works from another directory."""
import os
import shutil
import subprocess
import sys

import pytest

from conftest import CLI

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(os.path.dirname(HERE))


def test_pip_install(tmp_path):
    build = os.path.dirname(os.path.abspath(CLI))
    if not os.path.exists(os.path.join(build, "libhamlie.so")):
        pytest.skip(f"no libhamlie.so in {build}")
    pkg = tmp_path / "python"  # a copy: pip writes build files beside setup.py
    shutil.copytree(os.path.join(SRC, "python"), pkg,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "tests"))
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    py = str(venv / "bin" / "python")
    env = dict(os.environ, HAMLIE_BUILD_DIR=build, HAMLIE_SOURCE_DIR=SRC, PIP_NO_INDEX="1")
    env.pop("PYTHONPATH", None)  # the build tree's package must not be the one imported
    subprocess.run([py, "-m", "pip", "install", "-q", "--no-build-isolation", str(pkg)],
                   check=True, env=env, cwd=tmp_path)
    code = ("import hamlie, sympy as sp; q, p = sp.symbols('q p');"
            "s = hamlie.System('p^2/2 - cos(q)');"
            "assert s.generator() == {q: p, p: -sp.sin(q)};"
            "r = s.run('rk4', dt=0.1, t=1, init={'q': 1, 'p': 0}); assert len(r.t) == 11;"
            "print(hamlie.__file__)")
    out = subprocess.run([py, "-c", code], check=True, env=env, cwd=tmp_path,
                         capture_output=True, text=True).stdout
    assert str(venv) in out
