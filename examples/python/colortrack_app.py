#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""colortrack from Python (PyGObject): one JSON object per frame on stdout.

    {"time": 0.4, "frame": 12, "id": 1, "box": [201, 143, 40, 40], "state": "tracking", "score": 0.91,
     "verified": true, "meta": true}

Builds  SOURCE ! videoconvert ! colortrack post-messages=true ! appsink  and, for every buffer the appsink
receives, joins two things colortrack produced for that frame:
  * the bus message "colortrack" (every frame, with or without a track): frame number, id, state, score;
  * the GstVideoRegionOfInterestMeta on the buffer (frames with a track): the box and its "colortrack"
    parameters. PyGObject cannot cast the generic Gst.Meta that Gst.Buffer.get_meta() returns, so the meta
    is looked up by the id the message gives, with GstVideo.buffer_get_video_region_of_interest_meta_id().
"box" is the meta's box (what travels with the buffer); null when there is no track. "meta" says whether
the meta was found; when it is not (no track), state and score come from the message alone.

With --mode threshold (colour-range segmentation, several objects) each line also has "objects": every
confirmed object of the frame from the message's "objects" list, [{"id", "box", "state", "area"}]. That list
is a GstValueList, which plain PyGObject cannot read ("unknown type GstValueList"): it needs GStreamer's
Python overrides, Debian's python3-gst-1.0 (the test command installs it). Without them "objects" is null
and a note goes to stderr.

Usage: colortrack_app.py [--frames N] [--init-box X,Y,W,H] [--mode threshold [--hsv-lower H,S,V --hsv-upper
H,S,V]] [FILE-OR-URI]
Without FILE-OR-URI: videotestsrc's green ball on black, 320x240 at 30 fps, init-box on the ball at frame 0
(threshold mode: the ball's green range instead). In threshold mode --init-box learns the colour range from
the object in the box on the first frame, and --hsv-lower/--hsv-upper give the range instead.
Needs Debian's python3-gi, gir1.2-gstreamer-1.0 and gir1.2-gst-plugins-base-1.0 (and python3-gst-1.0 for
threshold mode's objects), hence /usr/bin/python3 above (a pyenv or venv python3 first in PATH usually has no
gi); another Python with PyGObject runs it as `that-python colortrack_app.py`.
"""
import argparse
import json
import sys

import gi

gi.require_version("Gst", "1.0")
gi.require_version("GstVideo", "1.0")
from gi.repository import GLib, Gst, GstVideo  # noqa: E402

BALL_INIT_BOX = "140,100,40,40"  # videotestsrc's ball (radius 20) sits at the frame centre at frame 0
BALL_HSV = ("90,0.4,0.3", "150,1,1")  # the built-in ball's green (0xff20c020), for threshold mode
PULL_TIMEOUT = Gst.SECOND // 10


def build_pipeline(args):
    if args.input:
        uri = args.input if Gst.uri_is_valid(args.input) else Gst.filename_to_uri(args.input)
        source = f'uridecodebin uri="{uri}"'
    else:
        source = (f"videotestsrc pattern=ball foreground-color=0xff20c020 num-buffers={args.frames} ! "
                  "video/x-raw,width=320,height=240,framerate=30/1")
    pipeline = Gst.parse_launch(
        f"{source} ! videoconvert ! video/x-raw,format=BGR ! colortrack name=tracker post-messages=true ! "
        "appsink name=sink sync=false max-buffers=4")
    tracker = pipeline.get_by_name("tracker")
    if args.mode == "threshold":
        tracker.set_property("mode", "threshold")
        if args.init_box:  # the element learns the colour range from the box on the first frame
            tracker.set_property("init-box", args.init_box)
            return pipeline
        lower, upper = (args.hsv_lower, args.hsv_upper) if args.hsv_lower else BALL_HSV
        tracker.set_property("hsv-lower", lower)
        tracker.set_property("hsv-upper", upper)
        return pipeline
    init_box = args.init_box or (None if args.input else BALL_INIT_BOX)
    if init_box:
        tracker.set_property("init-box", init_box)
    return pipeline


def objects_of(message):
    """Threshold mode's "objects" list of the message as dicts; None when PyGObject cannot read the list."""
    try:
        listed = message.get_value("objects")
    except TypeError:  # no python3-gst-1.0: "unknown type GstValueList"
        return None
    if listed is None:
        return []
    items = listed.array if hasattr(listed, "array") else list(listed)
    return [{"id": o.get_value("id"), "state": o.get_value("state"), "area": o.get_value("area"),
             "box": [round(o.get_value(k)) for k in ("x", "y", "width", "height")]} for o in items]


def track_record(pts, message, buffer):
    """The JSON object of one frame: the bus message's fields, the box and params from the buffer's meta."""
    record = {"time": pts / Gst.SECOND if pts != Gst.CLOCK_TIME_NONE else None, "frame": None, "id": 0,
              "box": None, "state": None, "score": None, "verified": None, "meta": False}
    if message is not None:
        record.update(frame=message.get_value("frame"), id=message.get_value("id"),
                      state=message.get_value("state"), score=message.get_value("score"),
                      verified=message.get_value("verified"))
        if message.has_field("objects"):
            record["objects"] = objects_of(message)
    if record["id"] > 0:
        roi = GstVideo.buffer_get_video_region_of_interest_meta_id(buffer, record["id"])
        if roi is not None and GLib.quark_to_string(roi.roi_type) == "colortrack":
            record.update(box=[roi.x, roi.y, roi.w, roi.h], meta=True)
            params = roi.get_param("colortrack")
            if params is not None:
                record.update(state=params.get_value("state"), score=params.get_value("score"),
                              verified=params.get_value("verified"))
    return record


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=150, help="frames of the test pattern (or to read)")
    parser.add_argument("--init-box", help='"x,y,w,h" of the object in the first frame')
    parser.add_argument("--mode", choices=("template", "threshold"), default="template",
                        help="colortrack's mode (threshold: every object in a colour range)")
    parser.add_argument("--hsv-lower", help='threshold mode: "h,s,v" lower end of the range')
    parser.add_argument("--hsv-upper", help='threshold mode: "h,s,v" upper end of the range')
    parser.add_argument("input", nargs="?", help="video file or URI (default: videotestsrc's ball)")
    args = parser.parse_args()
    if (args.hsv_lower is None) != (args.hsv_upper is None):
        parser.error("--hsv-lower and --hsv-upper go together")
    if args.hsv_lower and args.mode != "threshold":
        parser.error("--hsv-lower/--hsv-upper are for --mode threshold")
    if args.hsv_lower and args.init_box:
        parser.error("in threshold mode --init-box learns the colour range from the box: give it or "
                     "--hsv-lower/--hsv-upper, not both")

    Gst.init(None)
    try:
        pipeline = build_pipeline(args)
    except GLib.Error as e:
        sys.exit(f"pipeline: {e.message} (is the colortrack plugin on GST_PLUGIN_PATH?)")
    sink, bus = pipeline.get_by_name("sink"), pipeline.get_bus()
    pipeline.set_state(Gst.State.PLAYING)

    status = 0
    try:
        status = run(args, sink, bus)
    except BrokenPipeError:  # stdout closed early (| head): not an error of ours
        pass
    finally:
        pipeline.set_state(Gst.State.NULL)
    return status


def run(args, sink, bus):
    """Pulls frames until EOS, an error or --frames; prints one JSON line each. Returns the exit status."""
    # colortrack posts a frame's message before it pushes the buffer, so by the time the appsink hands us a
    # buffer its message is already on the bus: draining the bus after each pull pairs them by timestamp.
    messages = {}
    status, frames = 0, 0
    while args.input is None or args.frames <= 0 or frames < args.frames:
        sample = sink.emit("try-pull-sample", PULL_TIMEOUT)
        while (message := bus.pop()) is not None:
            if message.type == Gst.MessageType.ERROR:
                error, debug = message.parse_error()
                print(f"error from {message.src.get_name()}: {error.message}\n{debug or ''}", file=sys.stderr)
                status = 1
            elif message.type == Gst.MessageType.ELEMENT and message.get_structure().get_name() == "colortrack":
                s = message.get_structure()
                messages[s.get_value("timestamp")] = s
        if status:
            break
        if sample is None:
            if sink.get_property("eos"):
                break
            continue
        buffer = sample.get_buffer()
        record = track_record(buffer.pts, messages.pop(buffer.pts, None), buffer)
        if "objects" in record and record["objects"] is None and frames == 0:
            print("note: threshold mode's objects need GStreamer's Python overrides (Debian: python3-gst-1.0)",
                  file=sys.stderr)
        print(json.dumps(record), flush=True)
        frames += 1
    return status


if __name__ == "__main__":
    sys.exit(main())
