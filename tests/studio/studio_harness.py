# SPDX-License-Identifier: LGPL-2.1-or-later
"""Starts colortrack-studio on the built-in scene with robotctl writing to a pty, for the studio's tests."""
import json
import math
import os
import pty
import select
import subprocess
import sys
import tempfile
import time
import tty
import urllib.error
import urllib.request

SKIP = 77
STOP_LINE = b"L=0 R=0\n"  # robotctl protocol=text's stop, the studio's default protocol
# The built-in scene is videotestsrc's ball: radius 20, its centre at frame n (gstvideotestsrc.c, motion wavy)
# x = r + (0.5 + 0.5 sin(2 pi n / 200)) (w - 2r),  y = r + (0.5 + 0.5 sin(2 pi sqrt(2) n / 200)) (h - 2r).
RADIUS = 20


def ball_box(n, width=320, height=240):
    cx = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * n / 200)) * (width - 2 * RADIUS)
    cy = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * math.sqrt(2) * n / 200)) * (height - 2 * RADIUS)
    return [cx - RADIUS, cy - RADIUS, 2 * RADIUS, 2 * RADIUS]


def iou(a, b):
    ix = max(0, min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0]))
    iy = max(0, min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1]))
    inter = ix * iy
    union = a[2] * a[3] + b[2] * b[3] - inter
    return inter / union if union > 0 else 0.0


def meta_iou(state):
    """The IoU with the ball's true box of the best box colortrack attached to a buffer (its region-of-interest
    metas, as /state reports them), on that buffer's frame; 0 without one."""
    metas = state["metas"]
    if metas.get("test_frame") is None:
        return 0.0
    truth = ball_box(metas["test_frame"])
    return max((iou(box, truth) for box in metas["boxes"].values()), default=0.0)


def gi_missing():
    """None when /usr/bin/python3-like gi with Gst is importable here, else what is missing."""
    try:
        import gi
        gi.require_version("Gst", "1.0")
        from gi.repository import Gst  # noqa: F401
    except (ImportError, ValueError) as e:
        return f"PyGObject with GStreamer ({e})"
    return None


class Studio:
    """colortrack-studio as a child process, its robot a pty whose bytes are collected by read_robot()."""

    def __init__(self, program, *extra, robot=True):
        self.robot_fd = None
        args = [sys.executable, program, "--source", "test", "--port", "0", *extra]
        if robot:
            self.robot_fd, slave = pty.openpty()
            tty.setraw(self.robot_fd)
            args += ["--robot-location", os.ttyname(slave)]
            self.slave = slave
        self.robot_bytes = b""
        # Its stderr is kept (and passed on at close) so that a test can look for tracebacks in it.
        self.stderr = tempfile.TemporaryFile()
        self.errors = ""
        self.proc = subprocess.Popen(["nice", "-n", "5", *args], stdout=subprocess.PIPE, stderr=self.stderr,
                                     text=True)
        self.url = self.token = None
        try:
            self.wait_serving()
        except BaseException:
            self.close()
            raise

    def wait_serving(self):
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            line = self.proc.stdout.readline()
            if not line:
                raise RuntimeError(f"colortrack-studio exited with {self.proc.wait()} before serving")
            if "serving " in line:
                self.url = line.split("serving ", 1)[1].strip().split("?")[0]
            if "token " in line:
                self.token = line.split("token ", 1)[1].strip()
            if self.url and (self.token or "?token=" not in line):
                break
        self.wait_frames(3)

    def headers(self):
        return {"X-Studio-Token": self.token} if self.token else {}

    def get(self, path, timeout=5):
        req = urllib.request.Request(self.url.rstrip("/") + path, headers=self.headers())
        with urllib.request.urlopen(req, timeout=timeout) as r:
            return json.load(r)

    def post(self, path, body, timeout=5):
        req = urllib.request.Request(self.url.rstrip("/") + path, data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json", **self.headers()})
        try:
            with urllib.request.urlopen(req, timeout=timeout) as r:
                return r.status, json.load(r)
        except urllib.error.HTTPError as e:
            return e.code, json.loads(e.read() or b"{}")

    def wait_frames(self, count, timeout=30):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                if (self.get("/state").get("video_frames") or 0) >= count:
                    return
            except OSError:
                pass
            time.sleep(0.1)
        raise RuntimeError("no video frames from the studio")

    def read_robot(self, seconds=0.0):
        """The pty's bytes that arrived so far (and during `seconds` more), appended to robot_bytes."""
        out = b""
        deadline = time.monotonic() + seconds
        while True:
            wait = max(0.0, deadline - time.monotonic())
            if not select.select([self.robot_fd], [], [], wait if wait > 0 else 0.02)[0]:
                if time.monotonic() >= deadline:
                    break
                continue
            out += os.read(self.robot_fd, 4096)
        self.robot_bytes += out
        return out

    def select_ball(self):
        """POST /select on the middle of the ball where it will be next frame (threshold mode learns its
        colour from it); the HTTP status."""
        x, y, _, _ = ball_box(self.get("/state")["test_frame"] + 1)
        status, _ = self.post("/select", {"x": round(x + 8), "y": round(y + 8), "w": 24, "h": 24})
        return status

    def wait_moving(self, seconds=5.0):
        """True once the robot's pty has had a command other than stop within `seconds` (what was read is
        kept in robot_bytes only)."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            if self.read_robot(0.1).replace(STOP_LINE, b""):
                return True
        return False

    def alive(self):
        return self.proc.poll() is None

    def close(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(15)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        if self.robot_fd is not None:
            os.close(self.robot_fd)
            os.close(self.slave)
            self.robot_fd = None
        if not self.stderr.closed:
            self.stderr.seek(0)
            self.errors = self.stderr.read().decode(errors="replace")
            self.stderr.close()
            sys.stderr.write(self.errors)
        return self.proc.returncode

    def tracebacks(self):
        """After close(): how many Python tracebacks the studio printed (a bug of ours, caught or not)."""
        return self.errors.count("Traceback (most recent call last)")
