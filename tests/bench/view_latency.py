#!/usr/bin/env python3
"""How long after a script's end its model is on screen in the live view (docs/viewing.md).

Runs `sculpt --view --port 0 SCRIPT`, opens the page in headless Chromium (Debian's chromium and
chromium-driver, python3-selenium), then touches the script --runs times. For each run it reads
the page's state: the run's time and the script's share (sculpt's status message), and the time
the page drew the new scene's first frame, both on the system clock, so that "on screen after the
script" is the page's draw time minus the script's end. Also the scene message's bytes a triangle.

    /usr/bin/python3 tests/bench/view_latency.py build/release/sculpt --runs 3 \\
        --statement 'show(sphere(1, segments=1000), name="ball")'
    /usr/bin/python3 tests/bench/view_latency.py build/release/sculpt --runs 5 --script scripts/goblet.bsp

Exit code 77 when Chromium, its driver or Selenium is missing (as the browser test).
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("sculpt")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--statement", action="append",
                        help="a script line (repeatable); default: a 1000-segment sphere")
    parser.add_argument("--script", help="an existing script to run and touch (instead of --statement)")
    parser.add_argument("--timeout", type=float, default=300)
    args = parser.parse_args()
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
    except ImportError:
        print("view_latency: python3-selenium is not installed", file=sys.stderr)
        return 77
    chromium, driver_path = shutil.which("chromium"), shutil.which("chromedriver")
    if not chromium or not driver_path:
        print("view_latency: chromium or chromium-driver is not installed", file=sys.stderr)
        return 77
    statements = args.statement or ['show(sphere(1, segments=1000), name="ball")']
    work = tempfile.mkdtemp(prefix="view_latency.")
    script = os.path.abspath(args.script) if args.script else os.path.join(work, "scene.bsp")
    if not args.script:
        with open(script, "w") as f:
            f.write("\n".join(statements) + "\n")
    sculpt = subprocess.Popen([args.sculpt, "--view", "--port", "0", script], stdout=subprocess.PIPE, text=True)
    driver = None
    try:
        url = None
        while url is None:
            line = sculpt.stdout.readline()
            if not line:
                print("view_latency: sculpt ended before printing its address", file=sys.stderr)
                return 1
            m = re.match(r"view: (http://127\.0\.0\.1:\d+/)", line)
            if m:
                url = m.group(1)
        # The runs' own output is not read: drained so that a full pipe never stops sculpt.
        threading.Thread(target=lambda: sculpt.stdout.read(), daemon=True).start()
        options = webdriver.ChromeOptions()
        for a in ["--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--use-angle=swiftshader",
                  "--enable-unsafe-swiftshader", "--window-size=1100,700"]:
            options.add_argument(a)
        options.binary_location = chromium
        driver = webdriver.Chrome(service=Service(driver_path), options=options)
        driver.get(url)

        def state(expression):
            return driver.execute_script("return " + expression)

        def wait_for(expression):
            end = time.time() + args.timeout
            while not state(expression):
                if state("window.sculptView && sculptView.state.status && !sculptView.state.status.ok"):
                    raise RuntimeError("view_latency: the script failed: " + state("sculptView.state.status.error"))
                if time.time() > end:
                    raise TimeoutError("view_latency: timed out waiting for " + expression)
                time.sleep(0.01)

        # A run is complete on the page when its status has come and its scene has been drawn after
        # the script's end.
        complete = ("window.sculptView && sculptView.state.status && sculptView.state.status.run >= %d && "
                    "sculptView.state.drawnAt !== null && "
                    "sculptView.state.drawnAt >= sculptView.state.status.script_end")
        wait_for(complete % 1)
        triangles = state("sculptView.state.parts.reduce((n, p) => n + p.info.triangles, 0)")
        message = state("sculptView.state.bytes")
        print("scene: %d triangles, %d bytes, %.1f bytes a triangle" % (triangles, message, message / max(triangles, 1)))
        lags, scripts, totals = [], [], []
        for k in range(args.runs):
            run = state("sculptView.state.status.run")
            stamp = time.time() + 1 + k
            os.utime(script, (stamp, stamp))
            wait_for(complete % (run + 1))
            status = state("sculptView.state.status")
            lag = state("sculptView.state.drawnAt") - status["script_end"]
            arrived = state("sculptView.state.receivedAt") - status["script_end"]
            sent = status.get("scene_sent", 0) - status["script_end"]
            handled = state("sculptView.state.timings.scene")
            raster = state("sculptView.state.timings.raster")
            render = state("sculptView.state.timings.render")
            lags.append(lag)
            scripts.append(status["script_ms"])
            totals.append(status["ms"])
            print("run %d: script %.0f ms, run %.0f ms; after the script's end: the scene message was sent "
                  "at %.0f ms and arrived at %.0f ms, was handled in %.0f ms, on screen at %.0f ms (its first frame: render() %.0f ms, "
                  "then rasterized in %.0f ms)"
                  % (status["run"], status["script_ms"], status["ms"], sent, arrived, handled, lag, render, raster))
        print("median: script %.0f ms, on screen %.0f ms after the script's end (min %.0f, max %.0f)"
              % (statistics.median(scripts), statistics.median(lags), min(lags), max(lags)))
        return 0
    finally:
        if driver is not None:
            driver.quit()
        sculpt.terminate()
        sculpt.wait()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
