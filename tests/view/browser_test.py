#!/usr/bin/env python3
"""The live view in a real browser: sculpt --view serves the page, headless Chromium (Selenium)
opens it, and the test reads the pixels the page drew.

  browser_test.py SCULPT OUTDIR

Checks: the page shows the model (pixels of each part's colour); editing the script updates the
page (and how long that took); an error shows file:line:col with its caret and keeps the model;
fixing it clears the error; hiding a part hides its pixels; smooth shading changes the picture;
the section plane hides what lies beyond it; two clicks measure the distance between two corners;
the depth mode colours the boundary; a spline and a surface are parts drawn in their colours;
Ctrl-C ends sculpt. Saves screenshots as OUTDIR/view*.png
(docs/viewing.md's pictures come from here). Exit 77 (skipped) when Chromium,
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
GREEN = [0.25, 0.7, 0.3]  # color="green"
SHEET = [0.4, 0.2, 0.35]  # dark enough that lighting from the front does not saturate it
script = os.path.join(outdir, "model.bsp")
GOOD = """block = box([0, 0, 0], [2, 1, 1]) - box([1.5, -1, 0.5], [3, 2, 2])
show(block, name="block", color="red")
show(translate(sphere(0.5, segments=24), [3, 0.5, 0.5]), name="ball", color="blue")
"""
EDITED = GOOD.replace("[2, 1, 1]", "[2, 1, 1.5]")
# Curves and surfaces as parts: a closed spline around the block, a flat sheet under it.
CURVES = GOOD + """show(bspline([[-1, -1, 0.5], [3, -1, 0.5], [3, 2, 0.5], [-1, 2, 0.5]], closed=true), name="loop", color="green")
show(bspline_surface([[[-1, -1, -0.2], [-1, 2, -0.2]], [[4, -1, -0.2], [4, 2, -0.2]]], degree=1), name="sheet", color=[0.4, 0.2, 0.35])
"""
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


def click_at(driver, xyz):
    """Clicks the canvas where the world point xyz is drawn."""
    from selenium.webdriver.common.action_chains import ActionChains
    at = driver.execute_script("return sculptView.project(%s)" % list(xyz))
    canvas = driver.find_element(By.CSS_SELECTOR, "#canvas-box canvas")
    # Selenium 4 offsets from the element's centre.
    ActionChains(driver).move_to_element_with_offset(canvas, int(round(at["x"] - at["width"] / 2)),
                                                     int(round(at["y"] - at["height"] / 2))).click().perform()


def tools(driver, state, wait_for, total):
    # The script is GOOD: the block [0, 2] x [0, 1] x [0, 1] notched above x = 1.5, z = 0.5, and
    # the ball of radius 0.5 at (3, 0.5, 0.5). Show the ball again, look from the iso view.
    driver.find_element(By.ID, "part-visible-1").click()
    driver.find_element(By.ID, "view-iso").click()
    driver.find_element(By.ID, "projection").click()  # back to perspective

    # Smooth shading: the ball's facets give way to a smooth gradient (edges off, to see shading only).
    driver.find_element(By.ID, "edges").click()
    state("sculptView.grab()")
    driver.find_element(By.ID, "smooth").click()
    changed = state("sculptView.changed(12)")
    blue = state("sculptView.pixels(%s)" % BLUE)["near"]
    creases = state("sculptView.state.parts.map(p => p.info.edges[2])")
    print("  smooth shading: %d pixels changed, in %.0f ms; creases %s" % (changed, state("sculptView.state.timings.shading"), creases))
    check(changed > 300 and blue > 500, "the smooth toggle changes the shading (%d pixels) and keeps the ball" % changed)
    check(creases[1] == 0 and creases[0] == 18, "the block's 18 edges are creases, the ball has none (got %s)" % creases)
    driver.find_element(By.ID, "edges").click()
    driver.save_screenshot(os.path.join(outdir, "view_smooth.png"))
    state("sculptView.grab()")
    driver.find_element(By.ID, "smooth").click()
    check(state("sculptView.changed(12)") > 300, "flat shading comes back")

    # The section plane: x <= 2.1 keeps the block and hides the ball (x in [2.5, 3.5]); flipped,
    # the other way round.
    red0 = state("sculptView.pixels(%s)" % RED)["near"]
    blue0 = state("sculptView.pixels(%s)" % BLUE)["near"]
    model0 = state("sculptView.pixels(null)")["model"]
    driver.find_element(By.ID, "section").click()
    driver.execute_script("const s = document.getElementById('section-offset'); s.value = 600;"
                          "s.dispatchEvent(new Event('input'));")
    value = state("sculptView.state.sectionValue")
    red1 = state("sculptView.pixels(%s)" % RED)["near"]
    blue1 = state("sculptView.pixels(%s)" % BLUE)["near"]
    print("  section at x = %.3f: red %d -> %d, blue %d -> %d" % (value, red0, red1, blue0, blue1))
    check(2.0 < value < 2.5 and blue1 < blue0 / 20 and red1 > red0 / 2,
          "the section plane hides what lies beyond it (the ball), the block stays")
    check("section: showing x <= " in driver.find_element(By.ID, "section-info").text, "the panel names the section")
    driver.find_element(By.ID, "section-flip").click()
    red2 = state("sculptView.pixels(%s)" % RED)["near"]
    blue2 = state("sculptView.pixels(%s)" % BLUE)["near"]
    check(red2 < red0 / 20 and blue2 > blue0 / 2, "flipped, it keeps the ball and hides the block (red %d, blue %d)" % (red2, blue2))
    driver.execute_script("const s = document.getElementById('section-axis'); s.value = 'z';"
                          "s.dispatchEvent(new Event('input'));")
    driver.execute_script("const s = document.getElementById('section-offset'); s.value = 450;"
                          "s.dispatchEvent(new Event('input'));")
    driver.find_element(By.ID, "section-flip").click()
    driver.save_screenshot(os.path.join(outdir, "view_section.png"))
    red3 = state("sculptView.pixels(%s)" % RED)["near"]
    model3 = state("sculptView.pixels(null)")["model"]
    check(red3 > 0 and model3 < model0, "a z section at 0.45 cuts the block (model pixels %d -> %d)" % (model0, model3))
    # The cap: seen from above, the block's cut face (z = the section's value) is drawn in its
    # colour darkened and unlit, so every pixel of it is that one colour; without a cap the inside
    # of the block's bottom would show there, lit.
    z = state("sculptView.state.sectionValue")
    shade = state("sculptView.capShade")
    cap = [shade * c for c in RED]
    at = state("sculptView.colorAt(%s, %s)" % ([1.0, 0.5, z], cap))
    want = [round(255 * c) for c in cap]
    print("  cap at z = %.3f: %s where the block is cut (cap colour %s), %d pixels of it" % (z, at["rgb"], want, at["exact"]))
    check(all(abs(a - b) <= 2 for a, b in zip(at["rgb"], want)) and at["exact"] > 500,
          "the section draws the block's cut face as a cap (%s at its middle, %d pixels)" % (at["rgb"], at["exact"]))
    driver.find_element(By.ID, "part-visible-0").click()
    hidden = state("sculptView.colorAt(%s, %s)" % ([1.0, 0.5, z], cap))["exact"]
    check(hidden == 0, "a hidden part's cap is hidden too (%d cap pixels)" % hidden)
    driver.find_element(By.ID, "part-visible-0").click()
    driver.find_element(By.ID, "section").click()
    check(state("sculptView.colorAt(%s, %s)" % ([1.0, 0.5, z], cap))["exact"] == 0, "unticked, no cap is drawn")
    check(abs(state("sculptView.pixels(%s)" % RED)["near"] - red0) < red0 / 50, "unticked, the whole model is back")

    # Measuring: two clicks near two corners of the block's front face (y = 0) snap to the
    # corners (0, 0, 0) and (1.5, 0, 1): distance sqrt(1.5^2 + 1) exactly in float32 corners.
    driver.find_element(By.ID, "measure").click()
    click_at(driver, [0.03, 0, 0.03])
    check(wait_for("sculptView.state.measure.points.length == 1", 3), "the first click picks a point")
    cursor = driver.find_element(By.ID, "cursor").text
    check(cursor.startswith("cursor: 0, 0, 0 (corner) on block"), "the panel shows the picked corner (got %r)" % cursor)
    click_at(driver, [1.47, 0, 0.97])
    check(wait_for("sculptView.state.measure.distance !== null", 3), "the second click gives a distance")
    distance = state("sculptView.state.measure.distance")
    expected = (1.5 ** 2 + 1) ** 0.5
    text = driver.find_element(By.ID, "measurement").text
    print("  measured %r (expected %r); panel %r" % (distance, expected, text))
    check(distance is not None and abs(distance - expected) < 1e-6 and "distance 1.80278" in text,
          "the distance between the corners (0, 0, 0) and (1.5, 0, 1) is %.6f" % expected)
    driver.save_screenshot(os.path.join(outdir, "view_measure.png"))
    driver.find_element(By.ID, "measure").click()

    # The depth mode: sculpt sends the cell depths when asked, and the boundary takes their colours.
    scenes = state("sculptView.state.scenes")
    red0 = state("sculptView.pixels(%s)" % RED)["near"]
    start = time.time()
    driver.find_element(By.ID, "depth").click()
    got = wait_for("sculptView.state.scenes > %d && sculptView.state.parts.every(p => p.depths)" % scenes, 5)
    print("  depths arrived %.0f ms after the toggle (the script runs again)" % (1000 * (time.time() - start)))
    check(got, "the page receives the depths after entering the depth mode")
    depths = state("[...new Set(sculptView.state.parts[0].depths)].sort((a, b) => a - b)")
    red1 = state("sculptView.pixels(%s)" % RED)["near"]
    model = state("sculptView.pixels(null)")["model"]
    legend = driver.find_element(By.ID, "depth-legend").text
    print("  block's depths %s; red pixels %d -> %d; legend %r" % (depths, red0, red1, legend))
    check(red1 < red0 / 10 and model > 0.02 * total, "the depth mode changes the colours (red %d -> %d)" % (red0, red1))
    check(legend.startswith("cell depth") and str(depths[0]) in legend, "the legend shows the range of depths")
    driver.save_screenshot(os.path.join(outdir, "view_depth.png"))
    driver.find_element(By.ID, "depth").click()
    check(state("sculptView.pixels(%s)" % RED)["near"] > red0 / 2, "leaving the depth mode gives the colours back")


def curves(driver, state, wait_for):
    scenes = state("sculptView.state.scenes")
    write(CURVES)
    check(wait_for("sculptView.state.scenes > %d && sculptView.state.parts.length == 4" % scenes, 5),
          "the page gets the curve and the surface")
    driver.find_element(By.ID, "view-top").click()
    green = state("sculptView.pixels(%s)" % GREEN)["near"]
    sheet = state("sculptView.pixels(%s)" % SHEET)["near"]
    measures = driver.find_element(By.ID, "parts").text
    print("  curve pixels %d, sheet pixels %d" % (green, sheet))
    check(green > 200, "the closed spline is drawn as a line in its colour (%d pixels)" % green)
    check(sheet > 2000, "the surface is drawn in its colour (%d pixels)" % sheet)
    check("curve, length" in measures and "area 15" in measures,
          "the curve's length and the sheet's area (5 x 3) are listed (got %r)" % measures)
    driver.find_element(By.ID, "part-visible-2").click()
    hidden = state("sculptView.pixels(%s)" % GREEN)["near"]
    check(hidden < green / 20, "unticking the curve hides it (%d -> %d pixels)" % (green, hidden))
    driver.save_screenshot(os.path.join(outdir, "view_curves.png"))
    driver.find_element(By.ID, "view-iso").click()


def fine_mesh(driver, state, wait_for):
    """A part of more than 65,536 vertices goes out with its indices in 16-bit runs over windows of
    vertices (mesh/mesh_io.hpp, encode_glb_for_display): the page's triangles must enclose the
    part's volume, in the first scene and in the next one (which reuses the first's index array).
    More than 250,000 triangles make a large scene, whose flat mode lights diffusely only (a shader
    of the page's own): it must draw the part in its colour and clip it at the section plane."""
    for k in range(2):
        scenes = state("sculptView.state.scenes")
        write('show(sphere(1, segments=512), name="fine", color="blue")  # %d\n' % k)
        check(wait_for("sculptView.state.scenes > %d && sculptView.state.parts.length == 1 && "
                       "sculptView.state.parts[0].name == 'fine'" % scenes, 10), "the page gets the fine sphere")
        got = state("sculptView.meshVolume(0)")
        want = state("sculptView.state.parts[0].info.volume")
        triangles = state("sculptView.state.parts[0].info.triangles")
        print("  fine sphere, scene %d: %d triangles, volume %.9f in the page, %.9f sent" % (k, got["triangles"], got["volume"], want))
        check(triangles > 2 * 65536 and got["triangles"] == triangles, "the page holds every triangle (%d of %d)" % (got["triangles"], triangles))
        check(abs(got["volume"] - want) < 1e-5 * want, "the page's triangles enclose the part's volume (%.9f, %.9f)" % (got["volume"], want))
    check(state("sculptView.state.large && sculptView.state.parts[0].mesh.material.type") == "ShaderMaterial",
          "a scene of %d triangles is large: its flat mode uses the diffuse-only material" % triangles)
    driver.find_element(By.ID, "fit").click()
    drawn = state("sculptView.pixels(%s)" % BLUE)
    print("  large scene: %d model pixels, %d of them blue" % (drawn["model"], drawn["near"]))
    # (The most brightly lit pixels saturate a channel and change hue, as with the standard material.)
    check(drawn["model"] > 50000 and drawn["near"] > 0.6 * drawn["model"],
          "the diffuse-only material draws the part lit in its colour (%d of %d pixels)" % (drawn["near"], drawn["model"]))
    # The section (as the earlier steps left it): the cap on the plane is drawn where nothing
    # nearer hides it, so it shows only if the material discards the sphere's cut-away part.
    driver.find_element(By.ID, "section").click()
    axis = state("document.getElementById('section-axis').value")
    centre = [0.0, 0.0, 0.0]
    centre["xyz".index(axis)] = state("sculptView.state.sectionValue")
    cap = [state("sculptView.capShade") * c for c in BLUE]
    at = state("sculptView.colorAt(%s, %s)" % (centre, cap))
    print("  large scene cut at %s = %.3f: %s at the cut's centre, %d cap pixels" % (axis, max(centre, key=abs), at["rgb"], at["exact"]))
    driver.save_screenshot(os.path.join(outdir, "view_large_section.png"))
    check(at["exact"] > 5000, "the diffuse-only material is clipped by the section plane (%d cap pixels)" % at["exact"])
    driver.find_element(By.ID, "section").click()


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
    check(wait_for("sculptView.state.drawn >= 1"), "the scene's first frame is drawn")
    run_line = driver.find_element(By.ID, "run").text
    check(re.match(r"run \d+: ok in [\d.]+ ms \(script [\d.e-]+ ms; on screen [\d.]+ ms after it\)$", run_line),
          "the run line tells the script's time and when the scene was on screen (got %r)" % run_line)
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

    # 6. The tools: smooth shading, the section plane, measuring, the depth mode.
    tools(driver, state, wait_for, pixels["total"])

    # 7. Curves and surfaces are parts: drawn in their colours, listed with their measures, hidden
    # by their checkboxes.
    curves(driver, state, wait_for)

    # 8. A part too large for 16-bit indices alone arrives whole.
    fine_mesh(driver, state, wait_for)

    # 9. The REPL's :view follows the session: its last solid, then what it shows.
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
