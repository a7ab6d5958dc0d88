#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Test of colortrack_app.py: runs it on videotestsrc's ball and checks its JSON lines (one per frame, every
field there with its type) and that the box follows the ball; then in threshold mode, that each frame's
"objects" list (read through python3-gst-1.0's overrides) holds the ball, with the default range and, on a
red ball in a file, with the range learnt from --init-box. Exit code 77 (meson: skipped) without PyGObject."""
import json
import math
import os
import subprocess
import sys
import tempfile

FRAMES = 150
WIDTH, HEIGHT, RADIUS = 320, 240, 20


def ball_centre(frame):
    # videotestsrc pattern=ball, animation-mode=frames: a Lissajous path over the frame.
    x = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * frame / 200)) * (WIDTH - 2 * RADIUS)
    y = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * math.sqrt(2) * frame / 200)) * (HEIGHT - 2 * RADIUS)
    return x, y


def main():
    try:
        import gi
        gi.require_version("Gst", "1.0")
        gi.require_version("GstVideo", "1.0")
        from gi.repository import Gst, GstVideo  # noqa: F401
    except (ImportError, ValueError) as e:
        print(f"skipped: PyGObject with Gst and GstVideo typelibs is not available ({e})")
        return 77

    out = subprocess.run([sys.executable, sys.argv[1], "--frames", str(FRAMES)], capture_output=True, text=True,
                         timeout=60)
    sys.stderr.write(out.stderr)
    if out.returncode != 0:
        print(f"colortrack_app.py exited with {out.returncode}")
        return 1
    errors, tracked, with_meta = [], 0, 0
    lines = out.stdout.splitlines()
    if len(lines) != FRAMES:
        errors.append(f"{len(lines)} lines for {FRAMES} frames")
    for number, line in enumerate(lines):
        try:
            r = json.loads(line)
        except json.JSONDecodeError:
            errors.append(f"line {number} is not JSON: {line!r}")
            continue
        if not (r.get("frame") == number and isinstance(r.get("time"), float) and abs(r["time"] - number / 30) < 1e-3
                and isinstance(r.get("id"), int) and r.get("state") in ("searching", "tracking", "coasting", "lost")
                and isinstance(r.get("score"), float) and isinstance(r.get("verified"), bool)):
            errors.append(f"line {number}: fields missing or of the wrong type: {line}")
            continue
        if r["box"] is None:
            continue
        with_meta += r["meta"]
        x, y, w, h = r["box"]
        cx, cy = ball_centre(number)
        if math.hypot(x + w / 2 - cx, y + h / 2 - cy) <= 6 and 25 <= w <= 60 and 25 <= h <= 60:
            tracked += 1
        else:
            print(f"frame {number}: box {r['box']} off the ball at ({cx:.0f}, {cy:.0f})")
    print(f"{tracked}/{len(lines)} frames with the box on the ball (centre within 6 px), {with_meta} read from "
          "the ROI meta")
    if tracked < 0.9 * FRAMES:
        errors.append(f"the box followed the ball in only {tracked} of {FRAMES} frames")
    if with_meta != tracked and tracked:
        errors.append("boxes without a ROI meta")
    errors += check_threshold_objects()
    errors += check_threshold_init_box(Gst)
    for e in errors[:10]:
        print("FAIL:", e)
    return 1 if errors else 0


def write_red_ball_file(Gst, path):
    """The test pattern's ball in red (the app's default range is green), as Motion JPEG in AVI."""
    Gst.init(None)
    pipeline = Gst.parse_launch(
        f"videotestsrc pattern=ball foreground-color=0xffe02020 num-buffers={FRAMES} ! "
        f"video/x-raw,width={WIDTH},height={HEIGHT},framerate=30/1 ! jpegenc quality=95 ! avimux ! "
        f"filesink location={path}")
    pipeline.set_state(Gst.State.PLAYING)
    message = pipeline.get_bus().timed_pop_filtered(30 * Gst.SECOND, Gst.MessageType.EOS | Gst.MessageType.ERROR)
    pipeline.set_state(Gst.State.NULL)
    return message is not None and message.type == Gst.MessageType.EOS


def check_threshold_init_box(Gst):
    """Threshold mode on a file with --init-box (issue 48: it used to be ignored for the default range)."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "red-ball.avi")
        if not write_red_ball_file(Gst, path):
            return ["could not write the red ball's file (jpegenc and avimux, gstreamer1.0-plugins-good)"]
        return check_threshold_objects(["--init-box", "140,100,40,40", path], "with --init-box")


def check_threshold_objects(extra=(), what="default range"):
    """Threshold mode: the ball is among the objects of nearly every frame (it is confirmed from frame 2)."""
    out = subprocess.run([sys.executable, sys.argv[1], "--frames", str(FRAMES), "--mode", "threshold", *extra],
                         capture_output=True, text=True, timeout=60)
    sys.stderr.write(out.stderr)
    if out.returncode != 0:
        return [f"colortrack_app.py --mode threshold {' '.join(extra)} exited with {out.returncode}"]
    on_ball = 0
    for number, line in enumerate(out.stdout.splitlines()):
        objects = json.loads(line).get("objects")
        if objects is None:
            return [f"threshold line {number}: no objects list (python3-gst-1.0 missing?): {line}"]
        cx, cy = ball_centre(number)
        on_ball += any(math.hypot(o["box"][0] + o["box"][2] / 2 - cx, o["box"][1] + o["box"][3] / 2 - cy) <= 6
                       for o in objects)
    print(f"threshold mode ({what}): the ball among the objects in {on_ball}/{FRAMES} frames")
    if on_ball < 0.9 * FRAMES:
        return [f"threshold mode ({what}): the ball listed in only {on_ball} frames"]
    return []


if __name__ == "__main__":
    sys.exit(main())
