#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The include layers, kept by the suite (test include-layers).

The folders are layers, each on the ones below:

    core/maths (boxes, tracks, Kalman)  <  core/images (pixel formats, colour, histograms, the tracker interface)
      <  core/threshold (blobs), core/template (the histogram tracker and its methods)
      <  robot/ (control laws, protocols, links), publish/ (trackpublish's file and MQTT outputs)
      <  gst/ (the elements)

Folders on one layer (threshold and template; robot and publish) know nothing of each other. Inside a folder, a module is a source file with its header (one stem: x.cpp
and x.h or colortrack/x.hpp); its floor is one above the highest module it includes, and a module on floor 0
includes none. A breach: an include from a lower folder up to a higher one or across to a sibling, a source file of
core/ outside its concept folders, or modules that include each
other (a circle, so no floor can be told). Prints each folder's floors and exits 1 on a breach.

    check_layers.py SOURCE_ROOT [--verbose]
"""
import os
import re
import sys
from collections import defaultdict

# Each layered folder with its layer, bottom to top; folders on one layer may not include each other.
LAYERS = {
    "core/maths": 0,
    "core/images": 1,
    "core/threshold": 2,
    "core/template": 2,
    "robot": 3,
    "publish": 3,
    "gst": 4,
}
FOLDERS = tuple(LAYERS)
ROOTS = ("core", "robot", "publish", "gst")  # walked whole, so that a file outside every folder is seen
SUFFIXES = (".cpp", ".hpp", ".h")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def folder_of(relative):
    """The layered folder a path (relative to the source root) is in, or None."""
    for folder in FOLDERS:
        if relative == folder or relative.startswith(folder + "/"):
            return folder
    return None


def modules(root, strays):
    """{(folder, stem): [paths]} for every source file of the layered folders; the others go to strays."""
    found = defaultdict(list)
    for top in ROOTS:
        for directory, _, files in os.walk(os.path.join(root, top)):
            for f in files:
                if f.endswith(SUFFIXES):
                    path = os.path.join(directory, f)
                    folder = folder_of(os.path.relpath(path, root))
                    if folder is None:
                        strays.append(os.path.relpath(path, root))
                    else:
                        found[(folder, os.path.splitext(f)[0])].append(path)
    return found


def resolve(include, folder, found):
    """The module an include names: in the including folder first, then in the others (a colortrack/x.hpp
    header may be in any of core's folders or robot's)."""
    stem = os.path.splitext(os.path.basename(include))[0]
    for f in (folder,) + FOLDERS:
        if (f, stem) in found:
            return (f, stem)
    return None  # a system or generated header


def graph(root, strays):
    found = modules(root, strays)
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
    strays = []
    nodes, edges = graph(root, strays)
    breaches = [f"{stray}: in no layered folder ({', '.join(FOLDERS)})" for stray in sorted(strays)]
    for module, targets in edges.items():
        for target, where in targets.items():
            if LAYERS[target[0]] > LAYERS[module[0]]:
                breaches.append(f"{where}: {module[0]}/ includes {target[0]}/'s {target[1]}, a layer above it")
            elif LAYERS[target[0]] == LAYERS[module[0]] and target[0] != module[0]:
                breaches.append(f"{where}: {module[0]}/ includes {target[0]}/'s {target[1]}, a folder beside it")
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
