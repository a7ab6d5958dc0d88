# SPDX-License-Identifier: LGPL-2.1-or-later
"""colortrack-studio in a real headless browser (Debian's chromium and chromedriver, through selenium).

Usage: check_studio_browser.py COLORTRACK-STUDIO [SCREENSHOT-FOLDER]
On the built-in scene (videotestsrc's green ball, threshold mode, robotctl writing text commands to a pty):
loads the page, sees frames arrive in the video and the mask and the picture move with the ball, clicks on the
ball, checks through /state that a track follows it (IoU >= 0.5 between a box of colortrack's metadata, the
region-of-interest metas on its buffers, and the ball's true box on that buffer's frame), presses STOP and reads only
stop on the pty, releases it and sees the robot move again, lowers the upper hue with the keyboard and sees
the ball leave the mask and the track list. Screenshots go to SCREENSHOT-FOLDER (default: the current one).
Exit code 77 (skipped) without chromium, chromedriver, selenium or PyGObject (1 with COLORTRACK_REQUIRE_BROWSER=1,
as CI sets it).
"""
import os
import shutil
import sys
import time

from studio_harness import RADIUS, SKIP, STOP_LINE, Studio, ball_box, gi_missing, meta_iou

CLICK_BOX = 24   # the page's square for a click (studio.html)
SHOWN_WIDTH = 480  # the page shows the 320x240 video 480 px wide


def missing_tools():
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver = shutil.which("chromedriver")
    missing = [] if chromium else ["chromium"]
    missing += [] if driver else ["chromedriver (Debian: chromium-driver)"]
    try:
        import selenium  # noqa: F401
    except ImportError:
        missing.append("selenium (Debian: python3-selenium)")
    gi = gi_missing()
    missing += [gi] if gi else []
    return missing, chromium, driver


def browser(chromium, driver):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1200,1000", "--no-first-run", "--disable-extensions"):
        options.add_argument(arg)
    return webdriver.Chrome(service=Service(driver), options=options)


def wait(what, predicate, timeout=15, step=0.1):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(step)
    raise AssertionError(f"timed out waiting for {what}")


MAGENTA_JS = """
const img = document.getElementById(arguments[0]);
if (!img.naturalWidth) return -1;
const c = document.createElement('canvas'); c.width = img.naturalWidth; c.height = img.naturalHeight;
const g = c.getContext('2d'); g.drawImage(img, 0, 0);
const d = g.getImageData(0, 0, c.width, c.height).data;
let n = 0;
for (let i = 0; i < d.length; i += 4) if (d[i] > d[i + 1] + 30 && d[i + 2] > d[i + 1] + 30) n++;
return n;
"""


GREEN_CENTRE_JS = """
const img = document.getElementById('video');
const c = document.createElement('canvas'); c.width = img.naturalWidth; c.height = img.naturalHeight;
const g = c.getContext('2d'); g.drawImage(img, 0, 0);
const d = g.getImageData(0, 0, c.width, c.height).data;
let n = 0, sx = 0, sy = 0;
for (let i = 0; i < d.length; i += 4)
  if (d[i + 1] > d[i] + 60 && d[i + 1] > d[i + 2] + 60) { n++; sx += (i / 4) % c.width; sy += Math.floor(i / 4 / c.width); }
return n ? [sx / n, sy / n, n] : null;
"""


def page_latency(driver, studio, samples=15, shown_frames=None):
    """How many frames the picture on the page is behind the studio's newest frame: the ball's centre in the
    <img> (no overlay yet: nothing is tracked) gives the frame shown, /state right after it the newest. The
    frames shown are added to `shown_frames` (a set) if given."""
    lags = []
    for _ in range(samples):
        centre = driver.execute_script(GREEN_CENTRE_JS)
        newest = studio.get("/state")["test_frame"]
        if centre:
            shown = min(range(newest - 60, newest + 3), key=lambda n: (ball_box(n)[0] + RADIUS - centre[0]) ** 2
                        + (ball_box(n)[1] + RADIUS - centre[1]) ** 2)
            lags.append(newest - shown)
            if shown_frames is not None:
                shown_frames.add(shown)
        time.sleep(0.13)
    return sorted(lags)


def check_frames_arrive(driver, studio, failures):
    """Both views get pictures, the studio keeps serving frames, and the picture on the page moves with the
    ball (a frozen <img> shows one frame), at most 30 frames behind the newest."""
    wait("the video", lambda: driver.execute_script("return document.getElementById('video').naturalWidth") > 0)
    wait("the mask", lambda: driver.execute_script("return document.getElementById('mask').naturalWidth") > 0)
    first = studio.get("/state")["video_frames"]
    wait("more frames", lambda: studio.get("/state")["video_frames"] >= first + 15)
    print(f"frames arrive: {studio.get('/state')['video_frames']} served")
    shown = set()
    lags = page_latency(driver, studio, shown_frames=shown)
    if len(shown) < 5:
        failures.append(f"the page's picture does not move with the ball: frames shown {sorted(shown)}")
        return
    median = lags[len(lags) // 2]
    print(f"page latency: the picture in the page is {median} frame(s) ({median * 1000 / 30:.0f} ms at 30 fps) "
          f"behind the studio's newest frame (median of {len(lags)}; all: {lags}; {len(shown)} frames shown)")
    if median > 30:
        failures.append(f"the page shows frames {median} behind the newest")


def on_ball(studio):
    """The IoU with the ball's true box of the best box in colortrack's metadata (studio_harness.meta_iou),
    and the state it was read from."""
    state = studio.get("/state")
    return meta_iou(state), state


def ball_speed(n):
    """Pixels the ball moves between frame n and n + 1."""
    a, b = ball_box(n), ball_box(n + 1)
    return ((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) ** 0.5


def click_ball(driver, studio, actions_class, lead):
    """Clicks where the ball will be `lead` frames after the frame /state reports (the time /state, the
    browser and the click take to reach the studio), at a moment when the ball moves slowly there.
    Returns the frame aimed at and the frame /state reported."""
    video = driver.find_element("id", "video")
    deadline = time.monotonic() + 15
    while True:
        state = studio.get("/state")
        n = state["test_frame"] + lead
        if ball_speed(n) < 3 or time.monotonic() > deadline:
            break
        time.sleep(0.03)
    x, y, w, h = ball_box(n)
    scale = video.size["width"] / state["width"]
    dx = (x + w / 2 - state["width"] / 2) * scale   # selenium's offsets are from the element's centre
    dy = (y + h / 2 - state["height"] / 2) * scale
    actions_class(driver).move_to_element_with_offset(video, round(dx), round(dy)).click().perform()
    return n, state["test_frame"]


def main():
    program = sys.argv[1]
    folder = sys.argv[2] if len(sys.argv) > 2 else os.getcwd()
    os.makedirs(folder, exist_ok=True)
    missing, chromium, driver_path = missing_tools()
    if missing:
        if os.environ.get("COLORTRACK_REQUIRE_BROWSER") == "1":  # CI (.ci/run): a missing browser fails
            print(f"FAIL: missing {', '.join(missing)} and COLORTRACK_REQUIRE_BROWSER=1")
            return 1
        print(f"SKIPPED: missing {', '.join(missing)}")
        return SKIP
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys

    studio = Studio(program)
    driver = None
    failures = []
    try:
        driver = browser(chromium, driver_path)
        driver.get(studio.url)
        shot = lambda name: driver.save_screenshot(os.path.join(folder, f"studio-{name}.png"))  # noqa: E731

        check_frames_arrive(driver, studio, failures)
        shot("1-loaded")

        # Click on the ball (up to three times: the ball moves ~4 px a frame), then a track on it.
        best, attempts, lead = 0.0, 0, 8
        for attempts in range(1, 5):
            aimed, read = click_ball(driver, studio, ActionChains, lead)
            try:
                wait("a track", lambda: on_ball(studio)[0] >= 0.5, timeout=3)
                break
            except AssertionError:
                arrived = studio.get("/state")["last_select"]
                lead = arrived["frame"] - read + 1 if arrived else lead
                print(f"click {attempts} (aimed at frame {aimed}, ball {ball_box(aimed)}): no track on the ball "
                      f"yet; the studio got {studio.get('/state')['last_select']}")
        ious = []
        for _ in range(20):  # the track stays on the ball
            best, state = on_ball(studio)
            ious.append(best)
            time.sleep(0.1)
        good = sum(v >= 0.5 for v in ious)
        print(f"after {attempts} click(s): IoU >= 0.5 in {good}/20 polls (min {min(ious):.2f}, "
              f"max {max(ious):.2f}); learnt {state['settings']}; click to first tracked frame "
              f"{state['select_to_track_ms']} ms")
        if good < 18:
            failures.append(f"the track is on the ball in only {good}/20 polls")
        wait("the track list", lambda: driver.find_elements("css selector", "#tracks tr"))
        shot("2-tracking")

        # STOP: only stop goes to the robot until release; after release it moves again.
        studio.read_robot()
        moving = studio.read_robot(1.0)
        if not moving.replace(STOP_LINE, b""):
            failures.append(f"the robot did not move while tracking: {moving[-60:]!r}")
        driver.find_element("id", "stop").click()
        wait("STOP held", lambda: studio.get("/state")["robot"]["stopped"], timeout=5)
        studio.read_robot(0.3)   # what was on its way when STOP was pressed
        held = studio.read_robot(1.5)
        shot("3-stopped")
        if not held or held.replace(STOP_LINE, b""):
            failures.append(f"while STOP is held the pty got {held[-80:]!r}, not only stop")
        else:
            print(f"STOP: {held.count(STOP_LINE)} stop lines in 1.5 s, nothing else")
        driver.find_element("id", "stop").click()
        wait("release", lambda: not studio.get("/state")["robot"]["stopped"], timeout=5)
        after = studio.read_robot(2.0)
        if not after.replace(STOP_LINE, b""):
            failures.append(f"after release the robot never moved: {after[-60:]!r}")
        else:
            print("released: the robot moves again")

        # The upper hue slider down below the ball's hue (132): the ball leaves the mask and the tracks.
        magenta_before = driver.execute_script(MAGENTA_JS, "mask")
        upper_before = studio.get("/state")["settings"]["hsv-upper"]
        slider = driver.find_element("id", "h1")
        steps = int(float(upper_before.split(",")[0])) - 125
        slider.send_keys(*([Keys.ARROW_LEFT] * max(steps, 0)))
        wait("the new upper hue", lambda: studio.get("/state")["settings"]["hsv-upper"].startswith("125,"), timeout=5)
        wait("no object on the ball", lambda: on_ball(studio)[0] < 0.1 and not studio.get("/state")["objects"],
             timeout=5)
        time.sleep(0.5)
        magenta_after = driver.execute_script(MAGENTA_JS, "mask")
        rows = driver.find_elements("css selector", "#tracks tr")
        print(f"hue slider: hsv-upper {upper_before} -> {studio.get('/state')['settings']['hsv-upper']}; "
              f"magenta pixels in the mask {magenta_before} -> {magenta_after}; track rows {len(rows)}")
        if not magenta_before > 500 > 50 > magenta_after:
            failures.append(f"the mask did not change: {magenta_before} -> {magenta_after} magenta pixels")
        if rows:
            failures.append("the track list still shows objects")
        shot("4-hue-moved")
    except AssertionError as e:
        failures.append(str(e))
    finally:
        if driver is not None:
            driver.quit()
        alive = studio.alive()
        studio.close()
    if not alive:
        failures.append("colortrack-studio died")
    for f in failures:
        print("FAIL:", f)
    print(f"screenshots in {folder}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
