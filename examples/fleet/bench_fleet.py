#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""How many 720p30 camera pipelines one core sustains with colortrack: K gst-launch-1.0 pipelines pinned to one
core (taskset), decoding included (H.264 and MJPEG clips) and excluded (raw I420 frames from a file).

    examples/fleet/bench_fleet.py [--build build] [--cpu 0] [--frames 300] [--pipelines 1,4] [--runs 3]

Makes its clips once in BUILD/fleet-bench/: a 1280x720 30 fps scene (videotestsrc's SMPTE bars scrolling, its
ball on top) encoded with x264enc (veryfast, zerolatency, 4 Mbit/s, a key frame every 2 s: an IP camera's
stream; needs gstreamer1.0-plugins-ugly and, to decode, gstreamer1.0-libav, else skipped) and jpegenc
(quality 85, what UVC cameras send at 720p), and the raw I420 frames. Each case runs a long clip (FRAMES
frames) and a 30-frame one; the difference of their CPU time (user + system, from wait4) is the cost of
FRAMES - 30 frames without the start-up (plugin loading, the tracker's first frame), which a camera pipeline
that runs for days does not pay again. Prints, per case and K, the median over RUNS of:
  ms/frame     CPU per frame, start-up excluded
  fps/core     1000 / ms/frame: frames one core processes in a second
  cams@30      fps/core / 30: 720p30 pipelines one core sustains
  wall fps     K x FRAMES / wall time of the K long runs on the pinned core (start-up included; lower when
               other work shares the core)
The pipelines end in trackpublish location=/dev/null (the JSON documents built and written) and
fakesink sync=false (as fast as they go).
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time

WIDTH, HEIGHT = 1280, 720
SHORT = 30
INIT_BOX = "620,340,40,40"  # videotestsrc's ball (radius 20) at the frame centre in the first frame
TRACK = (f"videoconvert ! colortrack init-box={INIT_BOX} ! trackpublish location=/dev/null source=cam ! "
         "fakesink sync=false")


def gst(args, env, cpu=None):
    return subprocess.Popen((["taskset", "-c", cpu] if cpu is not None else []) + ["gst-launch-1.0", "-q"]
                            + args.split(), env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def has(env, *elements):
    return all(subprocess.run(["gst-inspect-1.0", "--exists", e], env=env).returncode == 0 for e in elements)


def make_clips(directory, frames, env):
    """The scene encoded as H.264 (if x264enc is there), MJPEG and raw I420, FRAMES and SHORT frames long."""
    h264 = has(env, "x264enc", "h264parse", "mp4mux")
    if not h264:
        print("note: no x264enc (Debian: gstreamer1.0-plugins-ugly): the H.264 rows are left out", file=sys.stderr)
    for n, tag in ((frames, "long"), (SHORT, "short")):
        if os.path.exists(os.path.join(directory, f"{tag}.i420")):
            continue
        outputs = (f"t. ! queue ! jpegenc quality=85 ! avimux ! filesink location={directory}/{tag}-mjpeg.avi "
                   f"t. ! queue ! filesink location={directory}/{tag}.i420.part ")
        if h264:
            outputs += (f"t. ! queue ! x264enc speed-preset=veryfast tune=zerolatency key-int-max=60 bitrate=4000 ! "
                        f"h264parse ! mp4mux ! filesink location={directory}/{tag}-h264.mp4")
        caps = f"video/x-raw,width={WIDTH},height={HEIGHT},framerate=30/1"
        p = gst(f"compositor name=mix background=black ! {caps} ! videoconvert ! video/x-raw,format=I420 ! "
                f"tee name=t "
                f"videotestsrc pattern=smpte horizontal-speed=3 num-buffers={n} ! {caps} ! videoconvert ! mix.sink_0 "
                f"videotestsrc pattern=ball background-color=0x00000000 num-buffers={n} ! "
                f"{caps.replace('x-raw,', 'x-raw,format=BGRA,')} ! videoconvert ! mix.sink_1 {outputs}", env)
        if p.wait() != 0:
            sys.exit("making the clips failed: " + p.stderr.read().decode()[-2000:])
        os.rename(f"{directory}/{tag}.i420.part", f"{directory}/{tag}.i420")


def cases(directory, env):
    raw = (f"filesrc location={directory}/{{tag}}.i420 blocksize={WIDTH * HEIGHT * 3 // 2} ! "
           f"rawvideoparse width={WIDTH} height={HEIGHT} format=i420 framerate=30/1")
    result = []
    if os.path.exists(f"{directory}/short-h264.mp4") and not has(env, "avdec_h264"):
        print("note: no avdec_h264 (Debian: gstreamer1.0-libav): the H.264 rows are left out", file=sys.stderr)
    if os.path.exists(f"{directory}/short-h264.mp4") and has(env, "avdec_h264"):
        h264 = f"filesrc location={directory}/{{tag}}-h264.mp4 ! decodebin"
        result += [("H.264 decode only", f"{h264} ! fakesink sync=false"),
                   ("H.264 decode + colortrack", f"{h264} ! {TRACK}")]
    mjpeg = f"filesrc location={directory}/{{tag}}-mjpeg.avi ! decodebin"
    result += [("MJPEG decode only", f"{mjpeg} ! fakesink sync=false"),
               ("MJPEG decode + colortrack", f"{mjpeg} ! {TRACK}"),
               ("raw frames only", f"{raw} ! fakesink sync=false"), ("raw frames + colortrack", f"{raw} ! {TRACK}")]
    return result


def run(pipeline, tag, k, env, cpu):
    """K pipelines at once on `cpu`: (CPU seconds of all, wall seconds)."""
    start = time.monotonic()
    processes = [gst(pipeline.format(tag=tag).replace("source=cam", f"source=cam{i}"), env, cpu) for i in range(k)]
    total = 0.0
    for p in processes:
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        if p.returncode != 0:
            sys.exit(f"failed ({p.returncode}): {pipeline.format(tag=tag)}\n{p.stderr.read().decode()[-2000:]}")
        total += usage.ru_utime + usage.ru_stime
    return total, time.monotonic() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build", help="the build directory (its gst/ has the plugin)")
    parser.add_argument("--cpu", default="0", help="taskset's CPU list for the pipelines (default: 0)")
    parser.add_argument("--frames", type=int, default=300, help="frames of the long clip (default: 300, 10 s)")
    parser.add_argument("--pipelines", default="1,4", help="numbers of pipelines at once (default: 1,4)")
    parser.add_argument("--runs", type=int, default=3, help="runs of each case; medians are printed")
    args = parser.parse_args()
    if not shutil.which("taskset") or not shutil.which("gst-launch-1.0"):
        sys.exit("needs taskset (util-linux) and gst-launch-1.0 (gstreamer1.0-tools)")

    directory = os.path.abspath(os.path.join(args.build, "fleet-bench"))
    os.makedirs(directory, exist_ok=True)
    env = dict(os.environ, GST_PLUGIN_PATH_1_0=os.path.abspath(os.path.join(args.build, "gst")),
               GST_REGISTRY_1_0=os.path.join(directory, "registry.bin"))
    make_clips(directory, args.frames, env)
    print(f"{WIDTH}x{HEIGHT} 30 fps, {args.frames}-frame clips minus {SHORT}-frame ones, pinned to CPU {args.cpu}, "
          f"median of {args.runs}; load average at the start {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")
    print(f"{'case':28} {'K':>2} {'ms/frame':>9} {'fps/core':>9} {'cams@30':>8} {'wall fps':>9}")
    for name, pipeline in cases(directory, env):
        for k in (int(x) for x in args.pipelines.split(",")):
            per_frame, wall_fps = [], []
            for _ in range(args.runs):
                cpu_long, wall = run(pipeline, "long", k, env, args.cpu)
                cpu_short, _ = run(pipeline, "short", k, env, args.cpu)
                per_frame.append(1000 * (cpu_long - cpu_short) / (k * (args.frames - SHORT)))
                wall_fps.append(k * args.frames / wall)
            ms = statistics.median(per_frame)
            print(f"{name:28} {k:2} {ms:9.2f} {1000 / ms:9.0f} {1000 / ms / 30:8.1f} "
                  f"{statistics.median(wall_fps):9.0f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
