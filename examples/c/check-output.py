#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Runs colortrack-app on videotestsrc's ball and checks its output: every line parses, one line per frame,
and the printed box follows the ball, whose centre videotestsrc computes exactly (see ball_centre)."""
import math
import re
import subprocess
import sys

FRAMES = 150
WIDTH, HEIGHT, RADIUS = 320, 240, 20
LINE = re.compile(r"^frame=(\d+) time=(-?[\d.]+) id=(\d+) state=(\w+)"
                  r"(?: x=(\d+) y=(\d+) w=(\d+) h=(\d+) score=([\d.]+) verified=([01]) scale=([\d.]+))?$")


def ball_centre(frame):
    # videotestsrc pattern=ball, animation-mode=frames: a Lissajous path over the frame.
    x = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * frame / 200)) * (WIDTH - 2 * RADIUS)
    y = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * math.sqrt(2) * frame / 200)) * (HEIGHT - 2 * RADIUS)
    return x, y


def main():
    out = subprocess.run([sys.argv[1], "--frames", str(FRAMES)], capture_output=True, text=True, timeout=60)
    sys.stderr.write(out.stderr)
    if out.returncode != 0:
        print(f"colortrack-app exited with {out.returncode}")
        return 1
    lines = out.stdout.splitlines()
    errors, tracked = [], 0
    if len(lines) != FRAMES:
        errors.append(f"{len(lines)} lines for {FRAMES} frames")
    for number, line in enumerate(lines):
        m = LINE.match(line)
        if not m:
            errors.append(f"line {number} does not parse: {line!r}")
            continue
        frame, time = int(m[1]), float(m[2])
        if frame != number or abs(time - frame / 30) > 1e-3:
            errors.append(f"line {number}: frame {frame} at {time} s")
        if m[5] is None:
            continue
        x, y, w, h = (int(m[i]) for i in range(5, 9))
        cx, cy = ball_centre(frame)
        error = math.hypot(x + w / 2 - cx, y + h / 2 - cy)
        # The ball moves up to ~4.5 px per frame: 6 px allows the filtered box about one frame of lag.
        if error <= 6 and 25 <= w <= 60 and 25 <= h <= 60:
            tracked += 1
        else:
            print(f"frame {frame}: box {x},{y},{w},{h} centre error {error:.1f} px")
    print(f"{tracked}/{len(lines)} frames with the box on the ball (centre within 6 px)")
    if tracked < 0.9 * FRAMES:
        errors.append(f"the box followed the ball in only {tracked} of {FRAMES} frames")
    for e in errors[:10]:
        print("FAIL:", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
