# SPDX-License-Identifier: LGPL-2.1-or-later
"""colortrack-studio's latencies, printed (a meson benchmark: `meson test -C build --benchmark bench-studio-latency`).

Usage: bench_studio_latency.py COLORTRACK-STUDIO
On the built-in scene (320x240 at 30 fps, threshold mode, no robot), with the tests' own measurements:
1. capture -> page: each /video.mjpg part carries its capture time (X-Capture-Ns); the age of each part when an
   HTTP client on this machine has it whole (check_studio_http.check_latency). In headless chromium too,
   when it is installed: how many frames the picture in the <img> is behind the newest frame
   (check_studio_browser.page_latency).
2. click -> first tracked frame: /select on the ball to the element's first message about the new track
   (the studio's select_to_track_ms), three times.
3. STOP -> stop on the wire: with robotctl writing text commands to a pty and the ball followed, the time
   from sending POST /stop {"hold": true} to the first stop line on the pty, five times (released between).
Exit code 77 (skipped) without PyGObject. Nothing is checked against a limit: the figures are for
docs/benchmarks.md.
"""
import os
import statistics
import sys
import time

from check_studio_browser import browser, missing_tools, page_latency
from check_studio_http import check_latency
from studio_harness import SKIP, STOP_LINE, Studio, gi_missing



def browser_lag(studio):
    missing, chromium, driver_path = missing_tools()
    if missing:
        print(f"capture -> page in chromium: not measured (missing {', '.join(missing)})")
        return
    driver = browser(chromium, driver_path)
    try:
        driver.get(studio.url)
        lags = page_latency(driver, studio, samples=30)
    finally:
        driver.quit()
    if lags:
        median = lags[len(lags) // 2]
        print(f"capture -> page in headless chromium: median {median} frame(s) ({median * 1000 / 30:.0f} ms at "
              f"30 fps) behind the newest frame, range {lags[0]}..{lags[-1]} over {len(lags)} samples")


def stop_latency(program):
    """POST /stop {"hold": true} -> the first stop line on the robot's pty, while the robot follows the ball."""
    studio = Studio(program, "--robot-protocol", "text")
    times = []
    try:
        studio.select_ball()
        for _ in range(5):
            if not studio.wait_moving(3.0):
                print("STOP -> stop on the wire: the robot did not move; not measured")
                return
            studio.read_robot()  # what was on its way before the request
            asked = time.monotonic()
            studio.post("/stop", {"hold": True})
            seen = b""
            while STOP_LINE not in seen and time.monotonic() - asked < 2:
                seen += studio.read_robot(0.001)
            times.append((time.monotonic() - asked) * 1000)
            studio.post("/stop", {"hold": False})
    finally:
        studio.close()
    print(f"STOP (POST /stop) -> first stop line on the robot's pty (robotctl rate 10 Hz): median "
          f"{statistics.median(times):.1f} ms, max {max(times):.1f} ms over {len(times)} presses")


def main():
    program = sys.argv[1]
    missing = gi_missing()
    if missing:
        print(f"SKIPPED: missing {missing}")
        return SKIP
    print(f"machine: {os.cpu_count()} cores; studio {program}")
    studio = Studio(program, robot=False)
    failures = []
    try:
        host, port = studio.url.split("//")[1].rstrip("/").split(":")
        check_latency(studio, host, int(port), failures)
        browser_lag(studio)
    finally:
        studio.close()
    stop_latency(program)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
