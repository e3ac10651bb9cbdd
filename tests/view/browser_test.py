#!/usr/bin/env python3
"""The live view in a real browser: sculpt --view serves the page, headless Chromium (Selenium)
opens it, and the test reads the pixels the page drew.

  browser_test.py SCULPT OUTDIR

Checks: the page shows the model (pixels of each part's colour); editing the script updates the
page (and how long that took); an error shows file:line:col with its caret and keeps the model;
fixing it clears the error; hiding a part hides its pixels; Ctrl-C ends sculpt. Saves a screenshot
as OUTDIR/view.png (docs/viewing.md's picture comes from here). Exit 77 (skipped) when Chromium,
chromedriver or Selenium is missing.
"""
import os
import pty
import re
import select
import shutil
import signal
import subprocess
import sys
import time

SKIP = 77
sculpt, outdir = sys.argv[1], sys.argv[2]
os.makedirs(outdir, exist_ok=True)

try:
    from selenium import webdriver
    from selenium.webdriver.common.by import By
except ImportError:
    print("view.browser: skipped: python3-selenium is not installed")
    sys.exit(SKIP)
chromium = shutil.which("chromium") or shutil.which("chromium-browser")
driver_path = shutil.which("chromedriver") or ("/usr/bin/chromedriver" if os.path.exists("/usr/bin/chromedriver") else None)
if not chromium or not driver_path:
    print("view.browser: skipped: chromium or chromium-driver is not installed")
    sys.exit(SKIP)

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


RED = [0.85, 0.2, 0.2]  # show(..., color="red") (lib/language/builtins_view.cpp)
BLUE = [0.25, 0.45, 0.85]  # color="blue"
script = os.path.join(outdir, "model.bsp")
GOOD = """block = box([0, 0, 0], [2, 1, 1]) - box([1.5, -1, 0.5], [3, 2, 2])
show(block, name="block", color="red")
show(translate(sphere(0.5, segments=24), [3, 0.5, 0.5]), name="ball", color="blue")
"""
EDITED = GOOD.replace("[2, 1, 1]", "[2, 1, 1.5]")
BROKEN = EDITED + "oops = box([0, 0, 0], [1, 1)\n"


def write(text):
    with open(script + ".tmp", "w") as f:
        f.write(text)
    os.replace(script + ".tmp", script)  # as editors save: the new file at once


def repl_view(driver, state, wait_for):
    pid, fd = pty.fork()
    if pid == 0:
        os.environ["TERM"] = "dumb"
        os.environ["HOME"] = outdir  # the REPL's history file goes there
        os.execv(sculpt, [sculpt, "--port", "0"])
    screen = ""

    def read_until(pattern, seconds=10):
        nonlocal screen
        end = time.time() + seconds
        while time.time() < end:
            m = re.search(pattern, screen)
            if m:
                return m
            ready, _, _ = select.select([fd], [], [], 0.1)
            if ready:
                try:
                    screen += os.read(fd, 4096).decode("utf-8", "replace")
                except OSError:
                    break
        return re.search(pattern, screen)

    try:
        read_until(r"sculpt> ")
        os.write(fd, b":view\n")
        m = read_until(r"view: (http://127\.0\.0\.1:\d+/)")
        check(m is not None, ":view prints the page's address")
        if not m:
            return
        driver.get(m.group(1))
        check(wait_for("window.sculptView && sculptView.state.scenes >= 1"), "the session's page connects")
        os.write(fd, b"b = box([0, 0, 0], [1, 1, 1])\n")
        check(wait_for("sculptView.state.parts.length == 1 && sculptView.state.parts[0].name == 'last solid'"),
              "after an entry the page shows the session's last solid")
        os.write(fd, b'show(sphere(1), name="ball", color="blue")\n')
        check(wait_for("sculptView.state.parts.length == 1 && sculptView.state.parts[0].name == 'ball'"),
              "after show() the page shows what was shown")
        check(state("sculptView.pixels(%s)" % BLUE)["near"] > 2000, "the session's ball is drawn")
        os.write(fd, b"nothing + 1\n")
        check(wait_for("sculptView.state.status && !sculptView.state.status.ok"), "an entry's error reaches the page")
        text = driver.find_element(By.ID, "error").text
        check("<stdin>:" in text and "unknown name 'nothing'" in text and "^" in text,
              "the session's error panel shows the message and caret (got %r)" % text)
        check(state("sculptView.state.parts.length") == 1, "the session's model stays after an error")
        os.write(fd, b"1 + 1\n")
        check(wait_for("sculptView.state.status.ok"), "the next entry clears the error")
        os.write(fd, b":quit\n")
        end = time.time() + 10
        while time.time() < end:
            done, status = os.waitpid(pid, os.WNOHANG)
            if done == pid:
                check(os.waitstatus_to_exitcode(status) == 0, ":quit ends the session with its view")
                return
            read_until(r"$^", 0.1)
        check(False, ":quit ends the session with its view")
    finally:
        try:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        except (ProcessLookupError, ChildProcessError):
            pass


write(GOOD)
process = subprocess.Popen([sculpt, "--view", "--port", "0", script], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
url = None
deadline = time.time() + 30
while time.time() < deadline and url is None:
    line = process.stdout.readline()
    if not line:
        break
    m = re.match(r"view: (http://127\.0\.0\.1:\d+/)", line)
    if m:
        url = m.group(1)
if url is None:
    process.kill()
    print("FAIL sculpt --view printed no URL; stderr:", process.stderr.read())
    sys.exit(1)
print("view at", url)

options = webdriver.ChromeOptions()
for argument in ["--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", "--window-size=1100,700", "--force-device-scale-factor=1"]:
    options.add_argument(argument)
options.binary_location = chromium
driver = None
try:
    from selenium.webdriver.chrome.service import Service
    driver = webdriver.Chrome(service=Service(driver_path), options=options)
    driver.get(url)

    def state(expression):
        return driver.execute_script("return " + expression)

    def wait_for(expression, seconds=10):
        end = time.time() + seconds
        while time.time() < end:
            if state(expression):
                return True
            time.sleep(0.02)
        return False

    # 1. The model on screen.
    check(wait_for("window.sculptView && sculptView.state.scenes >= 1 && sculptView.state.status && sculptView.state.status.ok"),
          "the page receives the scene and an ok status")
    names = state("sculptView.state.parts.map(p => p.name)")
    check(names == ["block", "ball"], "the parts list names block and ball (got %s)" % names)
    pixels = state("sculptView.pixels(%s)" % RED)
    blue = state("sculptView.pixels(%s)" % BLUE)
    print("  pixels: %d of %d not background, %d red, %d blue" % (pixels["model"], pixels["total"], pixels["near"], blue["near"]))
    check(pixels["model"] > 0.03 * pixels["total"], "the model covers part of the picture")
    check(pixels["near"] > 2000 and blue["near"] > 500, "both parts are drawn in their colours")
    measures = driver.find_element(By.ID, "parts").text
    check("volume 1.75" in measures and "box [0, 0, 0] to [2, 1, 1]" in measures,
          "the block's volume and box are listed (got %r)" % measures)
    edges = state("sculptView.state.parts[0].info.edges[1]")
    check(edges == 18, "the block has its 18 feature edges (got %s)" % edges)
    triangles = state("sculptView.state.parts.reduce((n, p) => n + p.info.triangles, 0)")
    print("  scene message: %d bytes for %d triangles (%.1f bytes a triangle, edges and JSON included)"
          % (state("sculptView.state.bytes"), triangles, state("sculptView.state.bytes") / triangles))
    driver.save_screenshot(os.path.join(outdir, "view.png"))

    # 2. An edit updates the page.
    scenes = state("sculptView.state.scenes")
    start = time.time()
    write(EDITED)
    updated = wait_for("sculptView.state.scenes > %d" % scenes, 5)
    elapsed = time.time() - start
    check(updated and elapsed < 1.0, "the page shows the edited model within a second (%.0f ms)" % (1000 * elapsed))
    measures = driver.find_element(By.ID, "parts").text
    check("box [0, 0, 0] to [2, 1, 1.5]" in measures, "the edited box is listed (got %r)" % measures)

    # 3. An error shows its message and caret and keeps the model.
    write(BROKEN)
    check(wait_for("sculptView.state.status && !sculptView.state.status.ok", 5), "the page gets the error")
    panel = driver.find_element(By.ID, "error")
    text = panel.text
    check(panel.is_displayed() and re.search(r"model\.bsp:4:\d+: error: ", text) is not None,
          "the error panel shows file:line:col: error: (got %r)" % text)
    check("^" in text and "oops = box" in text, "the error panel shows the line and its caret")
    kept = state("sculptView.pixels(%s)" % RED)
    check(state("sculptView.state.parts.length") == 2 and kept["near"] > 2000, "the last good model stays on screen")
    driver.save_screenshot(os.path.join(outdir, "view_error.png"))
    write(EDITED)
    check(wait_for("sculptView.state.status.ok", 5) and not panel.is_displayed(), "fixing the script clears the error")

    # 4. Hiding a part hides it.
    before = state("sculptView.pixels(%s)" % BLUE)["near"]
    driver.find_element(By.ID, "part-visible-1").click()
    after = state("sculptView.pixels(%s)" % BLUE)["near"]
    red_after = state("sculptView.pixels(%s)" % RED)["near"]
    check(before > 500 and after < before / 20 and red_after > 2000,
          "unticking the ball hides it (blue pixels %d -> %d), the block stays" % (before, after))
    # A new scene keeps the choice.
    scenes = state("sculptView.state.scenes")
    write(GOOD)
    wait_for("sculptView.state.scenes > %d" % scenes, 5)
    check(state("sculptView.pixels(%s)" % BLUE)["near"] < before / 20, "the hidden part stays hidden after an update")

    # 5. Named views and the projection change the picture, and the model stays in it.
    driver.find_element(By.ID, "view-top").click()
    top = state("sculptView.pixels(null)")["model"]
    driver.find_element(By.ID, "projection").click()
    ortho = state("sculptView.pixels(null)")["model"]
    check(top > 0.02 * pixels["total"] and ortho > 0.02 * pixels["total"], "top view and orthographic show the model")

    # 6. The REPL's :view follows the session: its last solid, then what it shows.
    repl_view(driver, state, wait_for)
finally:
    if driver:
        driver.quit()
    process.send_signal(signal.SIGINT)
    try:
        out, err = process.communicate(timeout=10)
        check(process.returncode == 0 and "view: stopped" in out, "Ctrl-C ends sculpt --view cleanly")
    except subprocess.TimeoutExpired:
        process.kill()
        failures.append("sculpt --view did not end on Ctrl-C")

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("view.browser: every check passed")
