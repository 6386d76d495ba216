#!/usr/bin/env python3
"""Calls between the .c files of src/, and the circles among them.

Reads the symbol tables of the library's object files (nm): a file that
uses a symbol another file defines depends on that file.  Files that
depend on each other, directly or through others, form a circle (a
strongly connected component of more than one file); each circle is
printed with the symbols that carry its edges, so one can see which
function to move.  Exit status 1 if there is a circle, 0 if none.

    scripts/file-deps.py [build-dir]          # circles only
    scripts/file-deps.py [build-dir] --edges  # and every edge

Why nm and not parsing: the object files know exactly which function a
file defines and which it calls, after the preprocessor and without a C
parser; static functions and static inline helpers in headers do not
appear, and they cannot make a circle between files anyway.
Python 3 standard library only.
"""
import os
import subprocess
import sys


def object_files(build):
    """{path of the .c under src/: path of its .o}, from every target of the
    build (the library and the command line; not the tests)."""
    root = os.path.join(build, "CMakeFiles")
    found = {}
    for target in sorted(os.listdir(root)):
        tdir = os.path.join(root, target)
        for d, _, files in os.walk(tdir):
            for f in files:
                rel = os.path.relpath(os.path.join(d, f[: -len(".o")]), tdir)
                if f.endswith(".c.o") and rel.startswith("src" + os.sep) and \
                        os.sep + "test" + os.sep not in rel:
                    found.setdefault(rel, os.path.join(d, f))
    if not found:
        sys.exit(f"file-deps: no object files of src/ under {root} (build first)")
    return found


def symbols(obj):
    """(defined, used): the external symbols the object file defines and needs."""
    out = subprocess.run(
        ["nm", "-P", "--no-sort", obj], capture_output=True, text=True, check=True
    ).stdout
    defined, used = set(), set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) < 2:
            continue
        name, kind = parts[0], parts[1]
        if kind == "U":
            used.add(name)
        elif kind in "TDBRVWC":  # upper case: external definitions only
            defined.add(name)
    return defined, used


def dependency_graph(objs):
    """{file: {file it uses: sorted symbols}}."""
    defs, uses = {}, {}
    for src, obj in objs.items():
        d, u = symbols(obj)
        uses[src] = u
        for s in d:
            defs[s] = src
    graph = {src: {} for src in objs}
    for src, used in uses.items():
        for s in used:
            to = defs.get(s)
            if to is not None and to != src:
                graph[src].setdefault(to, []).append(s)
    for edges in graph.values():
        for syms in edges.values():
            syms.sort()
    return graph


def circles(graph):
    """Strongly connected components with more than one file (Tarjan)."""
    index, low, on, stack, comps = {}, {}, set(), [], []
    counter = [0]

    def visit(v):  # iterative: deep call chains would pass Python's limit
        work = [(v, iter(sorted(graph[v])))]
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        while work:
            node, it = work[-1]
            nxt = next(it, None)
            if nxt is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    comp = []
                    while True:
                        w = stack.pop()
                        on.discard(w)
                        comp.append(w)
                        if w == node:
                            break
                    if len(comp) > 1:
                        comps.append(sorted(comp))
            elif nxt not in index:
                index[nxt] = low[nxt] = counter[0]
                counter[0] += 1
                stack.append(nxt)
                on.add(nxt)
                work.append((nxt, iter(sorted(graph[nxt]))))
            elif nxt in on:
                low[node] = min(low[node], index[nxt])

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return comps


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    build = args[0] if args else "build"
    graph = dependency_graph(object_files(build))
    if "--edges" in argv:
        for src in sorted(graph):
            for to, syms in sorted(graph[src].items()):
                print(f"{src} -> {to}: {' '.join(syms)}")
    comps = circles(graph)
    for comp in comps:
        print("circle: " + " ".join(comp))
        members = set(comp)
        for src in comp:
            for to, syms in sorted(graph[src].items()):
                if to in members:
                    print(f"  {src} -> {to}: {' '.join(syms)}")
    if not comps:
        print(f"no circles among {len(graph)} files")
    return 1 if comps else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
