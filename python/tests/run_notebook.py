"""Execute a notebook headless (Debian's python3-nbclient) with the build
tree's hamlie (PYTHONPATH, set by CTest) and fail on the first cell that
raises.  The executed copy goes to a temporary directory; the notebook in the
repository stays without outputs."""
import os
import sys
import tempfile

import nbformat
from nbclient import NotebookClient


def main(path):
    # the kernel runs in a temporary directory: a relative PYTHONPATH must not break
    os.environ["PYTHONPATH"] = os.pathsep.join(
        os.path.abspath(d) for d in os.environ.get("PYTHONPATH", "").split(os.pathsep) if d)
    nb = nbformat.read(path, as_version=4)
    with tempfile.TemporaryDirectory() as tmp:
        client = NotebookClient(nb, timeout=600, kernel_name="python3",
                                resources={"metadata": {"path": tmp}})
        client.execute()
        nbformat.write(nb, os.path.join(tmp, os.path.basename(path)))
    cells = sum(c.cell_type == "code" for c in nb.cells)
    print(f"{path}: {cells} code cells ran without error")


if __name__ == "__main__":
    main(sys.argv[1])
