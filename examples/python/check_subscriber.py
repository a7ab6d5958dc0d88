#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Test of track_subscriber.py against a real broker: starts Debian's mosquitto on a free loopback port with its
own config, runs gst-launch-1.0 pipelines that publish with trackpublish (the build tree's plugin, through
GST_PLUGIN_PATH_1_0), and checks what the subscriber prints: every frame once, in order, with the document's
fields, the box on videotestsrc's ball.

  live        the subscriber runs while a pipeline publishes FRAMES documents (source "demo")
  persistent  the subscriber registers its session and leaves; a pipeline publishes (source "demo-away");
              the subscriber comes back under the same client id and receives what the broker kept
  dedupe      the subscriber's Deduper on its own: repeats dropped, a restarted pipeline's frames kept

Usage: check_subscriber.py track_subscriber.py. Exit code 77 (meson: skipped) without paho-mqtt (Debian:
python3-paho-mqtt), mosquitto or gst-launch-1.0.
"""
import getpass
import importlib.util
import json
import math
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time

FRAMES = 90
WIDTH, HEIGHT, RADIUS = 320, 240, 20
FRAME_NS = 1_000_000_000 / 30


def ball_centre(frame):
    # videotestsrc pattern=ball, animation-mode=frames: a Lissajous path over the frame (as in check_app.py).
    x = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * frame / 200)) * (WIDTH - 2 * RADIUS)
    y = RADIUS + (0.5 + 0.5 * math.sin(2 * math.pi * math.sqrt(2) * frame / 200)) * (HEIGHT - 2 * RADIUS)
    return x, y


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Broker:
    """mosquitto on 127.0.0.1:port with a config of its own in a temporary directory."""

    def __init__(self, mosquitto, port, directory):
        config = os.path.join(directory, "mosquitto.conf")
        with open(config, "w") as f:
            # `user`: started by root, mosquitto would switch to its own user.
            f.write(f"user {getpass.getuser()}\nlistener {port} 127.0.0.1\nallow_anonymous true\n"
                    f"persistence false\nlog_dest file {directory}/mosquitto.log\n")
        self.process = subprocess.Popen([mosquitto, "-c", config], stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                return
            except OSError:
                time.sleep(0.05)
        self.stop()
        raise RuntimeError(f"mosquitto did not listen on port {port}")

    def stop(self):
        self.process.terminate()
        self.process.wait(10)


def publish(port, source):
    """The task's pipeline: FRAMES frames of the ball, tracked and published as `source`; returns on EOS (the
    element drains its queue to the broker first)."""
    pipeline = (f"videotestsrc pattern=ball num-buffers={FRAMES} ! video/x-raw,width={WIDTH},height={HEIGHT} ! "
                "videoconvert ! colortrack init-box=140,100,40,40 ! "
                f"trackpublish address=tcp://127.0.0.1:{port} source={source} add-empty-results=true ! fakesink")
    out = subprocess.run(["gst-launch-1.0", "-q", "-e"] + pipeline.split(), capture_output=True, text=True,
                         timeout=60)
    if out.returncode != 0:
        raise RuntimeError(f"gst-launch-1.0 exited with {out.returncode}: {out.stderr[-2000:]}")


class Subscriber:
    """track_subscriber.py in the background; ready() waits for its "subscribed" status line."""

    def __init__(self, script, port, *args):
        self.process = subprocess.Popen([sys.executable, script, "--host", "127.0.0.1", "--port", str(port)]
                                        + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.subscribed = threading.Event()
        self.status = []
        self.reader = threading.Thread(target=self._read_status, daemon=True)
        self.reader.start()

    def _read_status(self):
        for line in self.process.stderr:
            self.status.append(line.rstrip())
            if line.startswith("subscribed to"):
                self.subscribed.set()

    def ready(self, timeout=15):
        if not self.subscribed.wait(timeout):
            raise RuntimeError("the subscriber did not subscribe: " + " | ".join(self.status))

    def finish(self, timeout=60):
        stdout = self.process.stdout.read()
        code = self.process.wait(timeout)
        self.reader.join(5)
        return code, stdout.splitlines()


def check_documents(name, source, code, lines, status):
    """Errors in what the subscriber printed for FRAMES frames of `source`."""
    errors = [] if code == 0 else [f"{name}: the subscriber exited with {code}: {' | '.join(status)}"]
    if len(lines) != FRAMES:
        errors.append(f"{name}: {len(lines)} documents for {FRAMES} frames")
    on_ball = 0
    for number, line in enumerate(lines):
        try:
            doc = json.loads(line)
        except json.JSONDecodeError:
            errors.append(f"{name}: line {number} is not JSON: {line!r}")
            continue
        if doc.get("frame") != number:
            errors.append(f"{name}: line {number} is frame {doc.get('frame')}: out of order")
            continue
        if (doc.get("source") != source or doc.get("resolution") != {"width": WIDTH, "height": HEIGHT}
                or not isinstance(doc.get("timestamp"), int) or abs(doc["timestamp"] - number * FRAME_NS) > 1
                or not isinstance(doc.get("objects", []), list)):
            errors.append(f"{name}: frame {number}: source, resolution, timestamp or objects wrong: {line}")
            continue
        if len(doc.get("objects", [])) != 1:  # an empty frame's document has no "objects" (gvametaconvert)
            continue
        o = doc["objects"][0]
        box = o.get("detection", {}).get("bounding_box", {})
        if not (isinstance(o.get("id"), int) and all(isinstance(o.get(k), int) for k in "xywh")
                and o.get("state") in ("tracking", "coasting", "lost") and isinstance(o.get("score"), float)
                and isinstance(o.get("verified"), bool) and o.get("detection", {}).get("label") == "colortrack"
                and abs(box.get("x_min", -1) - o["x"] / WIDTH) < 1e-3):
            errors.append(f"{name}: frame {number}: object fields missing or wrong: {o}")
            continue
        cx, cy = ball_centre(number)
        if math.hypot(o["x"] + o["w"] / 2 - cx, o["y"] + o["h"] / 2 - cy) <= 6:
            on_ball += 1
    print(f"{name}: {len(lines)} documents of {source}, frames in order; the box on the ball in {on_ball}")
    if on_ball < 0.9 * FRAMES:
        errors.append(f"{name}: the box was on the ball in only {on_ball} of {FRAMES} frames")
    return errors


def check_deduper(module):
    d = module.Deduper(restart_gap=100)
    seen = [f for f in [0, 1, 2, 2, 3, 1, 4] if d.is_new("a", f)]
    errors = [] if seen == [0, 1, 2, 3, 4] else [f"dedupe: repeats kept or frames lost: {seen}"]
    if not d.is_new("b", 2):
        errors.append("dedupe: another source's frame 2 taken for a repeat")
    for f in range(5, 300):
        d.is_new("a", f)
    if not (d.is_new("a", 0) and d.is_new("a", 1) and not d.is_new("a", 1)):
        errors.append("dedupe: a restarted pipeline's frames (0, 1 after 299) not taken as new, or repeated")
    print("dedupe: repeats dropped, other sources and restarted runs kept" if not errors else "dedupe: FAIL")
    return errors


def check_unreachable(script):
    """A mistyped host or a port without a broker is said within seconds, not a silent wait (issue 48)."""
    errors = []
    for host, port, expected in (("no-such-host.invalid", 1883, "does not resolve"),
                                 ("127.0.0.1", free_port(), "cannot connect to 127.0.0.1")):
        try:
            out = subprocess.run([sys.executable, script, "--host", host, "--port", str(port), "--timeout", "4"],
                                 capture_output=True, text=True, timeout=60)
        except subprocess.TimeoutExpired:  # a resolver that never answers (offline): not the script's fault
            print(f"note: --host {host} not checked: name resolution took over a minute")
            continue
        if out.returncode != 1 or expected not in out.stderr or "connecting to" not in out.stderr:
            errors.append(f"--host {host} --port {port}: exit {out.returncode}, no '{expected}': {out.stderr!r}")
    return errors


def main():
    script = sys.argv[1]
    try:
        import paho.mqtt.client  # noqa: F401
    except ImportError as e:
        print(f"skipped: paho-mqtt (Debian: python3-paho-mqtt) is not available to {sys.executable} ({e})")
        return 77
    mosquitto = shutil.which("mosquitto") or shutil.which("mosquitto", path="/usr/sbin:/usr/local/sbin")
    if not mosquitto or not shutil.which("gst-launch-1.0"):
        print("skipped: needs mosquitto (Debian: mosquitto) and gst-launch-1.0 (Debian: gstreamer1.0-tools)")
        return 77

    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    spec = importlib.util.spec_from_file_location("track_subscriber", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    errors = check_deduper(module) + check_unreachable(script)

    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="check-subscriber-") as directory:
        port = free_port()
        broker = Broker(mosquitto, port, directory)
        try:
            live = Subscriber(script, port, "--client-id", "check-live", "--count", str(FRAMES), "--timeout", "60")
            live.ready()
            publish(port, "demo")
            errors += check_documents("live", "demo", *live.finish(), live.status)

            away = Subscriber(script, port, "--client-id", "check-away", "--topic", "colortrack/demo-away",
                              "--subscribe-only")
            code, lines = away.finish()
            if code != 0 or lines:
                errors.append(f"persistent: --subscribe-only exited with {code} and printed {len(lines)} lines")
            publish(port, "demo-away")
            back = Subscriber(script, port, "--client-id", "check-away", "--topic", "colortrack/demo-away",
                              "--count", str(FRAMES), "--timeout", "30")
            errors += check_documents("persistent", "demo-away", *back.finish(), back.status)
            if not any("session present: True" in s for s in back.status):
                errors.append(f"persistent: the broker did not keep the session: {back.status}")
        finally:
            broker.stop()
    print(f"{time.monotonic() - start:.1f} s with the broker")
    for e in errors[:10]:
        print("FAIL:", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
