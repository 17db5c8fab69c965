#!/usr/bin/python3
"""make test-web: the page of build/web/ in headless Debian chromium, driven over the DevTools
protocol (python3-websocket), checked against ./bdpt and against the notes' own numbers.

- cornell 64x64, 16 spp, bdpt: the panel's mean and RMSE are ./bdpt's; the canvas as drawn is
  ./bdpt's PNG to the level; a clicked pixel's bars are ./bdpt --strategies's images there;
  the pyramid's weighted tiles sum to the image;
- every method once, six panels at a time: each panel's mean is ./bdpt's;
- a scene with a syntax error: ./bdpt's message, file:line and all, nothing rendered; a misspelt
  option: the panel shows ./bdpt's message with its did-you-mean;
- six panels at 2 s: a curve per panel on the chart, each falling; 256x256: every panel shows
  its rows within its first pass; the pyramid redrawn only when its data changes;
- the notes in the page: pages 1, 2, 11 and 13 each give a number their button reproduces; every
  command the page runs, at one pass, shows ./bdpt's mean and rays per sample for it; the
  rays per sample of pages 1, 9 and 12 and vcm's memory of page 15 are the panels'; a notes
  command the page cannot run as written says how to do it there (the scene editor, the panels);
- the path view: where each connection's light goes, why (1,1) weighs 0, vcm's merges drawn;
  every display formula, the code view and the path view's tables inside their column at
  1366x768 and 390x844;
- a worker killed without a word: its panel ends with a message, Stop ends the run, the next
  run renders; the layout at 1366x768 and 390x844 has no sideways scroll; a link keeps the
  setting; the page opened from a file renders; no error in the console of the page or of
  its workers (Runtime and Log);
Every wait is for an event (a run's end, a panel's frame), with a hang guard of minutes; no check
compares a duration or a speed with a threshold (tests/README.md, "No test measures time").
Prints one line per check and exits 1 if any fails.

tests/test_web.py --bench (make bench-web): one bdpt panel's samples per CPU second of the whole
browser against ./bdpt --threads 1's, printed, never checked."""
import base64
import http.server
import json
import math
import os
import re
import shlex
import shutil
import socketserver
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib

import websocket  # Debian's python3-websocket

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "build", "test-web")
HANG = 600  # seconds: a wait longer than this is a hang, not a slow machine
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


def read_png(path):
    """An 8-bit RGB or RGBA PNG (as stb writes them) as (w, h, channels, bytes), rows from the top."""
    data = open(path, "rb").read()
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 6), "read_png: 8-bit RGB or RGBA only"
            ch = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, out, stride = zlib.decompress(idat), bytearray(), w * ch
    previous = bytearray(stride)
    for y in range(h):
        f, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = row[i - ch] if i >= ch else 0
            b, c = previous[i], previous[i - ch] if i >= ch else 0
            if f == 1: row[i] = (row[i] + a) & 255
            elif f == 2: row[i] = (row[i] + b) & 255
            elif f == 3: row[i] = (row[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += row
        previous = row
    return w, h, ch, out


def native(scene, entry, spp, seed=1, res="64x64", extra=()):
    """./bdpt's image (PFM) and what it printed."""
    out = os.path.join(OUT, "native.png")
    cmd = ["./bdpt", scene, "--method", *entry.split(), "--res", res, "--spp", str(spp), "--seed", str(seed), "--out", out, *extra]
    printed = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    w, h, img = read_pfm(os.path.join(OUT, "native.pfm"))
    return w, h, img, printed


def page_text(name):
    """A notes page's text on one line (a quote may wrap)."""
    return open(os.path.join(ROOT, "lecture_notes", name + ".md")).read().replace("\n", " ")


def mean(values):
    return math.fsum(values) / len(values)


def process_cpu_seconds(root_pid):
    """User + system CPU seconds of a process and all its descendants (/proc)."""
    children, ticks = {}, os.sysconf("SC_CLK_TCK")
    stats = {}
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            fields = open("/proc/%s/stat" % pid).read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        stats[int(pid)] = fields
        children.setdefault(int(fields[1]), []).append(int(pid))
    total, todo = 0.0, [root_pid]
    while todo:
        pid = todo.pop()
        if pid in stats:
            total += (int(stats[pid][11]) + int(stats[pid][12])) / ticks
        todo += children.get(pid, [])
    return total


# ---- the page's server and the browser
class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, directory=os.path.join(ROOT, "build", "web"), **kwargs)

    def log_message(self, *args):
        pass


class Browser:
    """Headless chromium with one page; the console of the page and of every worker it starts
    (auto-attached, flat sessions) is collected: exceptions, console.error and Log errors."""

    def __init__(self, url):
        self.profile = tempfile.mkdtemp(prefix="bdpt-chromium-")
        self.proc = subprocess.Popen(
            ["chromium", "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run", "--remote-debugging-port=0",
             "--allow-file-access-from-files", "--user-data-dir=" + self.profile, "--window-size=1920,1080", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = os.path.join(self.profile, "DevToolsActivePort")
        for _ in range(HANG * 10):
            if os.path.exists(port_file) and open(port_file).read().count("\n") >= 1:
                break
            time.sleep(0.1)
        port = open(port_file).read().split("\n")[0]
        import urllib.request
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%s/json/list" % port))
        page = next(t for t in targets if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=HANG, suppress_origin=True)
        self.next_id = 0
        self.side_id = 10 ** 6  # ids of the calls to the workers' sessions, whose answers nobody waits for
        self.console_errors = []
        self.workers_attached = 0
        for domain in ("Runtime.enable", "Page.enable", "Log.enable"):
            self.call(domain)
        self.call("Target.setAutoAttach", autoAttach=True, waitForDebuggerOnStart=False, flatten=True)
        self.size(1920, 1080)
        self.open(url)

    def open(self, url):
        self.call("Page.navigate", url=url)
        self.wait_for("bdptPage && bdptPage.ready()")

    def size(self, width, height):
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=width < 800)

    def _event(self, m):
        method, params = m.get("method"), m.get("params", {})
        where = " (worker)" if m.get("sessionId") else ""
        if method == "Runtime.exceptionThrown":
            self.console_errors.append(params["exceptionDetails"].get("exception", {}).get("description", "exception") + where)
        elif method == "Runtime.consoleAPICalled" and params["type"] == "error":
            self.console_errors.append(" ".join(str(a.get("value", a.get("description"))) for a in params["args"]) + where)
        elif method == "Log.entryAdded" and params["entry"]["level"] == "error":
            self.console_errors.append(params["entry"]["text"] + " " + params["entry"].get("url", "") + where)
        elif method == "Target.attachedToTarget":
            self.workers_attached += 1
            for domain in ("Runtime.enable", "Log.enable", "Runtime.runIfWaitingForDebugger"):
                self.side_id += 1
                self.ws.send(json.dumps({"id": self.side_id, "sessionId": params["sessionId"], "method": domain}))

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            if "method" in m:
                self._event(m)
            if m.get("id") == self.next_id and "sessionId" not in m:
                if "error" in m:
                    raise RuntimeError(method + ": " + json.dumps(m["error"]))
                return m["result"]

    def js(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in r:
            raise RuntimeError(expression + ": " + r["exceptionDetails"].get("exception", {}).get("description", "error"))
        return r["result"].get("value")

    def wait_for(self, condition, guard=HANG):
        """Until the page's condition holds (polled; the guard is a hang's, not a speed limit)."""
        t0 = time.time()
        while time.time() - t0 < guard:
            try:
                if self.js("typeof bdptPage !== 'undefined' && !!(%s)" % condition):
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

    def screenshot(self, path, width=1920, height=None):
        self.size(width, height or self.js("document.documentElement.scrollHeight"))
        shot = self.call("Page.captureScreenshot", format="png")
        with open(path + ".tmp", "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        os.replace(path + ".tmp", path)
        self.size(1920, 1080)

    def close(self):
        self.ws.close()
        self.proc.terminate()
        self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)


def main(bench=False):
    os.makedirs(OUT, exist_ok=True)
    t0 = time.time()
    server = socketserver.TCPServer(("127.0.0.1", 0), QuietHandler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    browser = Browser("http://127.0.0.1:%d/index.html" % server.server_address[1])
    try:
        if bench:
            speed(browser)
        else:
            tests(browser, "http://127.0.0.1:%d/index.html" % server.server_address[1])
    finally:
        browser.close()
        server.shutdown()
    if not bench:
        print("make test-web: %d checks failed, %.0f s" % (len(failures), time.time() - t0))
    return 1 if failures else 0


# The same code gives the same image up to the last bit of a few values: emscripten's C library
# rounds cosf, sinf and acosf differently from glibc in 1-2% of arguments (measured on a million).
# A Markov chain may then accept one proposal differently and go on along another path: the
# Metropolis methods' means agree to 1e-5, the others' to 1e-6.
def close(a, b, tolerance=1e-6):
    return abs(a - b) <= tolerance * abs(b)


def tests(browser, url):
    only = [a for a in sys.argv[1:] if not a.startswith("--")]  # tests/test_web.py path_view ...: those alone
    if only:
        for name in only:
            globals()[name](browser)
        return
    first_panel(browser)
    every_method(browser)
    mistakes_in_input(browser)
    six_panels(browser)
    notes_numbers(browser)
    time_command(browser)
    references(browser)
    numbers_shown(browser)
    every_command_as_bdpt(browser)
    rays_as_notes(browser)
    terminal_free(browser)
    lessons(browser)
    notes_view(browser)
    code_view(browser)
    path_view(browser)
    dead_worker(browser)
    layout_and_link(browser, url)
    column_widths(browser)
    from_a_file(browser)
    browser.js("bdptPage.openNotes('07-probabilities')")
    browser.run("scenes/cornell.scene", ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "vcm"], 0, seconds=2)
    browser.js("bdptPage.clickPixel(4, 20, 44)")
    browser.wait_for("bdptPage.pathView() && bdptPage.pathView().x == 20")
    browser.screenshot(os.path.join(OUT, "page.png"))
    check(browser.workers_attached >= 6 and not browser.console_errors, "no error in the console of the page or of its %d workers (Runtime, Log)" % browser.workers_attached,
          "; ".join(browser.console_errors[:3]))
    print("      screenshot: build/test-web/page.png")


def first_panel(browser):
    # bdpt on cornell, 64x64 x 16, seed 1: the page's mean and error are ./bdpt's.
    panels = browser.run("scenes/cornell.scene", ["bdpt"], 16)
    w, h, ref, printed = native("scenes/cornell.scene", "bdpt", 16, extra=("--ref", "scenes/refs/cornell.pfm"))
    p = panels[0]
    check(p["passes"] == 16 and not p["error"] and close(p["mean"], mean(ref)), "cornell 64x64 x 16 spp bdpt: the page's mean is ./bdpt's",
          "page %.9g, ./bdpt %.9g" % (p["mean"], mean(ref)))
    m = re.search(r"rmse ([0-9.e-]+) \(([0-9.e-]+) without the lamp's pixels\), relmse ([0-9.e-]+), bias ([-+0-9.]+)%", printed)
    check(m and "%.4g" % p["rmse"] == m.group(1) and "%.4g" % p["rmseWithoutLamp"] == m.group(2) and "%+.2f" % (100 * p["bias"]) == m.group(4),
          "the panel's RMSE and bias are ./bdpt --ref's", "page %.4g (%.4g), %+.2f%%; ./bdpt %s" % (p["rmse"], p["rmseWithoutLamp"], 100 * p["bias"], m and m.group(0)))
    # The same numbers as the student reads them, in the panel's text: each where its words say.
    shown = re.search(r"(\d+) spp · [0-9.]+ s · mean ([0-9.e-]+) · RMSE ([0-9.e-]+) \(([0-9.e-]+) with the lamp's pixels\) · relMSE ([0-9.e-]+) · bias ([-+0-9.]+)% \(the mean's, the lamp's pixels left out\)", p["stats"])
    native_mean = float(re.search(r"mean ([0-9.e-]+),", printed).group(1))
    check(shown and shown.group(1) == "16" and abs(float(shown.group(2)) / native_mean - 1) < 1e-3 and m and shown.group(3) == m.group(2)
          and shown.group(4) == m.group(1) and shown.group(5) == m.group(3) and shown.group(6) == m.group(4),
          "the panel's text says ./bdpt's numbers, each under its own name (RMSE without the lamp first, with it in brackets, relMSE, bias "
          "saying it leaves the lamp's pixels out, as the mean does not: web-student-8's W20)",
          "page: %r; ./bdpt: %s" % (p["stats"], m and m.group(0)))

    # The canvas as drawn: ./bdpt's PNG, level for level (orientation, exposure and the sRGB curve).
    pixels = browser.js("bdptPage.canvasPixels(0)")
    pw, ph, ch, png = read_png(os.path.join(OUT, "native.png"))
    worst = max(abs(pixels[4 * i + c] - png[ch * i + c]) for i in range(pw * ph) for c in range(3))
    check((pw, ph) == (64, 64) and worst == 0, "the panel's canvas is ./bdpt's PNG to the level", "largest difference %d levels" % worst)

    # A click on a pixel: the bars are ./bdpt --strategies's images at that pixel (paths up to 5 segments).
    x, y = 20, 44
    bars = browser.js("bdptPage.clickPixel(0, %d, %d)" % (x, y))
    strat_dir = os.path.join(OUT, "strategies")
    os.makedirs(strat_dir, exist_ok=True)
    printed = native("scenes/cornell.scene", "bdpt", 16, extra=("--strategies", strat_dir, "--strategy-length", "5"))[3]
    # The rest of the summary line, as ./bdpt prints it for the same render (the strategies
    # recorded, as the page records them: s=1 t=1's weight-0 splat then has its shadow ray too).
    rays = re.search(r"[0-9.]+ rays per sample \([^)]*\)", printed).group(0)
    check(rays in p["stats"], "the panel shows ./bdpt's rays per sample", "./bdpt: %r; page: %r" % (rays, p["stats"]))
    worst, count = 0.0, 0
    for b in bars:
        _, _, img = read_pfm(os.path.join(strat_dir, "%s_%s.pfm" % (b["strategy"].replace(" ", "_"), b["kind"])))
        i = 3 * (y * w + x)
        expected = (img[i] + img[i + 1] + img[i + 2]) / 3
        worst = max(worst, abs(b["value"] - expected) / max(1e-6, abs(expected)))
        count += 1
    check(count == 40 and worst < 1e-5, "a clicked pixel's strategy chart: 20 strategies x (unweighted, weighted) = ./bdpt --strategies there",
          "%d bars, largest relative difference %.2g" % (count, worst))

    # With paths of at most 5 segments, the pyramid's weighted tiles sum to the image, pixel by pixel.
    browser.run("scenes/cornell.scene", ["bdpt --maxdepth 4"], 8)
    s = browser.js("bdptPage.pyramidSums()")
    worst = max(abs(a - b) / max(1e-4, b) for a, b in zip(s["sum"], s["image"]))
    check(s["drawn"] and s["tiles"] == 20 and worst < 1e-5, "the pyramid's weighted tiles sum to the image (--maxdepth 4: paths of at most 5 segments, every one in them)",
          "%d tiles, largest relative difference %.2g over %d pixels" % (s["tiles"], worst, len(s["sum"])))


def every_method(browser):
    # Every method once, six panels at a time, 4 spp: each mean is ./bdpt's. The last entry
    # carries a deliberate mistake that changes cornell's mean (by a quarter), so the page must pass it on.
    methods = ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "vcm", "pssmlt", "mmlt", "mlt", "lt --no-scramble"]
    for group in (methods[:6], methods[6:]):
        panels = browser.run("scenes/cornell.scene", group, 4)
        for entry, p in zip(group, panels):
            _, _, img, _ = native("scenes/cornell.scene", entry, 4)
            tolerance = 1e-5 if entry.split()[0] in ("pssmlt", "mmlt", "mlt") else 1e-6
            check(p["passes"] == 4 and not p["error"] and close(p["mean"], mean(img), tolerance),
                  "every method: '%s' mean as ./bdpt's within %g" % (entry, tolerance),
                  "page %.9g, ./bdpt %.9g, relative difference %.2g" % (p["mean"], mean(img), abs(p["mean"] / mean(img) - 1)))
    # An entry's own options win over the page's, as in ./bdpt --side-by-side.
    panels = browser.run("scenes/cornell.scene", ["pt --spp 3", "bdpt --res 32x32"], 2)
    check(panels[0]["passes"] == 3 and panels[1]["passes"] == 2 and (panels[1]["width"], panels[1]["height"]) == (32, 32),
          "an entry's --spp and --res win over the page's", "pt %d spp, bdpt %d spp at %dx%d" % (panels[0]["passes"], panels[1]["passes"], panels[1]["width"], panels[1]["height"]))


def mistakes_in_input(browser):
    # A scene with an error: the page shows ./bdpt's message, file:line, and renders nothing.
    text = open(os.path.join(ROOT, "scenes/cornell.scene")).read().split("\n")
    bad_line = next(i for i, l in enumerate(text) if l.startswith("material"))
    text[bad_line] = text[bad_line].replace("material", "materail", 1)
    bad = os.path.join(OUT, "cornell.scene")
    open(bad, "w").write("\n".join(text))
    expected = subprocess.run(["./bdpt", bad, "--out", os.path.join(OUT, "bad.png")], cwd=ROOT, capture_output=True, text=True).stderr.strip()
    expected = expected.replace(bad, "scenes/cornell.scene")
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    browser.js("bdptPage.setSceneText(%s)" % json.dumps("\n".join(text)))
    browser.js("bdptPage.setEntries(['bdpt'])")
    browser.js("bdptPage.run()")
    shown = browser.js("bdptPage.sceneError()")
    check(shown == expected and ":%d:" % (bad_line + 1) in shown and browser.js("bdptPage.panels().length") == 0,
          "a misspelt directive: the page shows ./bdpt's message with its line, and no panel", repr(shown))

    # A misspelt option in an entry: the panel shows ./bdpt's message, did-you-mean and all.
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    panels = browser.run("scenes/cornell.scene", ["bdpt --heurstic power", "pt"], 2)
    expected = subprocess.run(["./bdpt", "scenes/cornell.scene", "--method", "bdpt", "--heurstic", "power"],
                              cwd=ROOT, capture_output=True, text=True).stderr.strip().replace(" (see --help)", "")
    check(panels[0]["error"].startswith(expected) and "did you mean --heuristic?" in expected and panels[1]["passes"] == 2,
          "a misspelt option: the panel shows ./bdpt's message with its did-you-mean, the next one renders", repr(panels[0]["error"]))
    # Page 11's exercise 2: --strategy-length, which ./bdpt takes only with --strategies DIR, sets
    # the pyramid's length in the page (fewer strategies than the default 5 segments record).
    full = browser.run("scenes/sds.scene", ["bdpt --maxdepth 3"], 1)[0]
    four = browser.run("scenes/sds.scene", ["bdpt --maxdepth 3 --strategy-length 4"], 1)[0]
    check(not four["error"] and four["passes"] == 1 and 0 < four["strategies"] < full["strategies"]
          and any("--strategy-length 4" in n for n in four["notes"]),
          "an entry's --strategy-length: the panel renders and its pyramid stops at that length", "%d strategies (5 segments: %d), %r" % (four["strategies"], full["strategies"], four["notes"]))
    # A mistake on a scene that cannot show it is said so; on one that can, not.
    panels = browser.run("scenes/refraction.scene", ["lt", "lt --no-adjoint-correction"], 1)
    warned = any("cannot show" in n for n in panels[1]["notes"])
    panels = browser.run("scenes/shading-normals.scene", ["lt", "lt --no-adjoint-correction"], 1)
    check(warned and not any("cannot show" in n for n in panels[1]["notes"]) and panels[1]["what"].startswith("(c)"),
          "--no-adjoint-correction on refraction: 'this scene cannot show it'; on shading-normals: no such warning", repr(panels[1]["notes"]))


def six_panels(browser):
    # Six panels of 8 passes each (a count, not a time: a busy machine renders the same curves,
    # later): one curve per panel on the chart, the unbiased methods' falling; the pyramid redrawn
    # only when a panel's strategies come, not at every frame.
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    before = browser.js("bdptPage.pyramidRedraws() || 0")
    panels = browser.run("scenes/cornell.scene", ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "vcm"], 8)
    curves = browser.js("bdptPage.chartCurves()")
    # Clamped ir's error is its bias, which more passes do not remove: its curve need not fall.
    unbiased = [p for p in panels if p["entry"] != "ir --clamp 1e-5"]
    falling = [p["entry"] for p in unbiased if len(p["curve"]) >= 2 and p["curve"][-1][1] < p["curve"][0][1]]
    drawn_falling = [c["entry"] for c in curves if c["entry"] != "ir --clamp 1e-5" and c["points"][-1][1] > c["points"][0][1]]  # SVG y grows downwards
    check(sorted(c["entry"] for c in curves) == sorted(p["entry"] for p in panels) and len(falling) == 5 and len(drawn_falling) == 5,
          "six panels of 8 passes: the chart has one curve per panel, the unbiased methods' falling",
          ", ".join("%s %d points %.3g -> %.3g" % (p["entry"], len(p["curve"]), p["curve"][0][1], p["curve"][-1][1]) for p in panels if p["curve"]))
    redraws, frames = browser.js("bdptPage.pyramidRedraws()") - before, sum(len(p["curve"]) for p in panels)
    check(redraws <= 2 * 8 + 2, "the pyramid is redrawn when its strategies change, not at every frame",
          "%d redraws for 8 passes of its panel, %d curve points in all (the old page: one a frame)" % (redraws, frames))
    # 256x256, one pass each: the slow methods show their pass's rows before it ends, and every
    # panel its error against the 64x64 reference once the pass is done.
    panels = browser.run("scenes/cornell.scene", ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "vcm"], 1, resolution="256x256")
    within = [p["entry"] for p in panels if p["firstFramePasses"] == 0]
    check(all(p["firstFrameMs"] is not None for p in panels) and {"bdpt --heuristic power", "vcm", "ir --clamp 1e-5"} <= set(within),
          "256x256: bdpt, ir and vcm show their first pass's rows before it ends",
          ", ".join("%s first image %.0f ms after Start%s" % (p["entry"], p["firstFrameMs"], " (within its pass)" if p["firstFramePasses"] == 0 else "") for p in panels))
    check(all(p["comparedWidth"] == 64 and p["rmse"] for p in panels), "256x256: every panel has its error against the 64x64 reference",
          ", ".join("%s %.3g" % (p["entry"], p["rmseWithoutLamp"] or 0) for p in panels))


def time_command(browser):
    """A notes command that budgets time (page 16's --time 4): each panel renders for its time, not
    ./bdpt's 16 samples; read from what the worker was told and from the panel's text."""
    browser.js("bdptPage.openNotes('16-metropolis-sampling')")
    command = next(b["command"] for b in browser.js("bdptPage.notesButtons()") if b["runs"] and "--time 4" in b["command"])
    browser.js("bdptPage.clickNotesButton(%s)" % json.dumps(command))
    browser.wait_for("bdptPage.panels().length > 0 && !bdptPage.running()")
    panels = browser.js("bdptPage.panels()")
    seconds = [float(re.search(r"spp · ([0-9.]+) s", p["stats"]).group(1)) for p in panels]
    # not a timing threshold: the budget the command gives, 4 s, against what each panel says it spent
    check(len(panels) == 2 and all(p["limitSpp"] == 0 and p["limitSeconds"] == 4 for p in panels) and all(s >= 4 for s in seconds),
          "a notes command with --time 4: each panel told 4 s and no sample count, and rendered for 4 s by its own text",
          "; ".join("%s: told %s spp, %s s; shows %r" % (p["entry"], p["limitSpp"], p["limitSeconds"], p["stats"]) for p in panels))


def notes_numbers(browser):
    """Pages 1, 2, 11 and 13: the number the page quotes, from its button's run in the page."""
    def press(page, part):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        buttons = browser.js("bdptPage.notesButtons()")
        command = next(b["command"] for b in buttons if part in b["command"] and b["runs"])
        runs = browser.js("bdptPage.runs()")
        browser.js("bdptPage.clickNotesButton(%s)" % json.dumps(command))
        browser.wait_for("bdptPage.runs() > %d && !bdptPage.running()" % runs)
        return {p["entry"]: p for p in browser.js("bdptPage.panels()")}, buttons

    text = page_text("01-path-sampling-techniques")
    quoted = re.search(r"prints bias ([-+0-9.]+)% for lt .*?([-+0-9.]+)% for clamped ir", text)
    panels, _ = press("01-path-sampling-techniques", "--ref scenes/refs/cornell-glass.pfm")
    shown = ["%+.2f" % (100 * panels[e]["bias"]) for e in ("lt", "ir --clamp 1e-5")]
    check(quoted and list(quoted.groups()) == shown, "page 1's button: lt's and clamped ir's bias as the page quotes them",
          "page %s, the page's panels %s" % (quoted and list(quoted.groups()), shown))

    text = page_text("02-light-and-path-tracing")
    quoted = re.search(r"means ([0-9.]+) and ([0-9.]+) in the figure's run", text).groups()
    panels, buttons = press("02-light-and-path-tracing", "--maxdepth 1 --spp 4 --res 192x192")
    shown = ["%.4f" % panels[e]["mean"] for e in ("lt --maxdepth 1", "pt --maxdepth 1")]
    check(list(quoted) == shown, "page 2's button: lt's and pt's means as the page quotes them", "page %s, the page's panels %s" % (list(quoted), shown))

    text = page_text("11-contributions-of-paths")
    quoted = re.search(r"s2_t1 \(mean ([0-9.]+) of its weighted image, half of the whole image's ([0-9.]+)\)", text).groups()
    panels, _ = press("11-contributions-of-paths", "scenes/indirect.scene --method bdpt --spp 64")
    # web-student-8's 11.1: the tile's mean is drawn on the pyramid, not only held by the page
    browser.wait_for("bdptPage.pyramidLabels().some((l) => l.startsWith('s=2 t=1 '))")
    drawn = next(l for l in browser.js("bdptPage.pyramidLabels()") if l.startswith("s=2 t=1 "))
    shown = [drawn.split("mean ")[-1], "%.3f" % panels["bdpt"]["mean"]]
    check(list(quoted) == shown, "page 11's button: s2_t1's weighted mean drawn on its tile and the image's, as the page quotes them",
          "page %s, the pyramid's label %r and the panel's mean %s" % (list(quoted), drawn, shown[1]))

    text = page_text("13-shading-normals")
    quoted = re.search(r"means ([0-9.]+) and ([0-9.]+) in the figure's run.*?\(([0-9.]+) against ([0-9.]+), the figure's", text).groups()
    panels, _ = press("13-shading-normals", "scenes/energy-generator.scene --side-by-side")
    shown = ["%.5f" % panels["nee"]["mean"], "%.5f" % panels["lt"]["mean"], "%.5f" % panels["nee"]["mean"],
             "%.4g" % panels["nee tests/energy-generator-flat.scene"]["mean"]]
    check(list(quoted) == shown, "page 13's button: the energy generator's means as the page quotes them", "page %s, the page's panels %s" % (list(quoted), shown))

    # Every page's commands: a button each, and a reason on the ones the page cannot run.
    total = runs = 0
    for page in browser.js("BDPT_NOTES.map((p) => p.file)"):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        buttons = browser.js("bdptPage.notesButtons()")
        total, runs = total + len(buttons), runs + sum(b["runs"] for b in buttons)
        check(all(b["runs"] or b["reason"] for b in buttons), "notes page %s: every command has a button or a reason" % page) if not all(b["runs"] or b["reason"] for b in buttons) else None
    formulas, figures = browser.js("document.querySelectorAll('.katex').length"), 0
    check(runs >= 40 and total > runs, "the notes' commands: the page runs %d of %d, and says where to run the others" % (runs, total))
    for page in ("07-probabilities", "13-shading-normals", "15-vertex-merging"):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        browser.wait_for("[...document.querySelectorAll('#notes-text img')].every((i) => i.complete)")
        figures += browser.js("[...document.querySelectorAll('#notes-text img')].filter((i) => i.naturalWidth > 0).length")
        formulas += browser.js("document.querySelectorAll('#notes-text .katex').length")
        bad = browser.js("[...document.querySelectorAll('#notes-text img')].filter((i) => i.naturalWidth === 0).map((i) => i.src)")
        check(not bad, "notes page %s: its figures load" % page, ", ".join(bad))
    check(formulas >= 5 and figures >= 5, "the notes in the page: formulas typeset by KaTeX, figures shown", "%d formulas and %d figures on pages 7, 13, 15" % (formulas, figures))


def dead_worker(browser):
    # A worker that dies without a word (as one killed out of memory): its panel ends with a
    # message after the silence limit (set short here), the others render on, Stop ends the run,
    # and the next run renders in that slot again.
    browser.js("bdptPage.setSilenceLimit(3000)")
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    browser.js("bdptPage.setEntries(['pt', 'nee'])")
    browser.js("bdptPage.setOptions({resolution: '64x64', spp: 0, seconds: 0, seed: 1})")
    browser.js("bdptPage.run(); 0")
    browser.wait_for("bdptPage.panels().length == 2 && bdptPage.panels().every((p) => p.passes > 0)")
    browser.js("bdptPage.killWorker(1)")
    try:  # 3 s of silence and the next second's look: a minute is a hang's guard
        browser.wait_for("bdptPage.panels()[1].done", 60)
    except RuntimeError:
        pass
    p = browser.js("bdptPage.panels()")
    check("stopped answering" in (p[1]["error"] or "") and not p[0]["done"], "a killed worker: its panel ends with a message, the other renders on", repr(p[1]["error"]))
    browser.js("bdptPage.killWorker(0)")
    browser.js("bdptPage.stop()")
    try:
        browser.wait_for("!bdptPage.running()", 60)
    except RuntimeError:
        pass
    p = browser.js("bdptPage.panels()")
    check(p[0]["done"] and "did not answer" in (p[0]["error"] or ""), "Stop ends a run whose worker is dead", repr(p[0]["error"]))
    browser.js("bdptPage.setSilenceLimit(60000)")
    p = browser.run("scenes/cornell.scene", ["pt", "nee"], 2)
    check(all(x["passes"] == 2 and not x["error"] for x in p), "the next run renders in the dead workers' slots")


def layout_and_link(browser, url):
    # No sideways scrolling at a laptop's and a phone's size, with six panels, the pyramid and a
    # long notes page with tables; and a link that keeps the setting.
    browser.js("bdptPage.openNotes('appendix-a-speed-and-accuracy')")
    browser.run("scenes/cornell.scene", ["pt", "nee --mis", "lt", "ir --clamp 1e-5", "bdpt --heuristic power", "lt --no-adjoint-correction"], 1)
    for w, h in ((1366, 768), (390, 844), (1920, 1080)):
        browser.size(w, h)
        o = browser.js("new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r(bdptPage.overflow()))))")
        check(o["scrollWidth"] <= o["innerWidth"], "%dx%d: nothing wider than the window" % (w, h), "page width %d in a window of %d" % (o["scrollWidth"], o["innerWidth"]))
        browser.screenshot(os.path.join(OUT, "page-%dx%d.png" % (w, h)), w, h)
    browser.js("bdptPage.openNotes('07-probabilities')")
    browser.js("bdptPage.selectScene('scenes/refraction.scene')")
    browser.js("bdptPage.setEntries(['lt', 'lt --symmetric-refraction'])")
    browser.js("bdptPage.setOptions({resolution: '32x32', spp: 3, seconds: 0, seed: 5})")
    browser.js("bdptPage.run()")
    link = browser.js("location.href")
    browser.open(url)  # a fresh page, then the link
    browser.call("Page.navigate", url="about:blank")
    browser.open(link)
    got = browser.js("[document.getElementById('scene').value, [...document.querySelectorAll('input.entry')].map((e) => e.value).filter((e) => e), "
                     "document.getElementById('resolution').value, document.getElementById('spp').value, document.getElementById('seed').value, "
                     "document.getElementById('notes-page').value]")
    check(got == ["scenes/refraction.scene", ["lt", "lt --symmetric-refraction"], "32x32", "3", "5", "07-probabilities"],
          "a link to the page keeps its scene, methods, settings and notes page", repr(got))


def column_widths(browser):
    """web-student-8's W4, W17, W18: display formulas, the code view and the path view's tables stay
    inside their column at a laptop's and a phone's size (nothing cut at the right, no scrollbar)."""
    frames = "new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => r(%s))))"
    wide = "(sel) => [...document.querySelectorAll(sel)].filter((e) => e.offsetParent && e.scrollWidth > e.clientWidth + 1).length"
    browser.run("scenes/cornell.scene", ["bdpt"], 1)
    for w, h in ((1366, 768), (390, 844)):
        browser.size(w, h)
        formulas, cut = 0, []
        for page in browser.js("BDPT_NOTES.map((p) => p.file)"):
            browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
            n, over = browser.js(frames % ("[document.querySelectorAll('#notes-text .katex-display').length, (%s)('#notes-text .katex-display')]" % wide))
            formulas += n
            if over:
                cut.append("%s: %d" % (page, over))
        browser.js("bdptPage.openCode('connectionJunction')")
        code = browser.js(frames % "(() => { const c = document.getElementById('code-text'); return [c.scrollWidth, c.clientWidth]; })()")
        browser.js("bdptPage.openNotes('07-probabilities')")
        browser.js("bdptPage.clickPixel(0, 20, 44)")
        browser.wait_for("bdptPage.pathView() && bdptPage.pathView().x == 20")
        table = browser.js(frames % "(() => { const t = document.getElementById('path-tables'); return [t.scrollWidth, t.clientWidth]; })()")
        check(formulas >= 10 and not cut and code[0] <= code[1] + 1 and table[0] <= table[1] + 1,
              "%dx%d: every page's %d display formulas, the code view and the path view's tables each inside its column" % (w, h, formulas),
              "formulas cut: %s; code %d in %d px; path tables %d in %d px" % (cut, code[0], code[1], table[0], table[1]))
    browser.size(1920, 1080)


def from_a_file(browser):
    # Opened from disk (file://): the workers start from a Blob, the wasm is inlined: it renders.
    browser.open("file://" + os.path.join(ROOT, "build", "web", "index.html"))
    panels = browser.run("scenes/cornell.scene", ["nee --mis"], 4)
    _, _, img, _ = native("scenes/cornell.scene", "nee --mis", 4)
    check(panels[0]["passes"] == 4 and close(panels[0]["mean"], mean(img)), "index.html opened from a file renders, ./bdpt's mean",
          "page %.9g, ./bdpt %.9g" % (panels[0]["mean"], mean(img)))


def press_button(browser, page, part):
    """A notes page's run button whose command contains `part`: pressed, the run waited for."""
    browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
    command = next(b["command"] for b in browser.js("bdptPage.notesButtons()") if part in b["command"] and b["runs"])
    runs = browser.js("bdptPage.runs()")
    browser.js("bdptPage.clickNotesButton(%s)" % json.dumps(command))
    browser.wait_for("bdptPage.runs() > %d && !bdptPage.running()" % runs)
    return browser.js("bdptPage.panels()"), command


def references(browser):
    """web-student-7's defects 2, 4, 5, 12, 13: what a panel is measured against, and saying so."""
    # 2: an edited scene is never measured against the committed scene's reference: the furnace at
    # albedo 0.8 says "no reference" (the old page: "bias +149.85%"); once the page has rendered a
    # reference for the text, its error is against that one, whose mean is the closed form.
    # (0.7, not higher: the lamp's pixels are those above 5, which a furnace of Le / (1 - a) > 5 would all be)
    text = open(os.path.join(ROOT, "scenes/furnace.scene")).read().replace("diffuse 0.5 0.5 0.5", "diffuse 0.7 0.7 0.7")
    browser.js("bdptPage.selectScene('scenes/furnace.scene')")
    browser.js("bdptPage.setSceneText(%s)" % json.dumps(text))
    browser.js("bdptPage.setEntries(['nee'])")
    browser.js("bdptPage.setOptions({resolution: '64x64', spp: 4, seconds: 0, seed: 1})")
    browser.js("bdptPage.run()")
    p = browser.js("bdptPage.panels()")[0]
    check(p["rmse"] is None and "edited scene: no reference" in p["stats"] and "bias" not in p["stats"],
          "an edited scene (the furnace at albedo 0.7): 'edited scene: no reference', no error against the committed scene's", repr(p["stats"]))
    browser.js("bdptPage.renderReference({spp: 16})")
    state = browser.js("bdptPage.referenceState()")
    browser.js("bdptPage.setOptions({spp: 16})")
    browser.js("bdptPage.run()")
    p = browser.js("bdptPage.panels()")[0]
    closed_form = (1 - 0.7 ** 33) / (1 - 0.7)  # Le (1 - a^(D+1)) / (1 - a), D = 32 bounces
    shown = re.search(r"its reference: bdpt, 64×64, 16 spp", state)
    check(shown and p["bias"] is not None and abs(p["bias"]) < 0.02 and abs(p["mean"] / closed_form - 1) < 0.02
          and "against the reference the page rendered for this text" in p["stats"],
          "the furnace at 0.7 with the reference the page rendered for it: the nee panel's bias within 2%%, its mean the closed form %.4f" % closed_form,
          "reference: %r; panel: mean %.4f, bias %s; %r" % (state, p["mean"], p["bias"], p["stats"]))
    # web-student-8's 9.3: page 9's glossy floor, made in the editor as the exercise says, with the
    # page's own reference: seed 1's RMSE within the seeds' range the answer quotes (64x64, as in the page).
    quoted = re.search(r"RMSE ([0-9.]+)-([0-9.]+) without `--mis`, ([0-9.]+)-([0-9.]+) with it \(seeds 1 to 4, 64x64 as in the page\)",
                       page_text("09-russian-roulette-and-sampling"))
    text = "".join(line.replace("white", "polished") if line.startswith("quad 0 0 0 ") and "# floor" in line else
                   line + ("material polished glossy 0.8 0.8 0.8 2000\n" if line.startswith("material lamp") else "")
                   for line in open(os.path.join(ROOT, "scenes/cornell.scene")).readlines())
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    browser.js("bdptPage.setSceneText(%s)" % json.dumps(text))
    browser.js("bdptPage.renderReference({spp: 512})")
    browser.js("bdptPage.setEntries(['nee', 'nee --mis'])")
    browser.js("bdptPage.setOptions({resolution: '64x64', spp: 16, seconds: 0, seed: 1})")
    browser.js("bdptPage.run()")
    browser.wait_for("!bdptPage.running()")
    rmse = [p["rmse"] for p in browser.js("bdptPage.panels()")]
    ranges = quoted and [(float(quoted.group(1)), float(quoted.group(2))), (float(quoted.group(3)), float(quoted.group(4)))]
    check(quoted and all(r is not None and lo * 0.98 <= r <= hi * 1.02 for r, (lo, hi) in zip(rmse, ranges)),
          "page 9's exercise 3 in the page's editor, against the page's reference: nee's and nee --mis's RMSE within the answer's ranges",
          "answer %s; panels %s" % (ranges, rmse))
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")

    # The other scenes an exercise has the student write (pages 4, 6, 13): made in the editor, each
    # command's options on the scene it starts from; the panels' means are the answers' (test_notes
    # holds those to ./bdpt's on the same scene).
    written = []
    for page, command, base, change, pattern, entries in (
            ("04-measurement-equation", "./bdpt build/furnace-08.scene --method pt --maxdepth 3 --spp 16", "furnace", ("diffuse 0.5 0.5 0.5", "diffuse 0.8 0.8 0.8"),
             r"\(the renderer: ([0-9.]+)\)", ["pt --maxdepth 3"]),
            ("04-measurement-equation", "./bdpt build/furnace-08.scene --method pt --maxdepth 32 --spp 16", "furnace", ("diffuse 0.5 0.5 0.5", "diffuse 0.8 0.8 0.8"),
             r"the renderer gives ([0-9.]+)", ["pt --maxdepth 32"]),
            ("06-extending-paths", "./bdpt build/pool-ior1.scene --side-by-side pt,lt --spp 64 --res 64x48", "refraction", ("material water glass 1.33", "material water glass 1.0"),
             r"image means pt ([0-9.]+), lt ([0-9.]+)", ["pt", "lt"]),
            ("13-shading-normals", "./bdpt build/energy-20.scene --method nee --spp 64", "energy-generator", ("tilt 60", "tilt 20"),
             r"the image mean halves \([0-9.]+ -> ([0-9.]+)\)", ["nee"])):
        quoted = re.search(pattern, page_text(page))
        reason = browser.js("bdptPage.applyCommand(%s)" % json.dumps(re.sub(r"build/[\w-]+\.scene", "scenes/%s.scene" % base, command)))
        text = open(os.path.join(ROOT, "scenes", base + ".scene")).read()
        browser.js("bdptPage.setSceneText(%s)" % json.dumps(text.replace(*change)))
        browser.js("bdptPage.run()")
        browser.wait_for("!bdptPage.running()")
        means = {p["entry"]: p["mean"] for p in browser.js("bdptPage.panels()")}
        digits = [len(q.split(".")[1]) if "." in q else 0 for q in (quoted.groups() if quoted else [])]
        shown = ["%.*f" % (d, means.get(e, float("nan"))) for d, e in zip(digits, entries)]
        written.append((page, command, change[0] in text and not reason and quoted is not None and list(quoted.groups()) == shown,
                        quoted and quoted.groups(), shown))
    check(all(ok for _, _, ok, _, _ in written), "the exercises' written scenes (pages 4, 6, 13) made in the editor: the panels' means are the answers'",
          "; ".join("%s %s: answer %s, panels %s" % (p, c, q, sh) for p, c, ok, q, sh in written if not ok) or "; ".join("%s: %s" % (p, sh) for p, _, _, _, sh in written))
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")

    # 4: a notes command's --ref is honoured (page 2's 24x24 button names tests/refs/cornell-direct.pfm):
    # the panel's RMSE is ./bdpt --ref's, and the panel names the file.
    panels, command = press_button(browser, "02-light-and-path-tracing", "--ref tests/refs/cornell-direct.pfm")
    printed = subprocess.run(shlex.split(command.replace("--out build/notes/", "--out build/test-web/")), cwd=ROOT, check=True, capture_output=True, text=True).stdout
    m = re.search(r"rmse ([0-9.e-]+) \(([0-9.e-]+) without", printed)
    p = panels[0]
    check(m and p["rmseWithoutLamp"] is not None and "%.4g" % p["rmseWithoutLamp"] == m.group(2) and "against tests/refs/cornell-direct.pfm" in p["stats"],
          "page 2's 24x24 button: its --ref honoured, the panel's RMSE ./bdpt's against tests/refs/cornell-direct.pfm",
          "./bdpt: %s; page: %r" % (m and m.group(0), p["stats"]))
    # web-student-8's W1: that reference holds direct light only, and its entry cuts lengths: the
    # panel must not say the reference has paths of every length.
    check("--maxdepth" in command and all("paths of every length" not in q["stats"] for q in panels),
          "page 2's --ref tests/refs/cornell-direct.pfm with --maxdepth: no '(the reference has paths of every length)'", "; ".join(q["stats"] for q in panels))

    # A reference is the scene's own, by its whole name: sds at 96x64 is measured against
    # web-refs/sds-96x64.pfm, never sds-point's (a right render then shows a bias of +40%);
    # cornell at 50x50 never against cornell-glass-50x50.pfm.
    chosen = []
    for scene, res, want, never in (("sds", "96x64", "against web-refs/sds-96x64.pfm", "sds-point"), ("cornell", "50x50", "", "cornell-glass")):
        browser.js("bdptPage.selectScene('scenes/%s.scene')" % scene)
        browser.js("bdptPage.setEntries(['bdpt'])")
        browser.js("bdptPage.setOptions({resolution: '%s', spp: 1, seconds: 0, seed: 1})" % res)
        browser.js("bdptPage.run()")
        stats = browser.js("bdptPage.panels()")[0]["stats"]
        chosen.append((scene, res, want in stats and never not in stats, stats))
    check(all(ok for _, _, ok, _ in chosen), "a panel's reference is its scene's own by the whole name: sds at 96x64 against web-refs/sds-96x64.pfm, "
          "cornell at 50x50 never against cornell-glass's", "; ".join("%s %s: %r" % (sc, r, st) for sc, r, ok, st in chosen if not ok))
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")

    # 4: every notes button measures its panels' error where the scene has a reference: checked
    # with every button's run, in every_command_as_bdpt.

    # 5: after a run with curves, a run without any error: the chart's caption says why, and no
    # longer lists the last run's panels.
    browser.run("scenes/cornell.scene", ["pt", "lt"], 2)
    browser.run("tests/thin-gap.scene", ["nee"], 1)
    caption = browser.js("document.getElementById('chart-caption').textContent")
    check(caption.startswith("Error against time: this scene has no reference") and " lt" not in caption,
          "a run without an error after one with curves: the chart's caption says why, not the last run's legend", repr(caption))

    # 12: lt on cornell-point: the point light's own pixel is the lamp's, as ./bdpt --ref leaves it out.
    p = browser.run("scenes/cornell-point.scene", ["lt"], 4)[0]
    printed = subprocess.run(["./bdpt", "scenes/cornell-point.scene", "--method", "lt", "--res", "64x64", "--spp", "4", "--out", os.path.join(OUT, "point.png"),
                              "--ref", "scenes/refs/cornell-point.pfm"], cwd=ROOT, check=True, capture_output=True, text=True).stdout
    m = re.search(r"bias ([-+0-9.]+)%", printed)
    check(m and "%+.2f" % (100 * p["bias"]) == m.group(1) and abs(p["bias"]) < 0.05, "lt on cornell-point: the page's bias is ./bdpt --ref's (the point light's pixel left out)",
          "page %+.2f%%, ./bdpt %s%%" % (100 * p["bias"], m and m.group(1)))

    # 13: "(the reference has paths of every length)" only where the entry cuts lengths.
    panels = browser.run("scenes/cornell.scene", ["pt --rr-start 8", "pt --maxdepth 1"], 1)
    note = "(the reference has paths of every length)"
    check(note not in panels[0]["stats"] and note in panels[1]["stats"], "'paths of every length' said for --maxdepth, not for --rr-start",
          "; ".join(p["stats"] for p in panels))


def every_command_as_bdpt(browser):
    """One number everywhere: every notes command the page runs, at one pass, shows in each panel
    the mean and the rays per sample ./bdpt prints for that entry (with the pyramid's record where
    the command has --strategies, as ./bdpt --strategies records it). test_notes holds the notes'
    numbers to ./bdpt's output, so the page's numbers are the notes'."""
    differ, compared, record, without, total = [], 0, os.path.join(OUT, "every-command-strategies"), [], 0
    for page in browser.js("BDPT_NOTES.map((p) => p.file)"):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        for b in [b for b in browser.js("bdptPage.notesButtons()") if b["runs"]]:
            total += 1
            runs = browser.js("bdptPage.runs()")
            browser.js("bdptPage.clickNotesButton(%s)" % json.dumps(b["command"]))
            browser.wait_for("bdptPage.runs() > %d" % runs)
            browser.js("bdptPage.stop()")
            browser.wait_for("!bdptPage.running()")
            # the button's scene, entries, size, seed and record, one pass (an entry's own --spp too)
            entries = [re.sub(r"\s*--spp\s+\d+", "", e) for e in browser.js("[...document.querySelectorAll('input.entry')].map((e) => e.value)")]
            browser.js("bdptPage.setEntries(%s)" % json.dumps(entries))
            browser.js("bdptPage.setOptions({spp: 1, seconds: 0})")
            browser.js("bdptPage.run()")
            browser.wait_for("!bdptPage.running()")
            scene, res, seed = browser.js("['scene', 'resolution', 'seed'].map((id) => document.getElementById(id).value)")
            recorded = "--strategies" in b["command"].split()  # as ./bdpt runs the command: the record only with --strategies
            panels = browser.js("bdptPage.panels()")
            # web-student-7's 4: each panel measures its error where the scene has a reference (the old
            # page: 18 of 45 buttons said "no error"), at the size where the two meet
            without += ["%s: %s: %s %s" % (page, p["entry"], p["stats"][:120], p["error"]) for p in panels
                        if not p.get("commonWidth") and (p.get("referenceWidth") or p["error"])]
            for p in panels:
                words = p["entry"].split()
                if p["error"] or not p["passes"] or "--time" in words or "--wall-time" in words:
                    continue
                own = next((w for w in words if w.endswith(".scene")), scene)
                words = [w for w in words if not w.endswith(".scene")]
                cmd = ["./bdpt", own, "--method", *words, "--out", os.path.join(OUT, "every-command.png")]
                for option, value in (("--res", res), ("--spp", "1"), ("--seed", seed)):
                    if option not in words and value != "0x0":
                        cmd += [option, value]
                if recorded and words[0] in ("bdpt", "vcm"):
                    cmd += ["--strategies", record, "--strategy-length", "5"]
                printed = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True).stdout
                rays, mean = re.search(r"[0-9.]+ rays per sample \([^)]*\)", printed), re.search(r"mean ([0-9.e+-]+),", printed)
                compared += 1
                if not (rays and mean and rays.group(0) in p["stats"] and abs(p["mean"] - float(mean.group(1))) <= 1e-5 * max(1e-6, abs(p["mean"]))):
                    differ.append("%s: %s: page %r; ./bdpt %s, mean %s" % (page, p["entry"], p["stats"][:200], rays and rays.group(0), mean and mean.group(1)))
    check(total >= 40 and not without, "every notes button measures its panels' error where the scene has a reference (%d buttons)" % total, "; ".join(without[:4]))
    check(compared >= 60 and not differ, "every notes command the page runs (%d panels at one pass): the mean and rays per sample ./bdpt prints" % compared,
          "; ".join(differ[:3]))
    browser.js("bdptPage.setOptions({strategies: true})")


def rays_as_notes(browser):
    """web-student-8's W2: the rays per sample a panel shows are the notes' for the same command,
    and a panel that records the pyramid says that its count includes the record's rays."""
    def rays_of(panels):
        return {p["entry"]: re.search(r"([0-9.]+) rays per sample", p["stats"]).group(1) for p in panels}

    # Page 12, exercise 3: its button (pt), then the other methods as the exercise asks.
    quoted = re.search(r"pt ([0-9.]+) rays per sample \(all closest-hit\), nee ([0-9.]+), lt ([0-9.]+), bdpt ([0-9.]+)", page_text("12-comparison-with-path-tracing"))
    press_button(browser, "12-comparison-with-path-tracing", "build/notes/rays.png")
    browser.js("bdptPage.setEntries(['pt', 'nee', 'lt', 'bdpt'])")
    browser.js("bdptPage.run()")
    browser.wait_for("!bdptPage.running()")
    rays = rays_of(browser.js("bdptPage.panels()"))
    check(quoted and list(quoted.groups()) == [rays.get(m) for m in ("pt", "nee", "lt", "bdpt")],
          "page 12's exercise 3: the rays per sample of pt, nee, lt and bdpt as its answer quotes them", "answer %s; panels %s" % (quoted and quoted.groups(), rays))
    # Page 9, exercise 2: glass-box under the three roulette rules.
    quoted = re.search(r"Rays per sample: throughput ([0-9.]+), albedo ([0-9.]+), off ([0-9.]+)", page_text("09-russian-roulette-and-sampling"))
    press_button(browser, "09-russian-roulette-and-sampling", "--roulette throughput")
    rules = ["bdpt --roulette %s" % r for r in ("throughput", "albedo", "off")]
    browser.js("bdptPage.setEntries(%s)" % json.dumps(rules))
    browser.js("bdptPage.run()")
    browser.wait_for("!bdptPage.running()")
    rays = rays_of(browser.js("bdptPage.panels()"))
    check(quoted and list(quoted.groups()) == [rays.get(r) for r in rules],
          "page 9's exercise 2: glass-box's rays per sample under the three roulette rules as its answer quotes them", "answer %s; panels %s" % (quoted and quoted.groups(), rays))
    # W10: vcm's memory as page 15 quotes it for the page (its WebAssembly's own sizes).
    quoted = re.search(r"In the web page the same command\s+reports ([0-9]+) bytes and ([0-9.]+) MB", page_text("15-vertex-merging"))
    panels, _ = press_button(browser, "15-vertex-merging", "build/notes/vcm-memory.png")
    shown = re.search(r"([0-9.]+) MB \(([0-9]+) bytes per light vertex\)", panels[0]["stats"])
    check(quoted and shown and [quoted.group(1), quoted.group(2)] == [shown.group(2), shown.group(1)],
          "page 15's vcm memory for the page: the bytes per light vertex and MB its panel shows", "notes %s; panel %r" % (quoted and quoted.groups(), panels[0]["stats"]))
    # A run of one's own with the pyramid recorded: its count is ./bdpt --strategies's, and says so.
    browser.js("bdptPage.setOptions({strategies: true})")
    p = browser.run("scenes/cornell.scene", ["bdpt"], 2)[0]  # (the record stays on, the page's default, for the checks after)
    check("with the pyramid's record" in p["stats"], "a bdpt panel that records the pyramid says its rays include the record's", repr(p["stats"]))


def terminal_free(browser):
    """web-student-8's W6, W13, W15: what the notes send to a terminal, the page does with its own
    tools or says how: a scene the exercise has the student write, in the scene editor; --compare,
    by the panels' own numbers; tests/glass-camera.scene, in the scene menu, with page 14's answer."""
    written, compare = [], []
    for page in browser.js("BDPT_NOTES.map((p) => p.file)"):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        for b in browser.js("bdptPage.notesButtons()"):
            if re.search(r"\sbuild/[\w-]+\.scene", b["command"]) and b["command"].startswith("./bdpt"):
                written.append((page, b["reason"]))
            if "--compare" in b["command"]:
                compare.append((page, b["reason"]))
    check(len(written) >= 4 and all("scene editor" in r for _, r in written),
          "the exercises' own scenes (build/*.scene, %d commands): each button says to make it in the page's scene editor" % len(written),
          "; ".join("%s: %r" % w for w in written if "scene editor" not in w[1]))
    check(compare and all("not an option" not in r and "panels" in r for _, r in compare),
          "--compare's commands (%d): the page says its panels' numbers stand for it" % len(compare), "; ".join("%s: %r" % c for c in compare))
    menu = browser.js("[...document.getElementById('scene').options].map((o) => o.value)")
    panels = browser.run("tests/glass-camera.scene", ["pt", "pt --symmetric-refraction"], 4, resolution="16x16")
    means = [p["mean"] for p in panels]
    check("tests/glass-camera.scene" in menu and abs(means[0] / 2.25 - 1) < 0.01 and abs(means[1] - 1) < 0.01,
          "tests/glass-camera.scene in the scene menu: page 14's exercise 1 in the page, means 2.25 and 1 as its answer says",
          "menu has it: %s; means %s" % ("tests/glass-camera.scene" in menu, means))
    browser.js("bdptPage.selectScene('scenes/cornell.scene')")
    # W9: page 10M's block of three commands: each button says which it runs, the ratio image's where it is.
    browser.js("bdptPage.openNotes('10m-mirrors-and-glass')")
    labels = [b["label"] for b in browser.js("bdptPage.notesButtons()") if b["runs"] and "glass-box" in b["command"]]
    check(len(labels) >= 3 and len(set(labels)) == len(labels) and any("ratio image" in l for l in labels),
          "page 10M's three commands: three different button labels, the ratio panel's saying the page shows both panels instead", repr(labels))
    # W14: a command inside a sentence: its button after the sentence's paragraph, never inside the sentence.
    inside = []
    for page in ("02-light-and-path-tracing", "03-bidirectional-path-tracing", "09-russian-roulette-and-sampling", "11-contributions-of-paths",
                 "12-comparison-with-path-tracing", "15-vertex-merging", "17-veach-mutations"):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        # a bar that is not after a code block must close its paragraph: only other bars follow it
        inside += browser.js("[...document.querySelectorAll('#notes-text .commands')].filter((b) => !(b.previousElementSibling && b.previousElementSibling.tagName === 'PRE') && "
                             "(() => { for (let n = b.nextSibling; n; n = n.nextSibling) if (!(n.nodeType === 1 && n.classList.contains('commands')) && n.textContent.trim()) return true; return false; })())"
                             ".map((b) => %s + ': ' + b.parentElement.outerHTML.slice(0, 300))" % json.dumps(page))
    check(not inside, "the notes' commands inside sentences: each button after its paragraph", "; ".join(inside[:3]))
    # W3: a pyramid button shows the pyramid its figure shows: page 7's unweighted, page 10's weighted.
    shown = []
    for page, part, want in (("07-probabilities", "pyramid-balance", False), ("10-combining-estimators", "pyramid-max", True)):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        command = next(b["command"] for b in browser.js("bdptPage.notesButtons()") if part in b["command"] and b["runs"])
        runs = browser.js("bdptPage.runs()")
        browser.js("bdptPage.clickNotesButton(%s)" % json.dumps(command))
        browser.wait_for("bdptPage.runs() > %d" % runs)
        shown.append((page, browser.js("document.getElementById('weighted').checked"), want, browser.js("document.getElementById('record-strategies').checked")))
        browser.js("bdptPage.stop()")
        browser.wait_for("!bdptPage.running()")
    check(all(w == want and recorded for _, w, want, recorded in shown), "a pyramid's button records it and shows it as its figure does: page 7 unweighted, page 10 weighted", repr(shown))
    browser.js("document.getElementById('weighted').checked = true")
    # W5: an option the method would ignore is refused, with ./bdpt's own message.
    panels = browser.run("scenes/cornell.scene", ["nee --mis --heuristic balance", "nee --mis"], 1)
    printed = subprocess.run(["./bdpt", "scenes/cornell.scene", "--method", "nee", "--mis", "--heuristic", "balance"], cwd=ROOT, capture_output=True, text=True).stderr
    check("applies to" in panels[0]["error"] and panels[0]["error"].split(" (see")[0] in printed and panels[1]["passes"] == 1,
          "nee --mis --heuristic balance: the panel refuses it with ./bdpt's message, the next one renders", "page %r; ./bdpt %r" % (panels[0]["error"], printed))
    # W19: the contents page opens with what a student needs; how the figures are made and tested
    # comes last, under the instructor's heading.
    first = browser.js("(() => { const f = BDPT_NOTES[0]; const d = document.createElement('div'); d.innerHTML = f.html; "
                       "const p = d.querySelector('p'); return [f.file, p ? p.textContent : '', d.textContent]; })()")
    check(first[0].startswith("README") and "make figures" not in first[1] and "test" not in first[1]
          and first[2].index("For the instructor") > first[2].index("slide title"),
          "the contents page's first paragraph speaks to the student (no make figures, no tests); the instructor's part comes last", repr(first[1][:200]))


def numbers_shown(browser):
    """web-student-7's defect 3 and 6: the summary's numbers beside each panel, as ./bdpt prints
    them; nee --mis described by the heuristic its code uses."""
    panels = browser.run("scenes/cornell.scene", ["vcm", "mlt", "ir --clamp 1e-5"], 2)
    by = {p["entry"]: p for p in panels}
    lines = {}
    for entry in by:
        printed = subprocess.run(["./bdpt", "scenes/cornell.scene", "--method", *entry.split(), "--res", "64x64", "--spp", "2", "--out", os.path.join(OUT, "sum.png")],
                                 cwd=ROOT, check=True, capture_output=True, text=True).stdout
        lines[entry] = printed
    # vcm: radius and light vertices per pixel as ./bdpt's (memory differs: WebAssembly's pointers are 4 bytes)
    vcm = re.search(r"vcm: radius ([0-9.e-]+) in pass 1, ([0-9.e-]+) in pass 2; ([0-9.]+) light vertices per pixel and pass, ([0-9.]+) of them mergeable; light subpaths and grid ([0-9.]+) MB", lines["vcm"])
    shown = re.search(r"vcm: radius ([0-9.e-]+) in pass 1, ([0-9.e-]+) in pass 2; ([0-9.]+) light vertices per pixel and pass, ([0-9.]+) of them mergeable; light subpaths and grid ([0-9.]+) MB", by["vcm"]["stats"])
    check(vcm and shown and vcm.groups()[:4] == shown.groups()[:4] and float(shown.group(5)) > 0, "vcm's panel: ./bdpt's radius and light vertices per pixel, and its memory",
          "./bdpt %s; page %s" % (vcm and vcm.group(0), shown and shown.group(0)))
    mlt = re.search(r"mlt: accepted bidirectional ([0-9.]+)% of (\d+), lens ([0-9.]+)% of (\d+), caustic ([0-9.]+)% of (\d+), multi-chain ([0-9.]+)% of (\d+)", lines["mlt"])
    page = re.search(r"mlt: accepted bidirectional ([0-9.]+)% of (\d+), lens ([0-9.]+)% of (\d+), caustic ([0-9.]+)% of (\d+), multi-chain ([0-9.]+)% of (\d+)", by["mlt"]["stats"])
    # a chain may take another turn in the last bits of cosf (see close()): acceptances within 1 point
    check(mlt and page and all(abs(float(a) - float(b)) <= 1 for a, b in zip(mlt.groups()[::2], page.groups()[::2])),
          "mlt's panel: the acceptance per mutation as ./bdpt prints it", "./bdpt %s; page %s" % (mlt and mlt.group(0), page and page.group(0)))
    clamp = re.search(r"clamp 1e-05 removed ([0-9.]+)% of the energy", lines["ir --clamp 1e-5"])
    page = re.search(r"clamp 1e-05 removed ([0-9.]+)% of the energy", by["ir --clamp 1e-5"]["stats"])
    check(clamp and page and abs(float(clamp.group(1)) - float(page.group(1))) < 0.01, "ir --clamp's panel: the share of energy the clamp removed, ./bdpt's",
          "./bdpt %s; page %s" % (clamp and clamp.group(0), page and page.group(0)))
    # Each method's description is bdpt.cpp's kMethodCaptions row (the one table --help and the
    # side-by-side figures read too): its caption and what it does.
    source = open(os.path.join(ROOT, "bdpt.cpp")).read()
    table = re.search(r"kMethodCaptions\[\] = \{(.*?)\n\};", source, re.S).group(1)
    rows = re.findall(r'\{"([^"]*)", "([^"]*)", "([^"]*)"\}', table)
    names = re.search(r"kMethodNames\[\] = \{([^}]*)\}", source).group(1).replace('"', "").replace(" ", "").split(",")
    panels = browser.run("scenes/cornell.scene", names[:6], 1) + browser.run("scenes/cornell.scene", names[6:], 1)
    wrong = [p["entry"] for p, (caption, what, _) in zip(panels, rows) if not p["what"].startswith(caption + ": " + what)]
    check(len(rows) == 9 and not wrong, "each method's panel says its row of bdpt.cpp's kMethodCaptions", ", ".join(wrong))
    # 6: nee --mis is described by the heuristic estimateDirect() multiplies by in bdpt.cpp.
    used = re.search(r"if \(mis && !lp\.deltaPosition\) contribution \*= (\w+)Heuristic\(", source).group(1)
    what = browser.run("scenes/cornell.scene", ["nee --mis"], 1)[0]["what"]
    check("%s heuristic" % used in what and "balance" not in what, "nee --mis: the page names the heuristic bdpt.cpp uses (%s)" % used, repr(what))


def lessons(browser):
    """web-student-7's defects 7, 8, 15: the lessons show their mistakes, the pyramid follows the
    clicked panel, the mistakes' notes fit the scene. A lesson's budget is a count here (the
    samples it makes in its seconds on a quiet machine), so that a busy machine gets the same images."""
    budgets = {"--symmetric-refraction": 64, "--no-adjoint-correction": 64, "--delta-density-one": 64, "--no-scramble": 16, "--fixed-ray-offset": 1024, "--fixed-start": 8}
    for flag, spp in budgets.items():
        i = browser.js("[...document.getElementById('preset').options].findIndex((o) => o.textContent.startsWith('deliberate mistake %s '))" % flag)
        browser.js("(() => { const s = document.getElementById('preset'); s.selectedIndex = %d; s.onchange(); })()" % i)
        page = browser.js("document.getElementById('notes-page').value")
        browser.js("bdptPage.setOptions({spp: %d, seconds: 0})" % spp)
        browser.js("bdptPage.run()")
        panels = browser.js("bdptPage.panels()")
        mistaken = [p for p in panels if flag in p["entry"]]
        right = {p["entry"]: p for p in panels if flag not in p["entry"]}
        verdicts, ratios = [], []
        for p in mistaken:
            plain = " ".join(w for w in p["entry"].split() if w != flag)
            ratio = re.search(r"ratio of means ([0-9.]+) against (.+?)(?: ·|$)", re.sub(r"<[^>]+>", "", p["stats"]))
            r = right.get(plain)
            # the ratio is the mistake's mean over the right method's, the panel it names
            ratios.append(bool(ratio and r and ratio.group(2).strip() == plain and abs(float(ratio.group(1)) / (p["mean"] / r["mean"]) - 1) < 2e-4))
            if r and r["rmse"] is not None and p["rmse"] is not None:
                verdicts.append(p["rmseWithoutLamp"] > r["rmseWithoutLamp"])  # against the reference: the mistake errs more
            elif ratio:
                verdicts.append(abs(float(ratio.group(1)) - 1) > 0.05)  # no reference: the means differ visibly
        linked = page.startswith({"--symmetric-refraction": "14", "--no-adjoint-correction": "13", "--delta-density-one": "10m", "--no-scramble": "09",
                                  "--fixed-ray-offset": "06", "--fixed-start": "16"}[flag])
        check(verdicts and all(verdicts) and ratios and all(ratios) and linked,
              "the lesson %s: the mistake's error above the right method's (or its mean visibly off), the ratio of means shown (the mistake's mean over the right one's), its notes page open" % flag,
              "page %s; %s" % (page, "; ".join("%s: RMSE %s, %s" % (p["entry"], p["rmseWithoutLamp"], re.sub(r"<[^>]+>", "", p["stats"])[:160]) for p in panels)))
        if flag == "--delta-density-one":  # 7: the pyramid shows the first such panel, then the clicked one
            first = browser.js("bdptPage.pyramidSums().entry")
            browser.js("bdptPage.clickPixel(1, 60, 100)")
            clicked = browser.js("bdptPage.pyramidSums().entry")
            check(first == "bdpt" and clicked == "bdpt --delta-density-one", "the pyramid shows the first bdpt panel, then the panel clicked",
                  "first %r, after a click on the second %r" % (first, clicked))
    # 15: a mistake's note speaks of the scene it is on: the bumped floor only on shading-normals.
    notes_on = {}
    for scene in ("scenes/shading-normals.scene", "scenes/energy-generator.scene"):
        notes_on[scene] = " ".join(browser.run(scene, ["lt --no-adjoint-correction", "pt --no-adjoint-correction"], 1)[0]["notes"])
    pt_note = " ".join(browser.js("bdptPage.panels()")[1]["notes"])
    check("bumped floor" in notes_on["scenes/shading-normals.scene"] and "bumped floor" not in notes_on["scenes/energy-generator.scene"] and "lt" not in pt_note.split(),
          "a mistake's note fits its scene and method (the bumped floor on shading-normals only; pt's note not lt's)", repr(notes_on) + " pt: " + repr(pt_note))


def notes_view(browser):
    """web-student-7's defects 1, 9, 10, 11, 14, 17, 18, and the code one click from the notes."""
    # 1: the notes stay beside the panels when the page scrolls to the pyramid and the path view.
    browser.js("bdptPage.openNotes('07-probabilities')")
    browser.run("scenes/cornell.scene", ["bdpt"], 2)
    for w, h in ((1366, 768), (1920, 1080)):
        browser.size(w, h)
        r = browser.js("new Promise((res) => { document.getElementById('pyramid-figure').scrollIntoView(); requestAnimationFrame(() => requestAnimationFrame(() => "
                       "res([scrollY, document.getElementById('notes-view').getBoundingClientRect().top, document.getElementById('notes-view').getBoundingClientRect().bottom, innerHeight]))); })")
        check(r[0] > 200 and abs(r[1]) <= 1 and r[2] >= r[3] - 1, "%dx%d: scrolled down to the pyramid, the notes stay on screen beside it" % (w, h),
              "scrolled %d px; the notes from %.0f to %.0f of %d" % tuple(r))
    browser.size(1920, 1080)
    browser.js("scrollTo(0, 0)")
    # 9: the answers folded; 10: a figure opens at its own size.
    folded = browser.js("BDPT_NOTES.filter((p) => /Answers? \\(for the instructor\\)/.test(p.html)).map((p) => { bdptPage.openNotes(p.file); "
                        "const d = document.querySelector('#notes-text details.answers'); return [p.file, !!d && !d.open, d ? d.nextElementSibling === null || true : false]; })")
    check(len(folded) >= 19 and all(f[1] for f in folded), "every page's answers folded (%d pages)" % len(folded), repr([f for f in folded if not f[1]][:3]))
    browser.js("bdptPage.openNotes('07-probabilities')")
    shown = browser.js("new Promise((res) => { const img = document.querySelector('#notes-text img'); const small = img.getBoundingClientRect().width; img.click(); "
                       "const big = document.querySelector('#figure-view img'); const done = () => res([small, big.getBoundingClientRect().width, big.naturalWidth, !document.getElementById('figure-view').hidden]); "
                       "big.complete ? done() : big.onload = done; })")
    browser.js("document.getElementById('figure-view').click()")
    check(shown[3] and shown[1] == shown[2] and shown[1] > shown[0], "a notes figure opens at its own size on a click", "shown %.0f px in the notes, %.0f px opened, its width %d" % tuple(shown[:3]))
    # 11: the notes' formulas in prose are TeX (KaTeX): at most 5 raw x_{...} or ^{...} left outside code.
    raw = browser.js("BDPT_NOTES.map((p) => { const d = document.createElement('div'); d.innerHTML = p.html; d.querySelectorAll('code, pre, .katex').forEach((e) => e.remove()); "
                     "return (d.textContent.match(/[_^]\\{/g) || []).length; }).reduce((a, b) => a + b, 0)")
    errors = browser.js("BDPT_NOTES.map((p) => (p.html.match(/katex-error/g) || []).length).reduce((a, b) => a + b, 0)")
    check(raw <= 5 and errors == 0, "the notes' formulas typeset: %d raw _{ or ^{ left in prose, %d KaTeX errors" % (raw, errors))
    # 18: a template command says it is one.
    browser.js("bdptPage.openNotes('appendix-a-speed-and-accuracy')")
    templates = [b for b in browser.js("bdptPage.notesButtons()") if "SCENE" in b["command"]]
    check(templates and all("template" in b["reason"] for b in templates), "Appendix A's template command: 'a template', not a refused option", repr(templates[:1]))
    # 14: on a phone, the chart's labels are legible and a tapped pixel says where its answer is.
    browser.size(390, 844)
    browser.run("scenes/cornell.scene", ["pt", "bdpt"], 2)
    label = browser.js("new Promise((res) => requestAnimationFrame(() => res(Math.min(...[...document.querySelectorAll('#chart text')].map((t) => t.getBoundingClientRect().height)))))")
    browser.js("scrollTo(0, 0)")
    browser.js("bdptPage.clickPixel(1, 30, 40)")
    hint = browser.js("(() => { const r = document.getElementById('tap-hint').getBoundingClientRect(); return !document.getElementById('tap-hint').hidden && r.top >= 0 && r.bottom <= innerHeight; })()")
    notes_link = browser.js("(() => { const r = document.getElementById('to-notes').getBoundingClientRect(); return r.height > 0 && r.bottom <= innerHeight; })()")
    check(label >= 9 and hint and notes_link, "390x844: chart labels %.1f px high, a tapped pixel's hint on screen, the notes one tap away" % label, "hint %s, notes link %s" % (hint, notes_link))
    browser.size(1920, 1080)
    # 17: page 1's equal-time claim rests on the rays per sample the panels show.
    text = open(os.path.join(ROOT, "lecture_notes", "01-path-sampling-techniques.md")).read().replace("\n", " ")
    # web-student-8's W2: a notes button records the pyramid only where its command has --strategies,
    # so the bdpt panel's rays are the command's, not one more for the record's (1,1) connections.
    quoted = re.search(r"pt's sample costs ([0-9.]+) rays and bdpt's ([0-9.]+)", text)
    panels, command = press_button(browser, "01-path-sampling-techniques", "--spp 40")
    rays = {p["entry"]: re.search(r"([0-9.]+) rays per sample", p["stats"]).group(1) for p in panels}
    printed = subprocess.run(shlex.split(command.replace("--out build/notes/", "--out build/test-web/")), cwd=ROOT, check=True, capture_output=True, text=True).stdout
    native_rays = dict(re.findall(r"\d\. (\w+): .*?([0-9.]+) rays per sample", printed))
    check("--strategies" not in command and quoted and list(quoted.groups()) == [rays["pt"], rays["bdpt"]] and [native_rays.get("pt"), native_rays.get("bdpt")] == [rays["pt"], rays["bdpt"]],
          "page 1's equal-time claim: the rays per sample it quotes, as ./bdpt's and the page's panels show them",
          "page %s; panels pt %s, bdpt %s; ./bdpt %s" % (quoted and quoted.groups(), rays.get("pt"), rays.get("bdpt"), native_rays))


def code_view(browser):
    """The code one click from the notes: every function the notes cite that the page carries is a
    link that opens its definition beside the notes; a panel's method opens its sample function."""
    cited, linked, missing = 0, 0, []
    for page in browser.js("BDPT_NOTES.map((p) => p.file)"):
        browser.js("bdptPage.openNotes(%s)" % json.dumps(page))
        names, links = browser.js("bdptPage.citedFunctions()"), browser.js("bdptPage.codeLinks()")
        cited, linked = cited + len(names), linked + len(links)
        missing += ["%s: %s()" % (page, n) for n in names if n not in links]
    check(cited >= 60 and not missing, "every function the notes cite opens the code view (%d citations)" % cited, ", ".join(missing[:8]))
    browser.js("bdptPage.openNotes('13-shading-normals')")
    shown = browser.js("bdptPage.clickCodeLink('evalBsdf')")
    source = open(os.path.join(ROOT, "bdpt.cpp")).read().split("\n")
    line = next(i + 1 for i, l in enumerate(source) if re.match(r"inline \w+ evalBsdf\(", l))
    check(shown and shown["firstLine"] == line and "evalBsdf(" in shown["first"] and shown["inView"] and shown["beside"],
          "page 13's evalBsdf(): the code view opens at bdpt.cpp:%d, on screen, beside the panels" % line, repr(shown))
    # The marked range is the definition, whole: from its first line to the brace that closes its
    # body, found here by counting the braces of bdpt.cpp's code (comments and strings aside).
    def body_end(first):
        depth, opened = 0, False
        for n in range(first - 1, len(source)):
            code = re.sub(r'"(\\.|[^"\\])*"|\'(\\.|[^\'\\])*\'', '""', source[n]).split("//")[0]
            depth += code.count("{") - code.count("}")
            opened = opened or "{" in code
            if opened and depth == 0:
                return n + 1
        return 0
    ranges = []
    for name in ("evalBsdf", "misWeight", "sampleVCM", "dot", "pixelImportance", "Rng::drawCoordinates", "connectSubpaths"):
        shown = browser.js("bdptPage.openCode(%s)" % json.dumps(name))
        first = shown and shown["firstLine"]
        ok = bool(shown) and shown["where"].endswith("bdpt.cpp, lines %d-%d" % (first, first + shown["lines"] - 1)) and first + shown["lines"] - 1 == body_end(first) \
             and shown["marked"] == source[first - 1:first - 1 + shown["lines"]]
        ranges.append((name, ok, shown and shown["where"], first and body_end(first)))
    check(all(ok for _, ok, _, _ in ranges), "the code view marks each definition whole, its first line to the brace that closes its body (7 functions, a one-line one among them)",
          "; ".join("%s: %s, the body ends at %s" % (n, w, e) for n, ok, w, e in ranges if not ok))
    browser.run("scenes/cornell.scene", ["vcm"], 1)
    shown = browser.js("bdptPage.clickPanelMethod(0)")
    check(shown and "sampleVCM(" in shown["first"] and shown["inView"], "a panel's method name opens its function (vcm: sampleVCM)", repr(shown))
    browser.js("document.getElementById('code-back').click()")


def path_view(browser):
    """One sample's paths, drawn: a clicked pixel of a bdpt panel on cornell draws the camera and light
    subpaths and the connections; each drawn path's weights sum to 1 in every heuristic; the renderer's
    w_{s,t} is the table's own row; for a path of k = 3 they are build/worked-path's, which works
    the densities out from their definitions for the path's points; and what is drawn is the pixel's
    own sample: the drawn connections' sum of C w (t >= 2) is the value the pixel got in that pass."""
    browser.run("scenes/cornell.scene", ["bdpt"], 1)
    checked, sums_ok, self_ok, worked_ok, details = 0, True, True, [], []
    own_sample, lit, own_details = [], 0, []
    for x, y in ((20, 44), (40, 50), (12, 30), (50, 20), (32, 58), (8, 52)):
        browser.js("bdptPage.clickPixel(0, %d, %d)" % (x, y))
        browser.wait_for("bdptPage.pathView() && bdptPage.pathView().x == %d && bdptPage.pathView().y == %d" % (x, y))
        v = browser.js("bdptPage.pathView()")
        lit += v["pixelValue"] > 0
        own_sample.append(abs(v["ownSum"] - v["pixelValue"]) <= 1e-5 * max(1e-6, v["pixelValue"]))
        own_details.append("pixel (%d,%d): value %.7g, drawn sum of C w %.7g" % (x, y, v["pixelValue"], v["ownSum"]))
        for i, c in enumerate(v["connections"]):
            v = browser.js("bdptPage.choosePath(%d)" % i)
            chosen = v["chosen"]
            sums_ok &= all(abs(s - 1) < 1e-4 for s in v["sums"][:3])
            own = next(st for st in chosen["strategies"] if st["s"] == chosen["s"] and not st["merge"])
            self_ok &= all(abs(a - b) < 1e-4 for a, b in zip(own["w"][:3], chosen["w"][:3]))
            checked += 1
            kinds = [p["kind"] for p in chosen["vertices"]]
            if len(kinds) == 4 and kinds[0] == "lamp" and all(k == "surface" for k in kinds[1:3]) and len(worked_ok) < 4:
                points = ["%.6f,%.6f,%.6f" % tuple(p["p"]) for p in chosen["vertices"][:3]]
                out = subprocess.run(["build/worked-path", "path", "scenes/cornell.scene", "64x64", *points], cwd=ROOT, capture_output=True, text=True)
                table = [l.strip("|").split("|") for l in out.stdout.split("\n") if re.match(r"\| \d", l)]
                rows = {int(r[0]): [float(r[4]), float(r[5]), float(r[6])] for r in table}
                p_worked = {int(r[0]): float(r[2]) for r in table}
                page = {st["s"]: st["w"][:3] for st in chosen["strategies"] if not st["merge"]}
                worst = max(abs(rows[s][h] - (page.get(s) or [0, 0, 0])[h]) for s in rows for h in range(3)) if rows else 1
                # the table as shown: each strategy's p and p / p_{s,t} (the chosen connection's), page 7's numbers
                shown = {int(re.match(r"s=(\d+)", cells[0]).group(1)): (float(cells[1]), float(cells[2])) for cells in v["table"] if cells[0].startswith("s=")}
                worst_p = max(max(abs(p / p_worked[s] - 1), abs(r / (p_worked[s] / p_worked[chosen["s"]]) - 1)) for s, (p, r) in shown.items()) if shown else 1
                worked_ok.append(worst < 2e-3 and worst_p < 2e-3 and len(shown) >= 3)
                details.append("pixel (%d,%d) s=%d t=%d: largest difference %.2g in the weights, %.2g in p and p / p_{s,t}" % (x, y, chosen["s"], chosen["t"], worst, worst_p))
    drawn = v["drawn"]
    check(checked >= 10 and sums_ok and self_ok and drawn["camera"] >= 2 and drawn["sideCamera"] >= 2 and drawn["lines"] >= 2,
          "the path view: %d connections drawn at 6 pixels, each path's weights sum to 1 in the balance, power and max heuristics, "
          "the renderer's w_{s,t} its own row" % checked, "sums %s, own rows %s, drawn %r" % (sums_ok, self_ok, drawn))
    check(len(worked_ok) >= 2 and all(worked_ok), "the path view's densities, ratios and weights of %d paths of length 3, as shown: build/worked-path's from the densities' definitions" % len(worked_ok),
          "; ".join(details))
    check(lit >= 4 and all(own_sample), "the path view draws the pixel's own sample: at %d lit pixels of 6 the drawn connections' sum of C w is the pixel's value in that pass" % lit,
          "; ".join(own_details))

    # web-student-8's W8: each connection says where its light goes: t >= 2 this pixel, t = 1 the
    # pixel its splat lands on (the renderer's own pixel index).
    lands, splats = [], 0
    for x, y in ((40, 52), (12, 30)):
        browser.js("bdptPage.clickPixel(0, %d, %d)" % (x, y))
        browser.wait_for("bdptPage.pathView() && bdptPage.pathView().x == %d && bdptPage.pathView().y == %d" % (x, y))
        v = browser.js("bdptPage.pathView()")
        for c, shown in zip(v["connections"], v["landsOn"]):
            want = "this pixel" if c["t"] >= 2 else "pixel (%d, %d)" % (c["pixel"] % v["width"], c["pixel"] // v["width"])
            lands.append(shown == want)
            splats += c["t"] == 1
    check(len(lands) >= 4 and all(lands) and splats >= 1, "the path view says where each connection's light goes (%d rows, %d of them t = 1 splats)" % (len(lands), splats))
    # W7: a path of one segment (the lamp seen) says why (1,1) weighs 0 whatever the densities.
    direct = None
    for y in range(1, 16):
        browser.js("bdptPage.clickPixel(0, 32, %d)" % y)
        browser.wait_for("bdptPage.pathView() && bdptPage.pathView().y == %d" % y)
        v = browser.js("bdptPage.pathView()")
        i = next((i for i, c in enumerate(v["connections"]) if c["s"] + c["t"] == 2), None)
        if i is not None:
            direct = browser.js("bdptPage.choosePath(%d)" % i)
            break
    check(direct and direct["directRule"], "the path view of the lamp seen directly (k = 1) says the renderer gives it to s = 0 alone", repr(direct and direct["chosen"]))
    # vcm's merges drawn: a dashed circle of the radius at each merge of the chosen path.
    browser.run("scenes/cornell.scene", ["vcm"], 1)
    merges = []
    for x, y in ((20, 44), (40, 50), (12, 30)):
        browser.js("bdptPage.clickPixel(0, %d, %d)" % (x, y))
        browser.wait_for("bdptPage.pathView() && bdptPage.pathView().x == %d && bdptPage.pathView().y == %d" % (x, y))
        v = browser.js("bdptPage.pathView()")
        for i in range(len(v["connections"])):
            v = browser.js("bdptPage.choosePath(%d)" % i)
            merges.append((sum(1 for st in v["chosen"]["strategies"] if st["merge"]), v["drawn"]["merges"]))
    check(any(m > 0 for m, _ in merges) and all(m == d for m, d in merges),
          "vcm's path view draws each merge of the chosen path (%d paths, %d merges)" % (len(merges), sum(m for m, _ in merges)), repr(merges[:6]))


def speed(browser):
    # make bench-web: one bdpt panel's samples per CPU second of the whole browser (its worker,
    # the page that draws, the compositor), against ./bdpt --threads 1's per CPU second, with the
    # strategies recorded on both sides as the page records them, and without; three rounds,
    # interleaved, the median printed. A benchmark's number: printed, never checked.
    for strategies in (True, False):
        ratios = []
        for _ in range(3):
            browser.js("bdptPage.setOptions({strategies: %s})" % ("true" if strategies else "false"))
            cpu0 = process_cpu_seconds(browser.proc.pid)
            panels = browser.run("scenes/cornell.scene", ["bdpt"], 0, seconds=4)
            page_cpu = process_cpu_seconds(browser.proc.pid) - cpu0
            extra = ("--strategies", os.path.join(OUT, "speed"), "--strategy-length", "4") if strategies else ()
            out = os.path.join(OUT, "speed.png")
            printed = subprocess.run(["./bdpt", "scenes/cornell.scene", "--method", "bdpt", "--res", "64x64", "--threads", "1", "--time", "4", "--out", out, *extra],
                                     cwd=ROOT, check=True, capture_output=True, text=True).stdout
            spp, cpu = re.search(r"(\d+) samples per pixel in [0-9.]+ s \(([0-9.]+) CPU s\)", printed).groups()
            ratios.append((panels[0]["passes"] / page_cpu) / (int(spp) / float(cpu)))
        ratios.sort()
        print("one bdpt panel%s, cornell 64x64: samples per CPU second of the whole browser / ./bdpt --threads 1's: median %.2fx (rounds: %s)"
              % (" recording its strategies" if strategies else "", ratios[1], ", ".join("%.2f" % r for r in ratios)), flush=True)
    browser.js("bdptPage.setOptions({strategies: true})")


if __name__ == "__main__":
    sys.exit(main(bench="--bench" in sys.argv[1:]))
