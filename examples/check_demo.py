#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Test of the demo (examples/run-demo.sh runs the same binary): 90 frames of the built-in scene in a temporary
directory; the demo must exit 0, track most frames with a mean IoU of at least 0.7, and leave the annotated
video, the robot's commands (robotctl's text protocol, ending with stops) and their log.

    check_demo.py COLORTRACK_DEMO"""
import os
import re
import subprocess
import sys
import tempfile

FRAMES = 90


def main():
    demo = os.path.abspath(sys.argv[1])  # the demo runs in a temporary folder
    with tempfile.TemporaryDirectory(prefix="colortrack-demo-") as directory:
        out = subprocess.run([demo, "--frames", str(FRAMES)], cwd=directory, capture_output=True, text=True,
                             timeout=120)
        sys.stdout.write(out.stdout[-1500:])
        sys.stderr.write(out.stderr[-1500:])
        errors = [] if out.returncode == 0 else [f"colortrack-demo exited with {out.returncode}"]
        iou = re.search(r"mean IoU\s+: ([0-9.]+)", out.stdout)
        tracked = re.search(r"frames tracked\s+: (\d+)", out.stdout)
        if not iou or float(iou.group(1)) < 0.7:
            errors.append(f"mean IoU {iou.group(1) if iou else 'missing'} (at least 0.7)")
        if not tracked or int(tracked.group(1)) < 0.9 * FRAMES:
            errors.append(f"frames tracked: {tracked.group(1) if tracked else 'missing'} of {FRAMES}")
        for name in ("colortrack-demo.avi", "colortrack-demo-robot.txt", "colortrack-demo-robot.log"):
            path = os.path.join(directory, name)
            if not os.path.isfile(path) or os.path.getsize(path) == 0:
                errors.append(f"{name} missing or empty")
        robot = os.path.join(directory, "colortrack-demo-robot.txt")
        if os.path.isfile(robot):
            with open(robot, encoding="ascii", errors="replace") as f:
                lines = f.read().splitlines()
            if not lines or lines[-1] != "L=0 R=0" or all(line == "L=0 R=0" for line in lines):
                errors.append("the robot's commands do not move and then end with stop")
    for e in errors:
        print("FAIL:", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
