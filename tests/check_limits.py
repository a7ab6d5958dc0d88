#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The size limits of the developers' guide, kept by the suite: a source file under 600 lines, a room (a .cpp
and its header of the same stem in the same module, e.g. core/threshold/src/blobs.cpp with
core/threshold/include/colortrack/blobs.hpp, or gst/trackpublish/x.cpp with x.h) under 600 lines together, a
function under 80 lines (120 in tests/), and so is a table initialiser (a variable's extent); no GStreamer or
GLib include in core/ and no GStreamer include in robot/ or publish/. Function and variable extents come from
Universal Ctags (Debian: universal-ctags); without it the check says SKIPPED (exit code 77).

    check_limits.py SOURCE_ROOT

Anything listed in KNOWN with its size may stay over a limit while it does not grow;
anything else over a limit is a breach. Exit code 1 with one line per breach.
"""
import json
import re
import os
import shutil
import subprocess
import sys

FILE_LIMIT = 600
FUNCTION_LIMIT, TEST_FUNCTION_LIMIT = 80, 120
FOLDERS = ("core", "robot", "publish", "gst", "tests", "examples", "tools")
HEADERS, BODIES = (".hpp", ".h"), (".cpp", ".c")
SUFFIXES = (".cpp", ".hpp", ".h", ".c", ".py")

# What may stay over a limit for now: path or path:function -> its lines (it may shrink, not grow).
KNOWN = {}  # empty: a breach must be fixed, not listed


def sources(root):
    found = []
    for folder in FOLDERS:
        for directory, subdirs, files in os.walk(os.path.join(root, folder)):
            subdirs[:] = [d for d in subdirs if d not in ("node_modules", "__pycache__")]
            found += [os.path.join(directory, f) for f in files
                      if f.endswith(SUFFIXES) or is_script(os.path.join(directory, f))]
    return sorted(found)


def is_script(path):
    """A program without a suffix (tools/studio/colortrack-studio): ctags knows it by its #! line."""
    if os.path.splitext(path)[1] or not os.access(path, os.X_OK):
        return False
    with open(path, "rb") as f:
        return f.readline().startswith(b"#!/usr/bin/python3")


def room_of(relative):
    """A C or C++ file's room: its module's folder (src/ and include/colortrack/ or include/ taken off) and its
    stem; None for other files."""
    directory, name = os.path.split(relative)
    stem, suffix = os.path.splitext(name)
    if suffix not in HEADERS + BODIES:
        return None
    for tail in ("/include/colortrack", "/include", "/src"):
        if directory.endswith(tail):
            directory = directory[: -len(tail)]
            break
    return f"{directory}/{stem}"


def measurements(root, paths):
    """(key, lines, limit) for every file, every room of more than one file, every function and every
    variable (a table's initialiser)."""
    rooms = {}  # room -> [(relative path, lines)]
    for path in paths:
        relative = os.path.relpath(path, root)
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = sum(1 for _ in f)
        yield relative, lines, FILE_LIMIT
        room = room_of(relative)
        if room is not None:
            rooms.setdefault(room, []).append((relative, lines))
    for room, members in sorted(rooms.items()):
        has_body = any(p.endswith(BODIES) for p, _ in members)
        has_header = any(p.endswith(HEADERS) for p, _ in members)
        if has_body and has_header:
            yield f"{room} (room: {' + '.join(p for p, _ in members)})", sum(n for _, n in members), FILE_LIMIT
    tags = subprocess.run(["ctags", "--kinds-c++=fv", "--kinds-c=fv", "--kinds-python=fm", "--fields=+ne",
                           "--output-format=json", "-o", "-"] + paths, capture_output=True, text=True, check=True)
    for line in tags.stdout.splitlines():
        tag = json.loads(line)
        if tag.get("_type") != "tag" or "end" not in tag:
            continue
        relative = os.path.relpath(tag["path"], root)
        limit = TEST_FUNCTION_LIMIT if relative.startswith("tests/") else FUNCTION_LIMIT
        yield f"{relative}:{tag['name']}", tag["end"] - tag["line"] + 1, limit


# The tracking core knows nothing of GStreamer (nor of GLib, which the elements' glue uses); the robot
# library knows nothing of GStreamer (its UDP port uses GIO), nor does the publish library (GLib validates
# UTF-8 there).
FOREIGN_INCLUDES = {
    "core": re.compile(r'^\s*#\s*include\s*[<"](gst/|glib|gio/|glib-object)'),
    "robot": re.compile(r'^\s*#\s*include\s*[<"]gst/'),
    "publish": re.compile(r'^\s*#\s*include\s*[<"]gst/'),
}


def foreign_includes(root, paths):
    """A breach for each GStreamer or GLib include in a GStreamer-free folder."""
    for path in paths:
        relative = os.path.relpath(path, root)
        foreign = FOREIGN_INCLUDES.get(relative.split("/")[0])
        if foreign is None:
            continue
        with open(path, encoding="utf-8", errors="replace") as f:
            for number, line in enumerate(f, 1):
                if foreign.match(line):
                    yield f"{relative}:{number}: an include {relative.split('/')[0]}/ must not have: {line.strip()}"


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    if not shutil.which("ctags"):
        print("SKIPPED: Universal Ctags is missing (Debian: universal-ctags)")
        return 77
    breaches, over = [], 0
    for key, lines, limit in measurements(root, sources(root)):
        if lines < limit:  # "under" the limit
            continue
        over += 1
        known = KNOWN.get(key)
        if known is None:
            breaches.append(f"{key}: {lines} lines, over the limit of {limit}")
        elif lines > known:
            breaches.append(f"{key}: {lines} lines, grew past the {known} it was allowed to keep")
    breaches += list(foreign_includes(root, sources(root)))
    print(f"{over} over a limit, {len(KNOWN)} known; {len(breaches)} breach(es)")
    for breach in breaches:
        print("FAIL:", breach)
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
