#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The size limits of the developers' guide, kept by the suite: a source file under 600 lines, a function
under 80 lines (120 in tests/), no GStreamer or GLib include in core/ and no GStreamer include in robot/. Function extents come from
Universal Ctags (Debian: universal-ctags); without it the check says SKIPPED (exit code 77).

    check_limits.py SOURCE_ROOT

Anything listed in KNOWN with its size may stay over a limit while it does not grow (the list is empty now);
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
FOLDERS = ("core", "robot", "gst", "tests", "examples")
SUFFIXES = (".cpp", ".hpp", ".h", ".c", ".py")

# What may stay over a limit for now: path or path:function -> its lines (it may shrink, not grow).
KNOWN = {}  # empty since issue 24's splits; a breach must be fixed, not listed


def sources(root):
    found = []
    for folder in FOLDERS:
        for directory, subdirs, files in os.walk(os.path.join(root, folder)):
            subdirs[:] = [d for d in subdirs if d not in ("node_modules", "__pycache__")]
            found += [os.path.join(directory, f) for f in files if f.endswith(SUFFIXES)]
    return sorted(found)


def measurements(root, paths):
    """(key, lines, limit) for every file and every function."""
    for path in paths:
        with open(path, encoding="utf-8", errors="replace") as f:
            yield os.path.relpath(path, root), sum(1 for _ in f), FILE_LIMIT
    tags = subprocess.run(["ctags", "--kinds-c++=f", "--kinds-c=f", "--kinds-python=fm", "--fields=+ne",
                           "--output-format=json", "-o", "-"] + paths, capture_output=True, text=True, check=True)
    for line in tags.stdout.splitlines():
        tag = json.loads(line)
        if tag.get("_type") != "tag" or "end" not in tag:
            continue
        relative = os.path.relpath(tag["path"], root)
        limit = TEST_FUNCTION_LIMIT if relative.startswith("tests/") else FUNCTION_LIMIT
        yield f"{relative}:{tag['name']}", tag["end"] - tag["line"] + 1, limit


# The tracking core knows nothing of GStreamer (nor of GLib, which the elements' glue uses); the robot
# library knows nothing of GStreamer (its UDP port uses GIO).
FOREIGN_INCLUDES = {
    "core": re.compile(r'^\s*#\s*include\s*[<"](gst/|glib|gio/|glib-object)'),
    "robot": re.compile(r'^\s*#\s*include\s*[<"]gst/'),
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
