# SPDX-License-Identifier: LGPL-2.1-or-later
"""colortrack-studio's pipeline: the source through colortrack to the MJPEG branches (and robotctl), the
state the page reads, and what a request may change (the box, the threshold settings, STOP, a preset)."""
import math
import os
import re
import shlex
import sys
import threading
import time
from http import HTTPStatus

import gi

gi.require_version("Gst", "1.0")
gi.require_version("GstVideo", "1.0")
from gi.repository import GLib, Gst, GstVideo  # noqa: E402

PRESET_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9 _.-]{0,63}")  # a key-file group name: no [ ] or new line
# The built-in scene: videotestsrc's ball (radius 20, deterministic by frame number) in green on grey.
TEST_BALL_COLOUR = 0xff20c040
TEST_BACKGROUND = 0xff404040


class BadRequest(Exception):
    """A request the studio refuses: HTTP status and a message for the client."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status


def source_description(source, width, height, fps):
    """gst-launch text of the source, ending in raw video at the given size where the source allows it."""
    caps = f"video/x-raw,width={width},height={height}"  # the source's own frame rate, except the test's
    if source == "test":
        return (f"videotestsrc is-live=true pattern=ball foreground-color={TEST_BALL_COLOUR:#x} "
                f"background-color={TEST_BACKGROUND:#x} ! {caps},framerate={fps}/1")
    if source.startswith("v4l2:"):
        return f"v4l2src device={shlex.quote(source[5:])} ! videoconvert ! videoscale ! {caps}"
    if source.startswith(("rtsp://", "rtsps://")):
        return f"rtspsrc location={shlex.quote(source)} latency=100 ! decodebin ! videoconvert ! videoscale ! {caps}"
    uri = source if Gst.uri_is_valid(source) else Gst.filename_to_uri(os.path.abspath(source))
    # A file is played at its own pace (clocksync), not as fast as it decodes.
    return f"uridecodebin uri={shlex.quote(uri)} ! videoconvert ! videoscale ! {caps} ! clocksync"


class Studio:
    """The pipeline and what the page reads and changes. Every method is safe to call from any thread."""

    def __init__(self, args):
        self.args = args
        self.lock = threading.Lock()
        self.frames = {"video": (0, b"", 0), "mask": (0, b"", 0)}   # seq, jpeg, capture time (ns)
        self.frame_cond = threading.Condition(self.lock)
        self.state = {"frame": None, "pts": None, "id": 0, "state": None, "box": None, "score": None,
                      "objects": []}
        self.robot = {"command": None, "left": None, "right": None, "sent": 0, "stopped": False}
        self.events = []            # the last warnings and errors of the pipeline
        self.select_time = None     # monotonic ns of the last /select, until its first tracked frame
        self.select_ids = set()
        self.select_to_track_ms = None
        self.last_select = None     # the last box /select gave, and the frame it arrived at
        self.width = self.height = None
        self.running = True
        self.on_fatal = None        # called (once) on a pipeline error or the end of the stream
        self.pipeline = Gst.parse_launch(self.description())
        self.ct = self.pipeline.get_by_name("ct")
        self.maskct = self.pipeline.get_by_name("maskct")
        self.robotctl = self.pipeline.get_by_name("robot")
        for name in ("video", "mask"):
            sink = self.pipeline.get_by_name(name)
            if sink is not None:
                sink.connect("new-sample", self.on_sample, name)
        self.roi_type = GLib.quark_from_string("colortrack")  # colortrack's roi-type: its metas
        self.metas = {"pts": None, "boxes": {}}
        self.ct.get_static_pad("src").add_probe(Gst.PadProbeType.BUFFER, self.on_ct_buffer)
        if args.preset:
            self.load_preset(args.preset)

    def load_preset(self, name):
        if not self.ct.load_preset(name):
            sys.exit(f"colortrack-studio: no colortrack preset '{name}' (searched $GST_PRESET_PATH and "
                                           f"{os.path.join(os.environ.get('XDG_DATA_HOME', '~/.local/share'), 'gstreamer-1.0/presets')})")
        mode = self.ct.get_property("mode").value_nick
        if mode != self.args.mode:
            sys.exit(f"colortrack-studio: preset '{name}' is mode={mode}: start with --mode {mode}")
        for prop in ("hsv-lower", "hsv-upper") if self.maskct is not None else ():
            self.maskct.set_property(prop, self.ct.get_property(prop))

    def description(self):
        a = self.args
        tracker = f"colortrack name=ct post-messages=true mode={a.mode} draw=box+trail+label"
        if a.mode == "threshold":
            tracker += f" hsv-lower={a.hsv_lower} hsv-upper={a.hsv_upper}"
        if a.init_box:
            tracker += f" init-box={a.init_box}"
        leaky = "queue leaky=downstream max-size-buffers=2 max-size-time=0 max-size-bytes=0"
        jpeg = f"videoconvert ! jpegenc quality={a.jpeg_quality}"
        appsink = "appsink sync=false max-buffers=1 drop=true emit-signals=true"
        text = (f"{source_description(a.source, a.width, a.height, a.fps)} ! videoconvert ! "
                f"video/x-raw,format=BGRx ! {tracker} ! tee name=t "
                f"t. ! {leaky} ! {jpeg} ! {appsink} name=video ")
        if a.mode == "threshold":
            text += (f"t. ! {leaky} ! colortrack name=maskct mode=threshold draw=mask follow-camera=false "
                     f"hsv-lower={a.hsv_lower} hsv-upper={a.hsv_upper} ! {jpeg} ! {appsink} name=mask ")
        if a.robot_location or a.robot_device:
            port = (f"location={shlex.quote(a.robot_location)}" if a.robot_location
                    else f"device={shlex.quote(a.robot_device)}")
            text += (f"t. ! queue leaky=downstream max-size-buffers=4 ! robotctl name=robot {port} "
                     f"protocol={a.robot_protocol} post-messages=true async=false")
        return text

    # ---- streaming side -------------------------------------------------------------------------------
    def on_ct_buffer(self, pad, info):
        if self.width is None:
            caps = pad.get_current_caps()
            if caps is not None:
                # VideoInfo, not the caps' structure: GStreamer 1.26's Python wraps that in a context manager.
                video = GstVideo.VideoInfo.new_from_caps(caps)
                self.width, self.height = video.width, video.height
        self.read_track_metas(info.get_buffer())
        return Gst.PadProbeReturn.OK

    def read_track_metas(self, buffer):
        """The boxes colortrack attached to the buffer (its region-of-interest metas) for the tracks its last
        message listed: what any element downstream reads, shown beside the messages' boxes."""
        with self.lock:
            ids = [o["id"] for o in self.state["objects"]]
        boxes = {}
        for track_id in ids:
            meta = GstVideo.buffer_get_video_region_of_interest_meta_id(buffer, track_id)
            if meta is not None and meta.roi_type == self.roi_type:
                boxes[str(track_id)] = [meta.x, meta.y, meta.w, meta.h]
        with self.lock:
            self.metas = {"pts": buffer.pts, "boxes": boxes}

    def capture_time(self, pts):
        """The pipeline clock's time (CLOCK_MONOTONIC, ns) when the frame with this PTS was captured."""
        if pts == Gst.CLOCK_TIME_NONE:
            return 0
        return self.pipeline.get_base_time() + pts

    def on_sample(self, sink, name):
        sample = sink.emit("pull-sample")
        if sample is None:
            return Gst.FlowReturn.EOS
        buffer = sample.get_buffer()
        data = buffer.extract_dup(0, buffer.get_size())
        with self.frame_cond:
            seq = self.frames[name][0] + 1
            self.frames[name] = (seq, data, self.capture_time(buffer.pts))
            self.frame_cond.notify_all()
        return Gst.FlowReturn.OK

    def wait_frame(self, name, after, timeout=5.0):
        with self.frame_cond:
            self.frame_cond.wait_for(lambda: self.frames[name][0] != after or not self.running, timeout)
            return self.frames[name]

    def watch_bus(self):
        bus = self.pipeline.get_bus()
        while self.running:
            message = bus.timed_pop(Gst.SECOND // 10)
            if message is not None:
                self.on_message(message)

    def on_message(self, message):
        t = message.type
        if t in (Gst.MessageType.ERROR, Gst.MessageType.WARNING):
            error, _ = message.parse_error() if t == Gst.MessageType.ERROR else message.parse_warning()
            kind = "error" if t == Gst.MessageType.ERROR else "warning"
            text = f"{kind} from {message.src.get_name()}: {error.message}"
            print(text, file=sys.stderr, flush=True)
            with self.lock:
                self.events = (self.events + [text])[-10:]
            if t == Gst.MessageType.ERROR and self.on_fatal is not None:
                self.on_fatal()
        elif t == Gst.MessageType.EOS:
            print("colortrack-studio: end of the stream", file=sys.stderr, flush=True)
            if self.on_fatal is not None:
                self.on_fatal()
        elif t == Gst.MessageType.ELEMENT and message.src is self.ct:
            self.on_track_message(message.get_structure())
        elif t == Gst.MessageType.ELEMENT and message.src is self.robotctl:
            s = message.get_structure()
            with self.lock:
                self.robot.update(command=s.get_value("command"), sent=self.robot["sent"] + 1,
                                  left=s.get_value("left") if s.has_field("left") else None,
                                  right=s.get_value("right") if s.has_field("right") else None)

    def on_track_message(self, s):
        objects = []
        if s.has_field("objects"):
            try:
                listed = s.get_value("objects")
                items = listed.array if hasattr(listed, "array") else list(listed or [])
                objects = [{"id": o.get_value("id"), "state": o.get_value("state"),
                            "score": round(o.get_value("score"), 3), "area": o.get_value("area"),
                            "box": [round(o.get_value(k)) for k in ("x", "y", "width", "height")]}
                           for o in items]
            except TypeError:  # no python3-gst-1.0: GstValueList unreadable
                objects = []
        track_id, state = s.get_value("id"), s.get_value("state")
        box = [round(s.get_value(k)) for k in ("x", "y", "width", "height")] if track_id > 0 else None
        if not objects and box is not None and state in ("tracking", "coasting"):
            objects = [{"id": track_id, "state": state, "score": round(s.get_value("score"), 3), "box": box}]
        with self.lock:
            pts = s.get_value("timestamp")
            self.state = {"frame": s.get_value("frame"), "pts": pts, "id": track_id, "state": state,
                          "box": box, "score": s.get_value("score"), "objects": objects}
            if self.select_time is not None and any(o["state"] == "tracking" and o["id"] not in self.select_ids
                                                    for o in objects):
                self.select_to_track_ms = (time.monotonic_ns() - self.select_time) / 1e6
                self.select_time = None
        if self.maskct is not None:  # the mask view follows the range colortrack learnt or was given
            for name in ("hsv-lower", "hsv-upper"):
                value = self.ct.get_property(name)
                if self.maskct.get_property(name) != value:
                    self.maskct.set_property(name, value)

    # ---- what the page asks ---------------------------------------------------------------------------
    def snapshot(self):
        with self.lock:
            out = dict(self.state)
            metas = dict(self.metas)
            out.update(robot=dict(self.robot) if self.robotctl is not None else None,
                       events=list(self.events), select_to_track_ms=self.select_to_track_ms,
                       last_select=self.last_select,
                       width=self.width, height=self.height, mode=self.args.mode,
                       video_frames=self.frames["video"][0], mask_frames=self.frames["mask"][0])
        out["settings"] = self.settings()
        if self.args.source == "test" and out["pts"] is not None:
            out["test_frame"] = round(out["pts"] * self.args.fps / Gst.SECOND)
        if self.args.source == "test" and metas["pts"] is not None:
            metas["test_frame"] = round(metas["pts"] * self.args.fps / Gst.SECOND)
        out["metas"] = metas
        return out

    def settings(self):
        names = ("hsv-lower", "hsv-upper", "min-area", "morph-size") if self.args.mode == "threshold" else ()
        return {name: self.ct.get_property(name) for name in names}

    def select(self, body):
        box = [number(body, key, integer=True) for key in ("x", "y", "w", "h")]
        if self.width is None:
            raise BadRequest(HTTPStatus.SERVICE_UNAVAILABLE, "no frame yet: the frame size is not known")
        x, y, w, h = box
        if w < 8 or h < 8 or x < 0 or y < 0 or x + w > self.width or y + h > self.height:
            raise BadRequest(HTTPStatus.BAD_REQUEST, f"box {x},{y},{w},{h} must be at least 8x8 and inside the "
                                                     f"{self.width}x{self.height} frame")
        x0, y0, x1, y1 = x, y, x + w, y + h
        with self.lock:
            self.select_time = time.monotonic_ns()
            self.select_ids = {o["id"] for o in self.state["objects"]}  # a new track answers the selection
            self.select_to_track_ms = None
            self.last_select = {"box": [x0, y0, x1 - x0, y1 - y0], "frame": self.state["frame"]}
        self.ct.set_property("init-box", f"{x0},{y0},{x1 - x0},{y1 - y0}")
        return {"init-box": [x0, y0, x1 - x0, y1 - y0]}

    def apply_settings(self, body):
        if self.args.mode != "threshold":
            raise BadRequest(HTTPStatus.CONFLICT, "settings are threshold mode's; this studio runs mode=template")
        known = ("hsv-lower", "hsv-upper", "min-area", "morph-size")
        unknown = [k for k in body if k not in known]
        if unknown:
            raise BadRequest(HTTPStatus.BAD_REQUEST, f"unknown setting(s) {unknown}; known: {list(known)}")
        values = {}
        lower = hsv(body["hsv-lower"], "hsv-lower") if "hsv-lower" in body else None
        upper = hsv(body["hsv-upper"], "hsv-upper") if "hsv-upper" in body else None
        cur_lower = [float(v) for v in self.ct.get_property("hsv-lower").split(",")]
        cur_upper = [float(v) for v in self.ct.get_property("hsv-upper").split(",")]
        lo, up = lower or cur_lower, upper or cur_upper
        if lo[1] > up[1] or lo[2] > up[2]:
            raise BadRequest(HTTPStatus.BAD_REQUEST,
                             f"hsv-lower's s and v ({lo[1]}, {lo[2]}) must not exceed hsv-upper's ({up[1]}, {up[2]})")
        if "min-area" in body:
            values["min-area"] = number(body, "min-area", integer=True, low=1,
                                        high=(self.width * self.height) if self.width else 1 << 26)
        if "morph-size" in body:
            values["morph-size"] = number(body, "morph-size", integer=True, low=0, high=255)
        if lower:
            values["hsv-lower"] = ",".join(fmt(v) for v in lower)
        if upper:
            values["hsv-upper"] = ",".join(fmt(v) for v in upper)
        for name, value in values.items():
            self.ct.set_property(name, value)
            if name in ("hsv-lower", "hsv-upper") and self.maskct is not None:
                self.maskct.set_property(name, value)
        return {"applied": values, "settings": self.settings()}

    def stop(self, body):
        if not isinstance(body.get("hold"), bool):
            raise BadRequest(HTTPStatus.BAD_REQUEST, 'give {"hold": true} (stop and hold) or {"hold": false} (release)')
        if self.robotctl is None:
            raise BadRequest(HTTPStatus.CONFLICT, "no robot: start with --robot-location or --robot-device")
        # robotctl's hold: stop at once from this thread, then only stop until released; tracking goes on.
        self.robotctl.set_property("hold", body["hold"])
        with self.lock:
            self.robot["stopped"] = self.robotctl.get_property("hold")
        return {"stopped": body["hold"]}

    def save(self, body):
        unknown = sorted(set(body) - {"name"})
        if unknown:
            raise BadRequest(HTTPStatus.BAD_REQUEST, f"/save takes only name, not {', '.join(unknown)[:100]}")
        name = body.get("name", "studio")
        if not isinstance(name, str) or not PRESET_NAME.fullmatch(name):
            raise BadRequest(HTTPStatus.BAD_REQUEST, "name must be 1-64 letters, digits, spaces, '_', '.' or '-', "
                             f"starting with a letter or digit; got {name!r:.70}")
        a = self.args
        props = {"mode": a.mode}
        props.update(self.settings())
        props = {k: str(v) for k, v in props.items()}
        tracker = "colortrack " + " ".join(f"{k}={v}" for k, v in props.items())
        if a.mode == "template" and self.last_select is not None:  # what it follows: the box picked last
            tracker += " init-box=" + ",".join(str(v) for v in self.last_select["box"])
        launch = (f"gst-launch-1.0 {source_description(a.source, a.width, a.height, a.fps)} ! videoconvert ! "
                  f"{tracker} ! videoconvert ! autovideosink")
        preset = f"[{name}]\n" + "".join(f"{k}={v}\n" for k, v in props.items())
        written = None
        if a.preset_out:  # GStreamer saves to $XDG_DATA_HOME/gstreamer-1.0/presets/, set to --preset-out
            if not self.ct.save_preset(name):
                raise BadRequest(HTTPStatus.INTERNAL_SERVER_ERROR, f"the preset could not be saved in {a.preset_out}")
            written = os.path.join(a.preset_out, "gstreamer-1.0", "presets", "GstColorTrack.prs")
            with open(written, encoding="utf-8") as f:
                preset = f.read()
        return {"launch": launch, "preset": preset, "written": written, "preset_name": name}

    def start(self):
        """Plays the pipeline; False (the error printed) when it cannot start."""
        if self.pipeline.set_state(Gst.State.PLAYING) == Gst.StateChangeReturn.FAILURE:
            message = self.pipeline.get_bus().pop_filtered(Gst.MessageType.ERROR)
            if message is not None:
                self.on_message(message)
            return False
        threading.Thread(target=self.watch_bus, daemon=True).start()
        return True

    def close(self):
        self.running = False
        with self.frame_cond:
            self.frame_cond.notify_all()
        self.pipeline.set_state(Gst.State.NULL)


def fmt(v):
    return f"{v:.4g}"


def number(body, key, integer=False, low=None, high=None):
    value = body.get(key)
    ok = isinstance(value, int) if integer else isinstance(value, (int, float))
    if isinstance(value, bool) or not ok or (isinstance(value, float) and not math.isfinite(value)):
        raise BadRequest(HTTPStatus.BAD_REQUEST, f"{key} must be {'an integer' if integer else 'a number'}, got {value!r:.60}")
    if (low is not None and value < low) or (high is not None and value > high):
        raise BadRequest(HTTPStatus.BAD_REQUEST, f"{key}={value} is outside {low}..{high}")
    return value


def hsv(value, key):
    """ "h,s,v" or [h, s, v] with h in 0..360 and s, v in 0..1, as three floats."""
    if isinstance(value, str) and len(value) < 100:
        parts = value.split(",")
    elif isinstance(value, list):
        parts = value
    else:
        raise BadRequest(HTTPStatus.BAD_REQUEST, f'{key} must be "h,s,v" or [h, s, v]')
    try:
        h, s, v = (float(p) if not isinstance(p, bool) else None for p in parts)
    except (TypeError, ValueError):
        raise BadRequest(HTTPStatus.BAD_REQUEST, f'{key} must be three numbers "h,s,v", got {value!r:.60}') from None
    if not all(x is not None and math.isfinite(x) for x in (h, s, v)) or not (0 <= h <= 360 and 0 <= s <= 1 and 0 <= v <= 1):
        raise BadRequest(HTTPStatus.BAD_REQUEST, f"{key}: h must be in 0..360, s and v in 0..1, got {value!r:.60}")
    return [h, s, v]

