# SPDX-License-Identifier: LGPL-2.1-or-later
"""colortrack-studio's HTTP side without a browser: a fuzz of the endpoints, the token, and the latency.

Usage: check_studio_http.py COLORTRACK-STUDIO
1. Fuzz (studio on 127.0.0.1, robotctl writing to a pty, nothing of the default red range in the scene, so
   the robot's only command is stop): bad JSON, bodies over the limit, wrong types and out-of-range values on
   every endpoint, broken request lines and headers, random bytes, requests as another site's page would
   send them (another Host, an Origin, a form or text/plain body: 403 or 415), and slow clients sending one
   byte at a time. Every answer must be a 4xx (never 2xx for a bad request, never 5xx), the studio must stay
   alive, print no traceback and answer /state promptly throughout, no track may start, and the pty must get
   nothing but stop.
2. Token: the studio listening on 0.0.0.0 refuses every request without the token (403), from loopback and
   from the machine's other address, and serves it with the token (header or ?token=).
3. Template mode: /select on the ball gives a track on it (IoU >= 0.5); threshold settings are refused (409).
4. Presets: /save with --preset-out writes colortrack's GstPreset file there (gst_preset_save_preset) and
   nowhere else; a studio started with --preset NAME has the saved settings.
5. Signals: SIGTERM or SIGHUP while the robot follows the ball: the studio exits 0 and the robot's last
   command is stop.
6. Latency: capture to receipt of /video.mjpg parts by an HTTP client on this machine, and /select to the
   first tracked frame; printed.
Exit code 77 (skipped) without PyGObject.
"""
import json
import os
import random
import signal
import socket
import statistics
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

from studio_harness import SKIP, STOP_LINE, Studio, ball_box, gi_missing, meta_iou



def raw_request(host, port, data, timeout=5.0, read=True):
    """Sends bytes, returns the status code of the answer (0: connection closed without one)."""
    with socket.create_connection((host, port), timeout=timeout) as s:
        try:
            s.sendall(data)
        except (BrokenPipeError, ConnectionResetError):
            pass  # the server refused the rest (an oversized body): its answer may still be there
        if not read:
            return None
        reply = b""
        try:
            while b"\r\n" not in reply:
                chunk = s.recv(4096)
                if not chunk:
                    break
                reply += chunk
        except (ConnectionResetError, socket.timeout):
            pass
    try:
        return int(reply.split(b" ", 2)[1])
    except (IndexError, ValueError):
        return 0


def post_bytes(path, body, content_type="application/json", extra=b""):
    return (f"POST {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: {content_type}\r\n"
            f"Content-Length: {len(body)}\r\n".encode() + extra + b"\r\n" + body)


# The answer a request from another site must get, whatever else is wrong with it.
CROSS_SITE = {"Host evil.example": 403, "GET Host evil.example": 403, "Origin evil.example": 403,
              "text/plain body": 415, "form body": 415, "no Host": 403}


def fuzz_cases(rng):
    """(name, request bytes) pairs, every one a request the studio must refuse."""
    cases = []
    bad_bodies = [b"", b"{", b"null", b"[]", b"42", b'"x"', b"{'x': 1}", b"\xff\xfe\x00", b"{" * 5000 + b"}" * 5000,
                  b'{"x": NaN}', b"[" * 100000]
    for path in ("/select", "/settings", "/stop", "/save"):
        for body in bad_bodies:
            cases.append((f"{path} body {body[:12]!r}", post_bytes(path, body)))
    wrong = [None, True, False, "12", [], {}, [1, 2], 1e308, -1e308, float("inf"), -5, 10 ** 30, "1,2,3", "x" * 1000]
    for value in wrong:
        for key in ("x", "y", "w", "h"):
            body = {"x": 100, "y": 100, "w": 30, "h": 30, key: value}
            cases.append((f"/select {key}={value!r:.20}", post_bytes("/select", json.dumps(body).encode())))
        for key in ("hsv-lower", "hsv-upper", "min-area", "morph-size"):
            cases.append((f"/settings {key}={value!r:.20}", post_bytes("/settings", json.dumps({key: value}).encode())))
        if not isinstance(value, bool):  # true and false are /stop's two good values
            cases.append((f"/stop hold={value!r:.20}", post_bytes("/stop", json.dumps({"hold": value}).encode())))
    # A preset name is a key-file group: nothing that could end the group, escape a folder or be empty.
    for name in (None, True, 5, [], {}, "", "a]b", "[x]", "a\nb", "../../x", "a/b", "x" * 65, " lead", "a=b", "é"):
        cases.append((f"/save name={name!r:.20}", post_bytes("/save", json.dumps({"name": name}).encode())))
    for body in ({"x": -500, "y": -500, "w": 20, "h": 20}, {"x": 5000, "y": 0, "w": 40, "h": 40},
                 {"x": 0, "y": 0, "w": 4, "h": 4}, {"x": 0, "y": 0}):
        cases.append((f"/select {body}", post_bytes("/select", json.dumps(body).encode())))
    for body in ({"hsv-lower": "0,1,1", "hsv-upper": "360,0.5,0.5"}, {"hsv-lower": "400,0,0"},
                 {"hsv-lower": "1,2"}, {"hsv-lower": "a,b,c"}, {"hsv-lower": [1, 2, 3, 4]}, {"min-area": 0},
                 {"min-area": 320 * 240 + 1}, {"morph-size": 256}, {"drop": 1}, {"hsv-lower": ["1", None, 0]}):
        cases.append((f"/settings {body}", post_bytes("/settings", json.dumps(body).encode())))
    # Over the 64 KiB limit, announced and sent; announced and not sent; chunked; broken lengths.
    big = b'{"x": "' + b"a" * (70 * 1024) + b'"}'
    cases.append(("/settings 70 KiB", post_bytes("/settings", big)))
    cases.append(("/select Content-Length 10**9", b"POST /select HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: 1000000000\r\n\r\n{}"))
    cases.append(("/stop chunked", b"POST /stop HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nhello\r\n0\r\n\r\n"))
    cases.append(("/stop Content-Length x", b"POST /stop HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: x\r\n\r\n"))
    cases.append(("/stop Content-Length -1", b"POST /stop HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: -1\r\n\r\n"))
    cases.append(("/stop short body", b"POST /stop HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: 50\r\n\r\n{\"hold\": true}"))
    # Broken requests: http.server's own parser answers them.
    cases.append(("garbage line", b"GARBAGE\r\n\r\n"))
    cases.append(("long URL", b"GET /" + b"a" * 70000 + b" HTTP/1.1\r\n\r\n"))
    cases.append(("many headers", b"GET /state HTTP/1.1\r\n" + b"X: y\r\n" * 200 + b"\r\n"))
    cases.append(("unknown path", b"POST /shutdown HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                                  b"Content-Length: 2\r\n\r\n{}"))
    cases.append(("unknown method", b"DELETE /state HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"))
    cases.append(("path traversal", b"GET /../../etc/passwd HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"))
    # Another site's page: a name made to point here (DNS rebinding), its Origin, a form or text/plain body
    # (sent by a browser without asking), no Host at all.
    # (A hold or a select let through would show in the studio's state, checked after the fuzz.)
    release = b'{"hold": true}'
    cases.append(("Host evil.example", post_bytes("/stop", release).replace(b"Host: 127.0.0.1", b"Host: evil.example:8550")))
    cases.append(("GET Host evil.example", b"GET /state HTTP/1.1\r\nHost: evil.example\r\n\r\n"))
    cases.append(("Origin evil.example", post_bytes("/stop", release, extra=b"Origin: http://evil.example\r\n")))
    cases.append(("text/plain body", post_bytes("/stop", release, content_type="text/plain")))
    cases.append(("form body", post_bytes("/select", b"x=1&y=1&w=30&h=30", content_type="application/x-www-form-urlencoded")))
    cases.append(("no Host", b"POST /stop HTTP/1.1\r\nContent-Type: application/json\r\nContent-Length: 15\r\n\r\n" + release))
    for i in range(40):  # random bytes, some after a valid request line
        junk = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400)))
        head = b" HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: 300\r\n\r\n"
        prefix = rng.choice([b"", b"POST /select" + head, b"POST /stop" + head])
        cases.append((f"random {i}", prefix + junk))
    return cases


def slow_client(host, port, data, gap, results):
    try:
        with socket.create_connection((host, port), timeout=30) as s:
            for byte in data:
                s.sendall(bytes([byte]))
                time.sleep(gap)
            reply = s.recv(200)
            results.append(int(reply.split(b" ", 2)[1]) if reply else 0)
    except OSError as e:
        results.append(f"error {e}")


def check_fuzz(program, failures):
    studio = Studio(program, "--request-timeout", "1")
    host, port = studio.url.split("//")[1].rstrip("/").split(":")
    port = int(port)
    try:
        studio.read_robot(0.5)
        rng = random.Random(50)
        cases = fuzz_cases(rng)
        statuses, unanswered = {}, []
        for name, data in cases:
            status = raw_request(host, port, data)
            statuses[status] = statuses.get(status, 0) + 1
            if status == 0:
                unanswered.append(name)
            if not (400 <= status < 500 or status == 0):
                failures.append(f"fuzz {name}: HTTP {status}")
            if name in CROSS_SITE and status != CROSS_SITE[name]:
                failures.append(f"fuzz {name}: HTTP {status}, not {CROSS_SITE[name]}")
            if not studio.alive():
                failures.append(f"fuzz {name}: the studio died")
                return
        print(f"fuzz: {len(cases)} bad requests, answers {dict(sorted(statuses.items()))} (0: the connection "
              f"closed without an answer: {', '.join(unanswered) or 'none'})")

        # Slow clients: 8 bad requests one byte every 50 ms (~5 s each), one that stops half way; /state
        # stays prompt meanwhile (2 s allowed: the machine may be busy).
        results = []
        slow = [threading.Thread(target=slow_client, args=(host, port, post_bytes("/stop", b'{"hold": "yes"}'),
                                                               0.05, results)) for _ in range(8)]
        half = socket.create_connection((host, port))
        half.sendall(b"POST /stop HTTP/1.1\r\nContent-Le")
        for t in slow:
            t.start()
        worst = 0.0
        for _ in range(20):
            start = time.monotonic()
            studio.get("/state")
            worst = max(worst, time.monotonic() - start)
            time.sleep(0.1)
        for t in slow:
            t.join(60)
        half.settimeout(10)
        start = time.monotonic()
        cut = half.recv(100) == b""
        half.close()
        if not cut:
            failures.append("a client stuck half way through its headers was not cut off")
        print(f"slow clients: answers {results}; /state meanwhile at most {worst * 1000:.0f} ms; a client stuck "
              f"half way through its headers {'cut off' if cut else 'NOT cut off'} after "
              f"{time.monotonic() - start:.1f} s more")
        if any(r != 400 for r in results):
            failures.append(f"slow clients: {results}")
        if worst > 2.0:  # each slow client takes ~5 s: /state is not waiting for them
            failures.append(f"/state took {worst:.2f} s during the slow clients")

        state = studio.get("/state")
        robot = studio.read_robot(0.5)
        others = studio.robot_bytes.replace(STOP_LINE, b"")
        print(f"robot pty during the fuzz: {len(studio.robot_bytes)} bytes, "
              f"{studio.robot_bytes.count(STOP_LINE)} stop lines, {len(others)} other bytes")
        if others:
            failures.append(f"the robot got something else than stop: {others[:80]!r}")
        if not robot:
            failures.append("the robot pty went silent (robotctl repeats stop at 10 Hz)")
        if state["objects"] or state["last_select"] or state["robot"]["stopped"]:
            failures.append(f"a bad request changed the studio: {state}")
        if state["settings"] != {"hsv-lower": "340,0.5,0.25", "hsv-upper": "20,1,1", "min-area": 50, "morph-size": 5}:
            failures.append(f"a bad request changed the settings: {state['settings']}")
        if not studio.alive():
            failures.append("the studio died")
        status, saved = studio.post("/save", {})
        if status != 200 or "colortrack mode=threshold hsv-lower=340,0.5,0.25" not in saved.get("launch", "") \
                or saved.get("written") is not None or "hsv-upper=20,1,1" not in saved.get("preset", ""):
            failures.append(f"/save without --preset-out: {status} {saved}")
        check_latency(studio, host, port, failures)
    finally:
        code = studio.close()
        if code not in (0, -15):
            failures.append(f"the studio exited with {code}")
        if studio.tracebacks() or "internal error" in studio.errors:
            failures.append(f"the fuzz made the studio print {studio.tracebacks()} traceback(s) or an internal error")


def check_latency(studio, host, port, failures):
    """Capture to receipt of /video.mjpg parts here; /select on the ball to its first tracked frame."""
    ages = []
    with socket.create_connection((host, port), timeout=5) as s:
        s.sendall(b"GET /video.mjpg HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        buf = b""
        while len(ages) < 90:
            chunk = s.recv(65536)
            if not chunk:
                break
            now = time.monotonic_ns()
            buf += chunk
            while True:
                head_end = buf.find(b"\r\n\r\n", buf.find(b"--frame"))
                if buf.find(b"--frame") < 0 or head_end < 0:
                    break
                head = buf[buf.find(b"--frame"):head_end].decode(errors="replace")
                fields = dict(line.split(": ", 1) for line in head.split("\r\n")[1:] if ": " in line)
                length = int(fields["Content-Length"])
                if len(buf) < head_end + 4 + length:
                    break
                ages.append((now - int(fields["X-Capture-Ns"])) / 1e6)
                buf = buf[head_end + 4 + length:]
    if len(ages) < 60:
        failures.append(f"only {len(ages)} MJPEG parts read")
        return
    ages = ages[10:]
    print(f"latency capture -> MJPEG part received (HTTP client on this machine, 320x240 at 30 fps): median "
          f"{statistics.median(ages):.1f} ms, max {max(ages):.1f} ms over {len(ages)} frames")
    # /select on the middle of the ball's true box (threshold mode learns its colour from it).
    times = []
    for _ in range(3):
        studio.select_ball()
        deadline = time.monotonic() + 3
        while time.monotonic() < deadline and studio.get("/state")["select_to_track_ms"] is None:
            time.sleep(0.02)
        times.append(studio.get("/state")["select_to_track_ms"])
        time.sleep(0.5)
    print(f"/select to the first tracked frame's message: {times} ms (the element reports a track after "
          "3 detections)")


def check_token(program, failures):
    studio = Studio(program, "--listen", "0.0.0.0", robot=False)
    try:
        port = int(studio.url.rsplit(":", 1)[1].rstrip("/"))
        if not studio.token:
            failures.append("no token printed for --listen 0.0.0.0")
            return
        hosts = ["127.0.0.1"]
        try:
            probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            probe.connect(("192.0.2.1", 9))  # no packet sent: only picks the outgoing interface's address
            other = probe.getsockname()[0]
            probe.close()
            if not other.startswith("127."):
                hosts.append(other)
        except OSError:
            pass
        for host in hosts:
            base = f"http://{host}:{port}"
            for path, data in (("/", None), ("/state", None), ("/video.mjpg", None), ("/stop", b'{"hold": true}'),
                               ("/state?token=wrong", None)):
                try:
                    urllib.request.urlopen(urllib.request.Request(base + path, data=data), timeout=5).close()
                    failures.append(f"{host}{path} without the token: served")
                except urllib.error.HTTPError as e:
                    if e.code != 403:
                        failures.append(f"{host}{path} without the token: HTTP {e.code}, not 403")
            with urllib.request.urlopen(f"{base}/state?token={studio.token}", timeout=5) as r:
                ok_query = r.status
            req = urllib.request.Request(f"{base}/state", headers={"X-Studio-Token": studio.token})
            with urllib.request.urlopen(req, timeout=5) as r:
                ok_header = r.status
            if (ok_query, ok_header) != (200, 200):
                failures.append(f"{host}: with the token {ok_query}, {ok_header}")
            print(f"token: {host} refused without it (403), served with it (?token= and X-Studio-Token)")
    finally:
        studio.close()


def check_template(program, failures):
    """Template mode: /select on the ball's box gives a track on it; the threshold settings are refused."""
    studio = Studio(program, "--mode", "template", robot=False)
    try:
        state = studio.get("/state")
        x, y, w, h = ball_box(state["test_frame"] + 1)
        status, _ = studio.post("/select", {"x": round(x), "y": round(y), "w": w, "h": h})
        time.sleep(0.5)
        ious = []
        for _ in range(10):
            state = studio.get("/state")
            ious.append(meta_iou(state))
            time.sleep(0.1)
        refused, _ = studio.post("/settings", {"min-area": 5})
        _, saved = studio.post("/save", {})
        launch = saved.get("launch", "")
        print(f"template mode: /select {status}; IoU with the ball {min(ious):.2f}..{max(ious):.2f}; /settings {refused}; "
              f"/save gives {launch!r}")
        if status != 200 or min(ious) < 0.5 or refused != 409 or f"init-box={round(x)},{round(y)}," not in launch:
            failures.append(f"template mode: select {status}, IoU {ious}, settings {refused}, launch {launch!r}")
    finally:
        studio.close()


def check_preset(program, failures):
    """/save writes a GstPreset under --preset-out only; --preset loads it into a new studio."""
    chosen = {"hsv-lower": "350,0.4,0.3", "hsv-upper": "25,1,0.9", "min-area": 77, "morph-size": 3}
    with tempfile.TemporaryDirectory() as out:
        studio = Studio(program, "--preset-out", out, robot=False)
        try:
            applied, _ = studio.post("/settings", chosen)
            status, saved = studio.post("/save", {"name": "outdoor 2"})
        finally:
            studio.close()
        files = sorted(os.path.relpath(os.path.join(d, f), out) for d, _, fs in os.walk(out) for f in fs)
        studio = Studio(program, "--preset-out", out, "--preset", "outdoor 2", robot=False)
        try:
            loaded = studio.get("/state")["settings"]
        finally:
            studio.close()
    print(f"preset: /settings {applied}, /save {status} wrote {files}; loaded back {loaded}")
    if (applied, status) != (200, 200) or files != ["gstreamer-1.0/presets/GstColorTrack.prs"] \
            or "[outdoor 2]" not in saved.get("preset", "") or loaded != chosen:
        failures.append(f"preset: settings {applied}, save {status} {saved}, files {files}, loaded {loaded}")


def check_signals(program, failures):
    """SIGTERM (systemd) and SIGHUP (ssh gone) while the robot follows the ball: exit 0, last command stop."""
    for signum in (signal.SIGTERM, signal.SIGHUP):
        studio = Studio(program)
        try:
            studio.select_ball()
            moving = studio.wait_moving()
            studio.proc.send_signal(signum)
            code = studio.proc.wait(15)
            last = (studio.read_robot(0.3).rstrip(b"\n").rsplit(b"\n", 1) or [b""])[-1] + b"\n"
        finally:
            studio.close()
        name = signal.Signals(signum).name
        print(f"{name} while {'moving' if moving else 'NOT moving'}: exit {code}, last command {last!r}")
        if not moving or code != 0 or last != STOP_LINE:
            failures.append(f"{name}: moving {moving}, exit {code}, last command {last!r}")


def main():
    program = sys.argv[1]
    missing = gi_missing()
    if missing:
        print(f"SKIPPED: missing {missing}")
        return SKIP
    failures = []
    check_fuzz(program, failures)
    check_token(program, failures)
    check_template(program, failures)
    check_preset(program, failures)
    check_signals(program, failures)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
