#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Follow a target on an IP camera that may restart: only the RTSP source is rebuilt, the track survives.

    rtsp_follow.py rtsp://192.0.2.10:554/stream --init-box 280,200,80,80
    rtsp_follow.py rtsp://camera/stream --template ball.png --robot /dev/ttyUSB0 --seconds 600

rtspsrc does not reconnect once the camera is gone (a reboot, a network cut). This program runs the pattern of
docs/sources.md: rtspsrc (TCP) sits outside the rest of the pipeline, and when it fails, ends, or delivers no
frame for 2 s (6 s for a session's first frame), only rtspsrc is set to NULL and started again with back-off (0.2 s doubling to 2 s), with the
pipeline's clock and base time. colortrack, its template (also one taken from --init-box) and its track ids,
and everything downstream keep running. With --robot, robotctl sends stop while no frame comes (its
lost-timeout) and follows again when the stream is back.

Decodes H.264 (most IP cameras; --codec mjpeg for MJPEG): decodebin picks the decoder (openh264dec from
gst-plugins-bad, or avdec_h264 from gstreamer1.0-libav). Prints one JSON line per frame on stdout, from
colortrack's bus message, {"time": s since start, "frame": n, "session": sources started so far, "id",
"state", "box": [x, y, w, h] or null}, and one status line per source event on stderr. Runs until --seconds
pass, or for ever.

Needs Debian's python3-gi and gir1.2-gstreamer-1.0, hence /usr/bin/python3 above.
"""
import argparse
import json
import sys
import time

import gi

gi.require_version("Gst", "1.0")
from gi.repository import Gst  # noqa: E402

STALL_SECONDS = 2.0  # no frame for this long: a silent failure (power cut, cable pulled)
# A session's first frame waits for the RTSP handshake, a key frame and the decoder: a loaded machine or a
# camera with a long key-frame interval needs longer than a stall does.
CONNECT_SECONDS = 6.0
FIRST_BACKOFF, MAX_BACKOFF = 0.2, 2.0
SOURCE_ENDED = "source-ended"  # the application message the EOS probe posts


class Follower:
    """The pipeline and the source's restart policy."""

    def __init__(self, args):
        self.args = args
        self.start = time.monotonic()
        self.last_frame_at = self.stall_from = self.start
        self.sessions = 1
        self.backoff = FIRST_BACKOFF
        self.restart_at = None
        self.session_frames = 0
        self.pipeline = Gst.parse_launch(self.description())
        self.source = Gst.ElementFactory.make("rtspsrc", "source")
        if self.source is None:
            sys.exit("rtspsrc is missing (Debian: gstreamer1.0-plugins-good)")
        self.source.set_property("location", args.url)
        self.source.set_property("latency", args.latency)
        Gst.util_set_object_arg(self.source, "protocols", "tcp")  # a server that goes away closes the socket
        self.pipeline.add(self.source)
        self.depay_sink = self.pipeline.get_by_name("depay").get_static_pad("sink")
        self.source.connect("pad-added", self.on_pad_added)
        # An EOS from a server that closed the connection must not end the pipeline: dropped, and told.
        self.depay_sink.add_probe(Gst.PadProbeType.EVENT_DOWNSTREAM, self.on_source_event)
        self.bus = self.pipeline.get_bus()

    def description(self):
        depay = "rtph264depay name=depay ! h264parse" if self.args.codec == "h264" else "rtpjpegdepay name=depay"
        tracker = "colortrack name=tracker post-messages=true draw=none"
        if self.args.init_box:
            tracker += f" init-box={self.args.init_box}"
        if self.args.template:
            tracker += f' template-location="{self.args.template}"'
        # robotctl stands the robot still when no confirmed target came for half of lost-timeout, and sends
        # stop when no frame at all came for all of it.
        tail = "fakesink sync=false"
        if self.args.robot:
            # A serial port through libserialport (device=, baud rate and framing set); a file, FIFO or
            # udp://HOST:PORT as written (location=).
            target = "device" if self.args.robot.startswith("/dev/tty") else "location"
            tail = f'robotctl protocol=text sync=false lost-timeout=500 {target}="{self.args.robot}"'

        return f"{depay} ! decodebin ! videoconvert ! {tracker} ! {tail}"

    def on_pad_added(self, _source, pad):
        if not self.depay_sink.is_linked():
            pad.link(self.depay_sink)

    def on_source_event(self, _pad, info):
        if info.get_event().type != Gst.EventType.EOS:
            return Gst.PadProbeReturn.OK
        self.source.post_message(Gst.Message.new_application(self.source, Gst.Structure.new_empty(SOURCE_ENDED)))
        return Gst.PadProbeReturn.DROP

    def report(self, message):
        """One JSON line from colortrack's message for a frame (posted for every frame it sees)."""
        s = message.get_structure()
        now = time.monotonic()
        self.last_frame_at = now
        self.session_frames += 1
        self.backoff = FIRST_BACKOFF  # frames flow: the next outage starts from the first back-off
        box = [round(s.get_value(k)) for k in ("x", "y", "width", "height")] if s.get_value("id") > 0 else None
        print(json.dumps({"time": round(now - self.start, 3), "frame": s.get_value("frame"),
                          "session": self.sessions, "id": s.get_value("id"), "state": s.get_value("state"),
                          "box": box}), flush=True)

    def schedule_restart(self, why):
        """Stops the source now and starts it again after the back-off."""
        self.source.set_state(Gst.State.NULL)
        self.restart_at = time.monotonic() + self.backoff
        print(f"source: {why}; restarting in {self.backoff:.1f} s", file=sys.stderr, flush=True)
        self.backoff = min(self.backoff * 2, MAX_BACKOFF)

    def restart(self):
        self.restart_at = None
        self.sessions += 1
        self.session_frames = 0
        self.stall_from = time.monotonic()  # the stall watchdog gives the new session its time
        # The pipeline's clock and base time, so the new session's timestamps continue the running time.
        self.source.set_clock(self.pipeline.get_clock())
        self.source.set_base_time(self.pipeline.get_base_time())
        self.source.sync_state_with_parent()

    def handle(self, message):
        """Returns False when the program should stop (an error outside the source)."""
        if message.type == Gst.MessageType.ELEMENT and message.get_structure().get_name() == "colortrack":
            self.report(message)
        elif message.type == Gst.MessageType.APPLICATION and message.get_structure().get_name() == SOURCE_ENDED:
            if self.restart_at is None:
                self.schedule_restart("the camera closed the stream")
        elif message.type == Gst.MessageType.ERROR:
            error, _ = message.parse_error()
            if not message.src.has_as_ancestor(self.source) and message.src != self.source:
                print(f"error from {message.src.get_name()}: {error.message}", file=sys.stderr, flush=True)
                return False
            if self.restart_at is None:
                self.schedule_restart(f"source error: {error.message}")
        return True

    def patience(self):
        """How long the source may stay silent before it is restarted."""
        return STALL_SECONDS if self.session_frames else CONNECT_SECONDS

    def run(self):
        self.pipeline.set_state(Gst.State.PLAYING)
        status = 0
        while self.args.seconds <= 0 or time.monotonic() - self.start < self.args.seconds:
            message = self.bus.timed_pop(20 * Gst.MSECOND)
            if message is not None and not self.handle(message):
                status = 1
                break
            now = time.monotonic()
            if self.restart_at is not None and now >= self.restart_at:
                self.restart()
            elif self.restart_at is None and now - max(self.last_frame_at, self.stall_from) > self.patience():
                self.schedule_restart(f"no frame for {self.patience():.0f} s")
        self.pipeline.set_state(Gst.State.NULL)
        return status


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("url", help="rtsp://HOST[:PORT]/PATH")
    parser.add_argument("--codec", choices=("h264", "mjpeg"), default="h264", help="what the camera sends")
    parser.add_argument("--init-box", help='"x,y,w,h" of the target in the first frame')
    parser.add_argument("--template", help="template image (survives even a restart of this program)")
    parser.add_argument("--robot", help="where robotctl sends: a serial port /dev/tty... (device=), a file or "
                        "udp://HOST:PORT (location=)")
    parser.add_argument("--latency", type=int, default=100, help="rtspsrc jitter buffer, ms")
    parser.add_argument("--seconds", type=float, default=0, help="stop after this long (0: run for ever)")
    args = parser.parse_args()
    if args.init_box and args.template:
        parser.error("--init-box and --template both define the target: give one of them")
    if not (args.init_box or args.template):
        parser.error("give --init-box or --template")
    Gst.init(None)
    try:
        follower = Follower(args)
    except Exception as e:  # noqa: BLE001  a pipeline that cannot be built: say why and stop
        sys.exit(f"pipeline: {e} (is the colortrack plugin on GST_PLUGIN_PATH?)")
    return follower.run()


if __name__ == "__main__":
    sys.exit(main())
