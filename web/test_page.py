#!/usr/bin/env python3
"""The web build in headless Chromium, driven through chromedriver (WebDriver, standard library
only). Serves the built folder on 127.0.0.1 and checks, from the page:

1. the app starts and draws its first frame (time to first frame reported, 20 s at most);
2. a screenshot of the canvas shows the default robot: the 3D view's pixels match the native
   golden tests/snapshots/app_default_robot.png (rendered by lavapipe; here WebGL2 on
   SwiftShader) within a stated tolerance, and the arm's link colour is there;
3. a scripted mouse drag on the IK target's gizmo changes the pose readout;
4. W computes the workspace in slices while the page keeps drawing: dots and the 2D figure;
5. the Screenshot button saves the window as a PNG download; a model file dropped on the page
   opens;
6. the Puma (``?model=puma560&q=...``, a generic pose) shows 8 solutions; a lesson opens; the
   two-link arm's workspace (time to the figure reported);
7. no console errors, no panic;
8. the graphics path: WebGL2 in this Chromium (it has no WebGPU adapter), then WebGPU in a second
   Chromium given SwiftShader's WebGPU adapter (WEBGPU_ARGS): the default robot against the same
   golden, and its workspace figure.

Usage: web/test_page.py DIST_DIR. Fails (never skips) when Chromium or chromedriver is missing.
"""

import base64
import functools
import http.server
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WIDTH, HEIGHT = 1280, 800


def fail(msg):
    print(f"web test FAILED: {msg}", file=sys.stderr)
    sys.exit(1)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# --- a PNG decoder (8-bit RGB/RGBA, non-interlaced: what Chromium and armlab write) -----------

def decode_png(data):
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width = 8, b"", None
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and color in (2, 6) and interlace == 0, (depth, color, interlace)
            bpp = 4 if color == 6 else 3
        elif kind == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, bpp, rows


def pixel(img, x, y):
    _, _, bpp, rows = img
    return rows[y][x * bpp:x * bpp + 3]


# --- WebDriver ----------------------------------------------------------------------------

# Chromium's WebGPU on SwiftShader's Vulkan: a WebGPU adapter without a GPU (headless Chromium
# has none otherwise, and the app then draws with WebGL2).
WEBGPU_ARGS = ["--enable-unsafe-webgpu", "--enable-features=Vulkan", "--use-vulkan=swiftshader",
               "--use-webgpu-adapter=swiftshader"]


class Driver:
    def __init__(self, chromedriver, chromium, extra=()):
        self.port = free_port()
        self.log = tempfile.NamedTemporaryFile(prefix="chromedriver-", suffix=".log", delete=False)
        self.proc = subprocess.Popen(
            [chromedriver, f"--port={self.port}"], stdout=self.log, stderr=subprocess.STDOUT)
        self.base = f"http://127.0.0.1:{self.port}"
        deadline = time.time() + 20
        while True:
            try:
                self.call("GET", "/status")
                break
            except (urllib.error.URLError, ConnectionError):
                if time.time() > deadline:
                    fail("chromedriver did not start")
                time.sleep(0.1)
        self.profile = tempfile.mkdtemp(prefix="armlab-chromium-")
        args = [
            "--headless=new", "--no-sandbox", "--disable-gpu-sandbox", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            "--disable-quic", "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
            f"--window-size={WIDTH},{HEIGHT}", "--force-device-scale-factor=1",
            f"--user-data-dir={self.profile}",
            *extra,
            *os.environ.get("ARMLAB_CHROMIUM_ARGS", "").split(),
        ]
        caps = {"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {"binary": chromium, "args": args},
            "goog:loggingPrefs": {"browser": "ALL"},
        }}}
        self.sid = self.call("POST", "/session", caps)["sessionId"]
        # The page exactly WIDTH x HEIGHT CSS pixels at one device pixel each (the window's size
        # includes the browser's own bars).
        self.call("POST", f"/session/{self.sid}/goog/cdp/execute", {
            "cmd": "Emulation.setDeviceMetricsOverride",
            "params": {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1, "mobile": False},
        })
        # Every console error and uncaught exception is kept on the page, from the first script on.
        self.call("POST", f"/session/{self.sid}/goog/cdp/execute", {
            "cmd": "Page.addScriptToEvaluateOnNewDocument",
            "params": {"source": """
                window.__errors = [];
                const e = console.error.bind(console);
                console.error = (...a) => { window.__errors.push(a.map(String).join(' ')); e(...a); };
                addEventListener('error', ev => window.__errors.push('error: ' + ev.message));
                addEventListener('unhandledrejection', ev => window.__errors.push('rejection: ' + ev.reason));
            """},
        })

    def call(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=120) as r:
                return json.loads(r.read())["value"]
        except urllib.error.HTTPError as e:
            fail(f"WebDriver {method} {path}: {e.read().decode(errors='replace')[:500]}")

    def s(self, path, body=None, method="POST"):
        return self.call(method, f"/session/{self.sid}{path}", body)

    def js(self, script, *args):
        return self.s("/execute/sync", {"script": script, "args": list(args)})

    def screenshot(self):
        return decode_png(base64.b64decode(self.s("/screenshot", method="GET")))

    def browser_log(self):
        try:
            return self.s("/se/log", {"type": "browser"}) or []
        except SystemExit:
            raise
        except Exception:  # noqa: BLE001 (older drivers have no log endpoint)
            return []

    def quit(self):
        try:
            self.call("DELETE", f"/session/{self.sid}")
        finally:
            self.proc.terminate()
            shutil.rmtree(self.profile, ignore_errors=True)


def status(d):
    text = d.js("return window.armlab ? window.armlab.status() : null")
    return json.loads(text) if text else None


def wait_for(d, what, cond, timeout):
    deadline = time.time() + timeout
    while True:
        st = status(d)
        if st and st.get("panicked"):
            fail(f"the app panicked: {d.js('return window.armlab.panic_message()')}")
        if st and cond(st):
            return st
        if time.time() > deadline:
            errors = d.js("return window.__errors || []")
            fail(f"{what}: not within {timeout} s; last status {st}; page errors {errors}")
        time.sleep(0.05)


def open_page(d, url, timeout=20.0):
    """Loads `url` and waits for the first frame; returns (status, ms from navigation start)."""
    d.s("/url", {"url": url})
    st = wait_for(d, "the app's first frame", lambda s: s.get("frames", 0) >= 1, timeout)
    return st, d.js("return performance.now()")


# --- the checks -------------------------------------------------------------------------------

def check_default_robot(d):
    img = d.screenshot()
    w, h, _, _ = img
    if (w, h) != (WIDTH, HEIGHT):
        fail(f"screenshot is {w}x{h}, expected {WIDTH}x{HEIGHT}")
    with open(os.path.join(ROOT, "tests/snapshots/app_default_robot.png"), "rb") as f:
        golden = decode_png(f.read())
    # The 3D view (left and right panels hold text, whose hinting differs between renderers).
    x0, x1, y0, y1 = 330, 940, 60, 740
    diff, link, n = 0, 0, 0
    for y in range(y0, y1, 2):
        for x in range(x0, x1, 2):
            a, b = pixel(img, x, y), pixel(golden, x, y)
            n += 1
            if max(abs(a[i] - b[i]) for i in range(3)) > 48:
                diff += 1
            r, g, bl = a
            if abs(r - g) > 40 or abs(g - bl) > 40:  # coloured (links, frames), not grey
                link += 1
    share = diff / n
    print(f"  canvas vs native golden (3D view): {share:.2%} of pixels differ by more than 48/255")
    if share > 0.03:
        path = os.path.join(tempfile.gettempdir(), "armlab-web-default.png")
        with open(path, "wb") as f:
            f.write(base64.b64decode(d.s("/screenshot", method="GET")))
        fail(f"the canvas does not show the default robot like the native golden ({share:.2%} "
             f"of pixels differ, tolerance 3 %); screenshot in {path}")
    if link < 500:
        fail(f"only {link} coloured pixels in the 3D view: no arm drawn")


def drag_from(d, x, y):
    """A scripted mouse drag from (x, y) px: press, ten moves of (-6, +4) px 30 ms apart, release."""
    steps = [{"type": "pointerMove", "x": int(x), "y": int(y), "origin": "viewport",
              "duration": 0}, {"type": "pointerDown", "button": 0}]
    for k in range(1, 11):
        steps.append({"type": "pointerMove", "x": int(x - 6 * k), "y": int(y + 4 * k),
                      "origin": "viewport", "duration": 30})
    steps.append({"type": "pointerUp", "button": 0})
    d.s("/actions", {"actions": [{"type": "pointer", "id": "mouse",
                                  "parameters": {"pointerType": "mouse"}, "actions": steps}]})
    d.s("/actions", method="DELETE")


def check_gizmo_drag(d):
    before = wait_for(d, "the gizmo's position", lambda s: s.get("gizmo"), 10)
    x, y = before["gizmo"]
    drag_from(d, x, y)
    after = wait_for(d, "the pose readout to change after the drag",
                     lambda s: s["position"] != before["position"], 10)
    moved = sum((a - b) ** 2 for a, b in zip(after["position"], before["position"])) ** 0.5
    print(f"  gizmo drag from ({x:.0f}, {y:.0f}) px: the tool moved {moved * 1000:.1f} mm")
    if moved < 1e-3:
        fail(f"the drag moved the tool only {moved} m")


def keep(d, name):
    """Saves the page's screenshot under the temporary folder (to look at after a run)."""
    with open(os.path.join(tempfile.gettempdir(), name), "wb") as f:
        f.write(base64.b64decode(d.s("/screenshot", method="GET")))


def press(d, key):
    d.js("document.getElementById('armlab_canvas').focus()")
    d.s("/actions", {"actions": [{"type": "key", "id": "keyboard", "actions": [
        {"type": "keyDown", "value": key}, {"type": "keyUp", "value": key}]}]})
    d.s("/actions", method="DELETE")


def click(d, x, y):
    d.s("/actions", {"actions": [{"type": "pointer", "id": "mouse",
                                  "parameters": {"pointerType": "mouse"}, "actions": [
                                      {"type": "pointerMove", "x": x, "y": y, "origin": "viewport",
                                       "duration": 0},
                                      {"type": "pointerDown", "button": 0},
                                      {"type": "pointerUp", "button": 0}]}]})
    d.s("/actions", method="DELETE")


def check_workspace(d, forms=True, workers=None):
    """W computes the workspace in slices across frames (no threads in a browser), its figure on
    the pool of web workers (one per core but the page's, or `workers` from the URL): the page
    keeps drawing meanwhile, the figure shows as it forms (`forms`: at least the coarse first
    look), and the overlay's dots and the 2D figure arrive."""
    press(d, "w")
    t0, frames0, worst, last = time.time(), status(d)["frames"], 0.0, time.time()
    while True:
        st = status(d)
        now = time.time()
        worst, last = max(worst, now - last), now
        if st.get("workspace_error"):
            fail(f"workspace: {st['workspace_error']}")
        if st.get("workspace_progress") == 1.0:
            break
        if now - t0 > 120:
            fail(f"the workspace did not finish in 120 s: {st}")
        time.sleep(0.05)
    frames = st["frames"] - frames0
    print(f"  workspace (W): {now - t0:.1f} s, {frames} frames meanwhile, longest wait for the "
          f"page {worst * 1000:.0f} ms; {st['workspace_dots']} dots, figure {st['workspace_figure']}"
          f", {st['workspace_previews']} pictures while it formed, {st['workers']} web workers")
    cores = d.js("return navigator.hardwareConcurrency || 1")
    wanted = workers or max(1, min(cores - 1, 8))
    if st["workers"] != wanted:
        fail(f"{st['workers']} web workers for {cores} cores (wanted {wanted})")
    if forms and not st["workspace_previews"]:
        fail("the figure did not show as it formed (no coarse look)")
    if not st["workspace_dots"] or not st["workspace_figure"]:
        fail(f"the workspace has no dots or no figure: {st}")
    if frames < 2 or worst > 1.0:
        fail(f"{frames} frames while the workspace was computed, the page waited up to "
             f"{worst:.1f} s: the page froze")
    # The Workspace tab shows the figure (the toolbar's one row: "Workspace" at x 159-241).
    click(d, 200, 20)
    time.sleep(1.0)
    if status(d).get("tab") != 1:
        fail(f"the click on the Workspace tab did not show it (tab {status(d).get('tab')})")
    img = d.screenshot()
    keep(d, "armlab-web-workspace-tab.png")
    colours = {pixel(img, x, y) for x in range(450, 900, 6) for y in range(100, 700, 6)}
    print(f"  workspace tab: {len(colours)} colours in the figure's area")
    if len(colours) < 30:
        fail("the Workspace (2D) tab shows no figure")
    click(d, 120, 20)
    time.sleep(0.5)
    if status(d).get("tab") != 0:
        fail("the click on the 3D view tab did not show it")
    press(d, "w")


def check_drop(d):
    """A model file dropped onto the page opens (the browser reads it asynchronously)."""
    with open(os.path.join(ROOT, "assets/robots/planar3.toml")) as f:
        text = f.read()
    d.js("""
        const dt = new DataTransfer();
        dt.items.add(new File([arguments[0]], "planar3.toml", {type: "application/toml"}));
        const c = document.getElementById('armlab_canvas');
        for (const kind of ['dragenter', 'dragover', 'drop']) {
            c.dispatchEvent(new DragEvent(kind, {dataTransfer: dt, bubbles: true, cancelable: true}));
        }
    """, text)
    st = wait_for(d, "the dropped planar3.toml to open", lambda s: s["dof"] == 3, 10)
    print(f"  dropped planar3.toml: {st['model']} ({st['dof']} DOF)")


def check_screenshot_download(d, folder):
    """The Screenshot button (top bar) saves the window as a PNG download."""
    d.call("POST", f"/session/{d.sid}/goog/cdp/execute", {
        "cmd": "Browser.setDownloadBehavior",
        "params": {"behavior": "allow", "downloadPath": folder},
    })
    click(d, 999, 20)  # "Screenshot", in the toolbar's one row (x 958-1040; six tabs fold the view presets, the Cell menu before it)
    deadline = time.time() + 30
    while True:
        done = [f for f in os.listdir(folder) if f.endswith(".png")]
        if done:
            break
        if time.time() > deadline:
            fail(f"no screenshot download in 30 s (status: {status(d)['messages'][-3:]})")
        time.sleep(0.1)
    time.sleep(0.3)
    with open(os.path.join(folder, done[0]), "rb") as f:
        data = f.read()
    with open(os.path.join(tempfile.gettempdir(), "armlab-web-download.png"), "wb") as f:
        f.write(data)
    img = decode_png(data)
    w, h, _, _ = img
    colours = {pixel(img, x, y) for x in range(0, w, 16) for y in range(0, h, 16)}
    print(f"  screenshot download: {done[0]} {w}x{h}, {len(colours)} colours")
    if (w, h) != (WIDTH, HEIGHT) or len(colours) < 20:
        fail(f"the screenshot is {w}x{h} with {len(colours)} colours")


def check_backend(st, want):
    if st.get("backend") != want:
        fail(f"the app draws with {st.get('backend')}, expected {want}")


def check_webgpu(chromedriver, chromium, url):
    """The WebGPU path, in a Chromium that has a WebGPU adapter (SwiftShader): the app picks
    WebGPU, draws the default robot like the native golden, and makes the workspace figure."""
    d = Driver(chromedriver, chromium, WEBGPU_ARGS)
    try:
        if not d.js("return !!navigator.gpu"):
            fail("this Chromium has no navigator.gpu even with " + " ".join(WEBGPU_ARGS))
        st, ms = open_page(d, url, timeout=60)
        check_backend(st, "BrowserWebGpu")
        print(f"  WebGPU (SwiftShader adapter): first frame {ms / 1000:.2f} s after navigation")
        time.sleep(0.5)
        check_default_robot(d)
        check_workspace(d)
        errors = d.js("return window.__errors || []")
        severe = [e for e in d.browser_log() if e.get("level") == "SEVERE"]
        if errors or severe:
            fail(f"WebGPU: console errors: {errors} {severe}")
    finally:
        d.quit()


def main():
    if len(sys.argv) != 2:
        fail("usage: web/test_page.py DIST_DIR")
    dist = sys.argv[1]
    for f in ("index.html", "armlab.js", "armlab_bg.wasm"):
        if not os.path.isfile(os.path.join(dist, f)):
            fail(f"{dist}/{f} is missing: run web/build.sh first")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    chromedriver = shutil.which("chromedriver")
    if not chromium or not chromedriver:
        fail("headless Chromium and chromedriver are needed: apt-get install chromium chromium-driver")

    port = free_port()
    handler = functools.partial(QuietHandler, directory=dist)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", port), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{port}/index.html"
    d = Driver(chromedriver, chromium)
    try:
        st, ms = open_page(d, url)
        print(f"  started {st['model']} ({st['dof']} DOF): first frame {ms / 1000:.2f} s after "
              f"navigation")
        if st["model"] != "anthropomorphic arm with spherical wrist" and st["dof"] != 6:
            fail(f"expected the default robot, got {st['model']}")
        # No WebGPU adapter in this Chromium: the WebGL2 fallback.
        check_backend(st, "Gl")
        time.sleep(0.5)  # a few frames: the camera framed, the 3D view at full quality
        check_default_robot(d)
        check_gizmo_drag(d)
        check_workspace(d)
        downloads = tempfile.mkdtemp(prefix="armlab-downloads-")
        check_screenshot_download(d, downloads)
        shutil.rmtree(downloads, ignore_errors=True)
        check_drop(d)
        st, ms = open_page(d, url + "?model=puma560&q=0.3,0.8,-1,0.4,0.6,0.2")
        st = wait_for(d, "the Puma's solutions", lambda s: s.get("solutions") == 8, 10)
        print(f"  ?model=puma560&q=...: {st['model']}, {st['solutions']} solutions "
              f"({st['within_limits']} within limits)")
        st, ms = open_page(d, url + "?lesson=lessons/anthropomorphic_postures.toml")
        st = wait_for(d, "the lesson to open", lambda s: (s.get("lesson") or {}).get("steps") == 4, 10)
        if st["dof"] != 3 or st["solutions"] != 4:
            fail(f"the lesson's first step: {st['model']} with {st['solutions']} solutions")
        press(d, "\ue00f")  # Page Down
        st = wait_for(d, "the lesson's next step", lambda s: s["lesson"]["step"] == 1, 10)
        print(f"  ?lesson=...: {st['lesson']['title']}, step {st['lesson']['step'] + 1} of "
              f"{st['lesson']['steps']}, {st['solutions']} solutions")
        # the orientation lab in the browser: its lesson opens the Orientation tab (index 5),
        # which draws the turned frame in its own 3D view
        st, ms = open_page(d, url + "?lesson=lessons/orientation_euler_gimbal_lock.toml")
        st = wait_for(d, "the orientation lesson", lambda s: s.get("tab") == 5, 10)
        time.sleep(1.0)
        img = d.screenshot()
        keep(d, "armlab-web-orientation-tab.png")
        colours = {pixel(img, x, y) for x in range(300, 640, 4) for y in range(120, 680, 4)}
        print(f"  ?lesson=orientation_euler_gimbal_lock.toml: tab {st['tab']}, "
              f"{len(colours)} colours in its 3D view")
        if len(colours) < 20:
            fail("the Orientation tab's 3D view shows no frame")
        st, ms = open_page(d, url + "?model=stanford&workers=2")
        print(f"  ?model=stanford&workers=2 (the approach scan, spread over two workers):")
        check_workspace(d, workers=2)
        st, ms = open_page(d, url + "?model=planar2")
        print(f"  ?model=planar2: first frame {ms / 1000:.2f} s after navigation")
        # Its exact figure is done in a fraction of a second, before the page looks for the
        # coarse look (a worker's latest message wins).
        check_workspace(d, forms=False)
        errors = d.js("return window.__errors || []")
        severe = [e for e in d.browser_log() if e.get("level") == "SEVERE"]
        if errors or severe:
            fail(f"console errors: {errors} {severe}")
        d.quit()
        d = None
        check_webgpu(chromedriver, chromium, url)
    finally:
        if d is not None:
            d.quit()
        server.shutdown()
    print("web test passed")


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".wasm": "application/wasm", ".js": "text/javascript"}

    def log_message(self, *args):
        pass


if __name__ == "__main__":
    main()
