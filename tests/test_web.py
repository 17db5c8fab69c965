#!/usr/bin/python3
"""make test-web: the page of build/web/ in headless Debian chromium, driven over the DevTools
protocol (python3-websocket), checked against ./bdpt.

- cornell 64x64, 16 spp, bdpt: the panel's mean equals ./bdpt's for the same options and seed;
- every method once, six panels at a time: each panel's mean equals ./bdpt's;
- a scene with a syntax error: the page shows ./bdpt's message, file:line and all, and renders nothing;
  a misspelt option in an entry: that panel shows ./bdpt's message;
- a click on a pixel: the strategy chart's bars are ./bdpt --strategies's images at that pixel;
- no error in the page's console; a screenshot of the page at 1920 wide (build/test-web/page.png).
Prints one line per check and exits 1 if any fails."""
import http.server
import json
import math
import os
import shutil
import socketserver
import struct
import subprocess
import sys
import tempfile
import threading
import time

import websocket  # Debian's python3-websocket

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "build", "test-web")
failures = []


def check(ok, what, detail=""):
    print(("ok    " if ok else "FAIL  ") + what + (": " + detail if detail else ""), flush=True)
    if not ok:
        failures.append(what)


# ---- ./bdpt, the expected values
def read_pfm(path):
    with open(path, "rb") as f:
        data = f.read()
    header, rest = data.split(b"\n", 3)[:3], data.split(b"\n", 3)[3]
    w, h = map(int, header[1].split())
    floats = struct.unpack("<%df" % (3 * w * h), rest[: 12 * w * h])
    rows = [floats[3 * w * y: 3 * w * (y + 1)] for y in range(h)][::-1]  # PFM rows from the bottom
    return w, h, [v for row in rows for v in row]


def native(scene, entry, spp, seed=1, res="64x64", extra=()):
    out = os.path.join(OUT, "native.png")
    cmd = ["./bdpt", scene, "--method", *entry.split(), "--res", res, "--spp", str(spp), "--seed", str(seed),
           "--quiet", "--out", out, *extra]
    subprocess.run(cmd, cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
    return read_pfm(os.path.join(OUT, "native.pfm"))


def mean(values):
    return math.fsum(values) / len(values)


# ---- the page's server and the browser
class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, directory=os.path.join(ROOT, "build", "web"), **kwargs)

    def log_message(self, *args):
        pass


class Browser:
    def __init__(self, url):
        self.profile = tempfile.mkdtemp(prefix="bdpt-chromium-")
        self.proc = subprocess.Popen(
            ["chromium", "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run", "--remote-debugging-port=0",
             "--user-data-dir=" + self.profile, "--window-size=1920,1080", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = os.path.join(self.profile, "DevToolsActivePort")
        for _ in range(300):
            if os.path.exists(port_file) and open(port_file).read().count("\n") >= 1:
                break
            time.sleep(0.1)
        port = open(port_file).read().split("\n")[0]
        import urllib.request
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%s/json/list" % port))
        page = next(t for t in targets if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=600, suppress_origin=True)
        self.next_id = 0
        self.console_errors = []
        self.call("Runtime.enable")
        self.call("Page.enable")
        self.call("Emulation.setDeviceMetricsOverride", width=1920, height=1080, deviceScaleFactor=1, mobile=False)
        self.call("Page.navigate", url=url)
        self.wait_for("bdptPage && bdptPage.ready()", 60)

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            if m.get("method") == "Runtime.exceptionThrown":
                self.console_errors.append(m["params"]["exceptionDetails"].get("exception", {}).get("description", "exception"))
            elif m.get("method") == "Runtime.consoleAPICalled" and m["params"]["type"] == "error":
                self.console_errors.append(" ".join(str(a.get("value", a.get("description"))) for a in m["params"]["args"]))
            if m.get("id") == self.next_id:
                if "error" in m:
                    raise RuntimeError(method + ": " + json.dumps(m["error"]))
                return m["result"]

    def js(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in r:
            raise RuntimeError(expression + ": " + r["exceptionDetails"].get("exception", {}).get("description", "error"))
        return r["result"].get("value")

    def wait_for(self, condition, seconds):
        t0 = time.time()
        while time.time() - t0 < seconds:
            try:
                if self.js("typeof bdptPage !== 'undefined' && (%s)" % condition):
                    return
            except RuntimeError:
                pass
            time.sleep(0.1)
        raise RuntimeError("the page did not get to: " + condition)

    def run(self, scene, entries, spp, seconds=0, resolution="64x64", seed=1):
        self.js("bdptPage.selectScene(%s)" % json.dumps(scene))
        self.js("bdptPage.setEntries(%s)" % json.dumps(entries))
        self.js("bdptPage.setOptions({resolution: %s, spp: %d, seconds: %g, seed: %d})" % (json.dumps(resolution), spp, seconds, seed))
        self.js("bdptPage.run()")
        return self.js("bdptPage.panels()")

    def screenshot(self, path):
        height = self.js("document.documentElement.scrollHeight")
        self.call("Emulation.setDeviceMetricsOverride", width=1920, height=height, deviceScaleFactor=1, mobile=False)
        shot = self.call("Page.captureScreenshot", format="png")
        import base64
        with open(path + ".tmp", "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        os.replace(path + ".tmp", path)
        self.call("Emulation.setDeviceMetricsOverride", width=1920, height=1080, deviceScaleFactor=1, mobile=False)

    def close(self):
        self.ws.close()
        self.proc.terminate()
        self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)


def main():
    os.makedirs(OUT, exist_ok=True)
    t0 = time.time()
    server = socketserver.TCPServer(("127.0.0.1", 0), QuietHandler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    browser = Browser("http://127.0.0.1:%d/index.html" % server.server_address[1])
    try:
        tests(browser)
    finally:
        browser.close()
        server.shutdown()
    print("make test-web: %d checks failed, %.0f s" % (len(failures), time.time() - t0))
    return 1 if failures else 0


# The same code gives the same image up to the last bit of a few values: emscripten's C library
# rounds cosf, sinf and acosf differently from glibc in 1-2% of arguments (measured on a million).
# A Markov chain may then accept one proposal differently and go on along another path: the
# Metropolis methods' means agree to 1e-5, the others' to 1e-6.
def close(a, b, tolerance=1e-6):
    return abs(a - b) <= tolerance * abs(b)


def tests(browser):
    # 1. bdpt on cornell, 64x64 x 16, seed 1: the page's mean is ./bdpt's.
    panels = browser.run("scenes/cornell.scene", ["bdpt"], 16)
    w, h, ref = native("scenes/cornell.scene", "bdpt", 16)
    p = panels[0]
    check(p["passes"] == 16 and not p["error"] and close(p["mean"], mean(ref)), "cornell 64x64 x 16 spp bdpt: the page's mean is ./bdpt's",
          "page %.9g, ./bdpt %.9g, %d passes, first image %.0f ms after Start" % (p["mean"], mean(ref), p["passes"], p["firstFrameMs"]))
    check(p["rmse"] is not None and 0 < p["rmse"] < 1, "the panel's RMSE against scenes/refs/cornell.pfm", "%.4g" % p["rmse"])

    # 2. A click on a pixel: the bars are ./bdpt --strategies's images there (paths up to 4 segments).
    x, y = 20, 44
    bars = browser.js("bdptPage.clickPixel(0, %d, %d)" % (x, y))
    strat_dir = os.path.join(OUT, "strategies")
    os.makedirs(strat_dir, exist_ok=True)
    native("scenes/cornell.scene", "bdpt", 16, extra=("--strategies", strat_dir, "--strategy-length", "4"))
    worst, count = 0.0, 0
    for b in bars:
        name = b["strategy"].replace(" ", "_")
        _, _, img = read_pfm(os.path.join(strat_dir, "%s_%s.pfm" % (name, b["kind"])))
        i = 3 * (y * w + x)
        expected = (img[i] + img[i + 1] + img[i + 2]) / 3
        worst = max(worst, abs(b["value"] - expected) / max(1e-6, abs(expected)))
        count += 1
    check(count == 28 and worst < 1e-5, "a clicked pixel's strategy chart: 14 strategies x (unweighted, weighted) = ./bdpt --strategies there",
          "%d bars, largest relative difference %.2g" % (count, worst))
    weighted = sum(b["value"] for b in bars if b["kind"] == "weighted")
    check(weighted > 0, "the weighted bars carry light at (%d, %d)" % (x, y), "sum %.4g" % weighted)

    # 3. Every method once, six panels at a time, 4 spp: each mean is ./bdpt's. The last entry
    # carries a deliberate mistake that changes cornell's mean (by a quarter), so the page must pass it on.
    methods = ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "vcm", "pssmlt", "mmlt", "mlt", "lt --no-scramble"]
    for group in (methods[:6], methods[6:]):
        panels = browser.run("scenes/cornell.scene", group, 4)
        for entry, p in zip(group, panels):
            _, _, img = native("scenes/cornell.scene", entry, 4)
            tolerance = 1e-5 if entry.split()[0] in ("pssmlt", "mmlt", "mlt") else 1e-6
            check(p["passes"] == 4 and not p["error"] and close(p["mean"], mean(img), tolerance),
                  "every method: '%s' mean as ./bdpt's within %g" % (entry, tolerance),
                  "page %.9g, ./bdpt %.9g, relative difference %.2g" % (p["mean"], mean(img), abs(p["mean"] / mean(img) - 1)))

    # 4. A scene with an error: the page shows ./bdpt's message, file:line, and renders nothing.
    text = open(os.path.join(ROOT, "scenes/cornell.scene")).read().split("\n")
    bad_line = next(i for i, l in enumerate(text) if l.startswith("material"))
    text[bad_line] = text[bad_line].replace("material", "materail", 1)
    bad = os.path.join(OUT, "cornell.scene")
    open(bad, "w").write("\n".join(text))
    expected = subprocess.run(["./bdpt", bad, "--quiet", "--out", os.path.join(OUT, "bad.png")], cwd=ROOT, capture_output=True, text=True).stderr.strip()
    expected = expected.replace(bad, "scenes/cornell.scene")
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    browser.js("bdptPage.setSceneText(%s)" % json.dumps("\n".join(text)))
    browser.js("bdptPage.setEntries(['bdpt'])")
    browser.js("bdptPage.run()")
    shown = browser.js("bdptPage.sceneError()")
    check(shown == expected and ":%d:" % (bad_line + 1) in shown, "a misspelt directive: the page shows ./bdpt's message with its line",
          repr(shown))

    # 5. A misspelt option in an entry: the panel shows ./bdpt's message, and the other panel renders.
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    panels = browser.run("scenes/cornell.scene", ["bdpt --heurstic power", "pt"], 2)
    expected = subprocess.run(["./build/bdpt-lecture", "scenes/cornell.scene", "--method", "bdpt", "--heurstic", "power", "--seed", "1"],
                              cwd=ROOT, capture_output=True, text=True).stderr.strip()
    check(panels[0]["error"] == expected and panels[1]["passes"] == 2, "a misspelt option: the panel shows ./bdpt's message, the next one renders",
          repr(panels[0]["error"]))

    # 6. The page as a class sees it: six methods at equal time, a pixel chosen; no error in the console.
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    panels = browser.run("scenes/cornell.scene", ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "vcm"], 0, seconds=3)
    check(all(p["seconds"] >= 3 and p["passes"] > 0 for p in panels), "six panels at 3 s each, side by side",
          ", ".join("%s %d spp" % (p["entry"], p["passes"]) for p in panels))
    first, gap = max(p["firstFrameMs"] for p in panels), browser.js("bdptPage.longestFrameGap()")
    check(first < 1000, "each of six panels shows its first image within 1 s of Start", "the last after %.0f ms" % first)
    check(gap < 500, "the page stays responsive while six workers render (a frame at least every 500 ms)",
          "longest gap between frames %.0f ms" % gap)
    browser.js("bdptPage.clickPixel(4, 20, 44)")
    browser.screenshot(os.path.join(OUT, "page.png"))
    check(not browser.console_errors, "no error in the page's console", "; ".join(browser.console_errors[:3]))
    print("      screenshot: build/test-web/page.png")


if __name__ == "__main__":
    sys.exit(main())
