#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The include layers, kept by the suite (test include-layers).

The folders are floors, each on the ones below: core/ (the tracker) < robot/ (control laws, protocols,
links) < gst/ (the elements). Inside a folder, a module is a source file with its header (one stem: x.cpp
and x.h or colortrack/x.hpp); its floor is one above the highest module it includes, and a module on floor 0
includes none. A breach: an include from a lower folder up to a higher one, or modules that include each
other (a circle, so no floor can be told). Prints each folder's floors and exits 1 on a breach.

    check_layers.py SOURCE_ROOT [--verbose]
"""
import os
import re
import sys
from collections import defaultdict

FOLDERS = ("core", "robot", "gst")  # bottom to top
SUFFIXES = (".cpp", ".hpp", ".h")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def modules(root):
    """{(folder, stem): [paths]} for every source file of the layered folders."""
    found = defaultdict(list)
    for folder in FOLDERS:
        for directory, _, files in os.walk(os.path.join(root, folder)):
            for f in files:
                if f.endswith(SUFFIXES):
                    found[(folder, os.path.splitext(f)[0])].append(os.path.join(directory, f))
    return found


def resolve(include, folder, found):
    """The module an include names: in the including folder first, then in the others (a colortrack/x.hpp
    header may be core's or robot's)."""
    stem = os.path.splitext(os.path.basename(include))[0]
    for f in (folder,) + FOLDERS:
        if (f, stem) in found:
            return (f, stem)
    return None  # a system or generated header


def graph(root):
    found = modules(root)
    edges = defaultdict(dict)  # module -> {included module: "path:line"}
    for module, paths in found.items():
        for path in paths:
            text = open(path, encoding="utf-8", errors="replace").read()
            for m in INCLUDE.finditer(text):
                target = resolve(m.group(1), module[0], found)
                if target and target != module:
                    line = text.count("\n", 0, m.start()) + 1
                    edges[module].setdefault(target, f"{os.path.relpath(path, root)}:{line}")
    return found, edges


def circles(nodes, edges):
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return out


def floors(nodes, edges):
    """Each module's floor inside its folder (a graph without circles)."""
    floor = {}

    def of(v):
        if v not in floor:
            floor[v] = 0
            below = [of(w) for w in edges[v] if w[0] == v[0]]
            floor[v] = 1 + max(below) if below else 0
        return floor[v]

    for v in nodes:
        of(v)
    return floor


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    root = args[0] if args else "."
    nodes, edges = graph(root)
    breaches = []
    for module, targets in edges.items():
        for target, where in targets.items():
            if FOLDERS.index(target[0]) > FOLDERS.index(module[0]):
                breaches.append(f"{where}: {module[0]}/ includes {target[0]}/'s {target[1]}, a floor above it")
    found_circles = circles(nodes, edges)
    for circle in found_circles:
        members = set(circle)
        closing = [where for m in circle for t, where in edges[m].items() if t in members]
        breaches.append("modules include each other: " + ", ".join(f"{f}/{s}" for f, s in circle) +
                        " (includes: " + ", ".join(sorted(closing)) + ")")
    if not found_circles:
        floor = floors(nodes, edges)
        for folder in FOLDERS:
            mine = {m: f for m, f in floor.items() if m[0] == folder}
            print(f"{folder}/: {len(mine)} modules on {max(mine.values()) + 1} floors")
            if "--verbose" in sys.argv:
                for level in range(max(mine.values()) + 1):
                    print(f"  floor {level}: " + " ".join(sorted(s for (_, s), f in mine.items() if f == level)))
    for breach in breaches:
        print("FAIL:", breach)
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
