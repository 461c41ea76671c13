#!/usr/bin/env python3
"""The viewer page (web/page/) in headless Chromium: how fast it orbits, how soon
it shows a picture, and how much it downloads.

What it measures, each in the page itself (performance.now()):

1. WebAssembly engine (target/web/viewer/, the Web Worker), the point-lit Cornell
   box at 256 x 256, one sample a pixel: for `none`, the five exact hard-shadow
   methods and `shadow-map`, the method is chosen (`lumiere.choose`), then the
   camera orbits through N frames (`lumiere.orbit`, yaw stepping 2 pi / N, each
   awaited before the next). Per frame: the time from asking to the frame put on
   the canvas, and the engine's own render time (the frame header's `times`).
   One unmeasured orbit with the first method goes before, so that the engine
   is warm (WebAssembly code tiers up as it runs).
2. Native engine (`lumiere view --no-open`, over the page's WebSocket) at
   512 x 512: the same loop for every method of the scene's first family, beside
   the retired X11 window's figures and `lumiere view --benchmark N`
   run now (same load), as ratios.
3. Time to first picture: from navigation start to `lumiere.ready` (the first
   frame drawn), cold (a fresh profile) and warm (loaded again), for the
   WebAssembly page, the native page and, given `--site DIR`, a gallery topic
   page of DIR whose viewer is in an iframe (each topic opens its own scene).
4. Download size: the WebAssembly module and its JS glue, raw and gzip -9.

Orbit frames are asked at quality `full` by default (the page's own
`lumiere.orbit`): the scene's supersample is 1, so that is the same work as
`preview`, and the engine records `times` for full frames only. `--quality
preview` sends `{type: 'set', orbit, quality: 'preview'}` through `lumiere.send`
instead (no engine time then).

The machine's load average is printed beside each figure: other work on the
cores disturbs them.

Run (needs /usr/bin/chromium, target/web/viewer from tools/build-web.sh and
target/release/lumiere):

    python3 bench/viewer_browser.py [--frames 36] [--site DIR] [--skip-native]
        [--skip-wasm] [--lumiere PATH] [--quality full|preview] [--json FILE]

Markdown tables go to stdout. Python 3 standard library only; every process it
starts (Chromium, `lumiere view`) is ended on exit, errors included.
"""

import argparse
import contextlib
import functools
import gzip
import http.server
import json
import os
import re
import select
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VIEWER_DIR = os.path.join(ROOT, "target", "web", "viewer")
CHROMIUM = "/usr/bin/chromium"

SCENE = "cornell-box-point"
EXACT = ["ray-cast", "scanline", "shadow-polygons", "shadow-volumes", "stencil-shadow-volumes"]
WASM_METHODS = ["none", *EXACT, "shadow-map"]
WASM_SIZE = 256
NATIVE_SIZE = 512
WARM_LOADS = 3
PAGE_SCRIPTS = ["viewer.js", "engines.js", "protocol.js", "worker.js"]


def log(message):
    print(message, file=sys.stderr, flush=True)


def load_average():
    return os.getloadavg()[0]


def uptime():
    return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()


# ---------------------------------------------------------------------------
# Processes: each in its own process group, ended by that group's id


def end_process(proc, grace=5.0):
    """SIGTERM to the process's group (Chromium's helpers with it), then SIGKILL."""
    if proc.poll() is not None:
        return
    for sig, wait in ((signal.SIGTERM, grace), (signal.SIGKILL, grace)):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, sig)
        try:
            proc.wait(wait)
            return
        except subprocess.TimeoutExpired:
            pass


# ---------------------------------------------------------------------------
# Chromium over the DevTools protocol (--remote-debugging-pipe: messages are
# JSON, NUL-terminated; Chromium reads fd 3 and writes fd 4)


class Chromium:
    def __init__(self, width=1024, height=768):
        self.profile = tempfile.mkdtemp(prefix="lumiere-bench-chromium-")
        to_chrome_r, self.to_chrome = os.pipe()
        self.from_chrome, from_chrome_w = os.pipe()

        def child():
            os.dup2(to_chrome_r, 3)
            os.dup2(from_chrome_w, 4)

        self.proc = subprocess.Popen(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
             "--disable-background-networking", "--disable-component-update",
             "--no-first-run", "--disable-sync", f"--user-data-dir={self.profile}",
             "--remote-debugging-pipe", f"--window-size={width},{height}", "about:blank"],
            pass_fds=(3, 4), preexec_fn=child, start_new_session=True,
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self.buffer = b""
        self.last_id = 0
        self.events = []
        self.problems = []  # console errors and exceptions, for a failure's message
        try:
            targets = self.call("Target.getTargets")["targetInfos"]
            page = next(t for t in targets if t["type"] == "page")
            self.session = self.call("Target.attachToTarget", targetId=page["targetId"],
                                     flatten=True)["sessionId"]
            for domain in ("Page.enable", "Runtime.enable"):
                self.call(domain, session=True)
        except BaseException:
            self.close()
            raise

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self.proc.poll() is None:
            with contextlib.suppress(Exception):
                self.call("Browser.close", timeout=5)
            with contextlib.suppress(subprocess.TimeoutExpired):
                self.proc.wait(5)
        end_process(self.proc)
        for fd in (self.to_chrome, self.from_chrome):
            with contextlib.suppress(OSError):
                os.close(fd)
        shutil.rmtree(self.profile, ignore_errors=True)

    def _receive(self, deadline):
        """The next message, or None at the deadline."""
        while b"\0" not in self.buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            if select.select([self.from_chrome], [], [], left)[0]:
                chunk = os.read(self.from_chrome, 1 << 20)
                if not chunk:
                    raise RuntimeError("Chromium closed its DevTools pipe")
                self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def _keep(self, event):
        params = event.get("params", {})
        if event.get("method") == "Runtime.exceptionThrown":
            details = params["exceptionDetails"]
            self.problems.append(details.get("exception", {}).get("description", details.get("text")))
        elif event.get("method") == "Runtime.consoleAPICalled" and params.get("type") == "error":
            self.problems.append(" ".join(str(a.get("value", a.get("description", ""))) for a in params["args"]))
        self.events.append(event)

    def call(self, method, session=False, timeout=30, **params):
        self.last_id += 1
        message = {"id": self.last_id, "method": method, "params": params}
        if session:
            message["sessionId"] = self.session
        os.write(self.to_chrome, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            reply = self._receive(deadline)
            if reply is None:
                raise TimeoutError(f"{method}: no answer in {timeout} s")
            if reply.get("id") == self.last_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self._keep(reply)

    def wait_event(self, method, timeout=60):
        """Waits for (and consumes) the next event named `method`."""
        deadline = time.monotonic() + timeout
        while True:
            for i, event in enumerate(self.events):
                if event.get("method") == method:
                    return self.events.pop(i)
            event = self._receive(deadline)
            if event is None:
                raise TimeoutError(f"no {method} in {timeout} s")
            self._keep(event)

    def goto(self, url, timeout=60):
        """Navigates and waits for the page's load event (its module scripts ran)."""
        self.events.clear()
        result = self.call("Page.navigate", session=True, url=url)
        if result.get("errorText"):
            raise RuntimeError(f"{url}: {result['errorText']}")
        self.wait_event("Page.loadEventFired", timeout)

    def evaluate(self, expression, timeout=120):
        """The value of `expression` (a promise is awaited), or a RuntimeError."""
        result = self.call("Runtime.evaluate", session=True, timeout=timeout,
                           expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in result:
            details = result["exceptionDetails"]
            text = details.get("exception", {}).get("description", details.get("text"))
            extra = "; page: " + " | ".join(self.problems[-5:]) if self.problems else ""
            raise RuntimeError(f"{text}{extra}")
        return result["result"].get("value")

    def on_new_document(self, source):
        self.call("Page.addScriptToEvaluateOnNewDocument", session=True, source=source)


# ---------------------------------------------------------------------------
# Servers


class QuietFiles(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".wasm": "application/wasm", ".js": "text/javascript"}

    def log_message(self, *args):
        pass


@contextlib.contextmanager
def static_server(directory):
    """`python3 -m http.server --bind 127.0.0.1` on `directory`, in a thread here."""
    handler = functools.partial(QuietFiles, directory=directory)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


@contextlib.contextmanager
def native_server(lumiere, size, timeout=60):
    """`lumiere view SCENE --no-open` at size x size; yields the page's URL."""
    errors = tempfile.TemporaryFile()
    proc = subprocess.Popen(
        [lumiere, "view", SCENE, "--no-open", "--width", str(size), "--height", str(size)],
        stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=errors,
        start_new_session=True)
    try:
        line = b""
        deadline = time.monotonic() + timeout
        while b"\n" not in line and time.monotonic() < deadline:
            if not select.select([proc.stdout], [], [], 0.5)[0]:
                if proc.poll() is not None:
                    break
                continue
            chunk = os.read(proc.stdout.fileno(), 4096)
            if not chunk:
                break
            line += chunk
        found = re.search(rb"(http://127\.0\.0\.1:\d+/\S*)", line)
        if not found:
            errors.seek(0)
            raise RuntimeError(f"lumiere view printed no address: {line!r} {errors.read(2000)!r}")
        yield found.group(1).decode()
    finally:
        end_process(proc)
        proc.stdout.close()
        errors.close()


# ---------------------------------------------------------------------------
# In the page

# Installed before any page's scripts (the iframes' too): when viewer.js sets
# window.lumiere, the moment its `ready` resolves (the first frame drawn) is kept
# as an absolute time, to be read back whenever.
READY_HOOK = """
(() => {
  let api;
  Object.defineProperty(window, 'lumiere', {
    configurable: true, enumerable: true,
    get() { return api; },
    set(value) {
      api = value;
      Promise.resolve(value && value.ready).then(
        () => { window.__lumiereReadyAt = performance.timeOrigin + performance.now(); },
        (e) => { window.__lumiereReadyError = String((e && e.message) || e); });
    },
  });
})();
"""

# The first frame, in this document or its first viewer iframe, in ms after this
# document's navigation start.
FIRST_PICTURE_JS = """
(async () => {
  const deadline = performance.now() + %(timeout_ms)d;
  const views = () => [window, ...[...document.querySelectorAll('iframe')].map((f) => f.contentWindow)];
  for (;;) {
    for (const w of views()) {
      if (w && w.__lumiereReadyError) throw new Error('lumiere.ready failed: ' + w.__lumiereReadyError);
      if (w && w.__lumiereReadyAt) {
        return {
          ready_ms: w.__lumiereReadyAt - performance.timeOrigin,
          in_iframe: w !== window,
          engine: w.lumiere.state().engine,
          frame: w.lumiere.state().frame,
        };
      }
    }
    if (performance.now() > deadline) throw new Error('no first picture in %(timeout_ms)d ms');
    await new Promise((r) => setTimeout(r, 5));
  }
})()
"""

# The scene's facts once the first frame is drawn.
SCENE_JS = """
(async () => {
  await window.lumiere.ready;
  const s = window.lumiere.state();
  return {
    engine: s.engine, width: s.scene.width, height: s.scene.height,
    supersample: s.scene.supersample, orbit: s.orbit,
    families: s.scene.families.map((f) => ({ name: f.name, options: f.options.map((o) => o.name) })),
  };
})()
"""

# One method: chosen, then N orbit frames each awaited; times from performance.now().
ORBIT_JS = """
(async () => {
  const L = window.lumiere, family = %(family)s, method = %(method)s, n = %(frames)d;
  const preview = %(preview)s;
  await L.ready;
  const { yaw, pitch, distance } = L.state().scene.orbit;
  let t = performance.now();
  const chosen = await L.choose(family, method);
  const first_ms = performance.now() - t;
  const frame_ms = [], engine_ms = [];
  const start = performance.now();
  for (let k = 1; k <= n; k++) {
    const orbit = { yaw: yaw + 2 * Math.PI * k / n, pitch, distance };
    t = performance.now();
    let header;
    if (preview) {
      const replies = await L.send({ type: 'set', orbit, quality: 'preview' });
      const last = replies[replies.length - 1];
      if (!last || !last.header || last.header.type !== 'frame') {
        throw new Error('set: ' + (last ? last.message || JSON.stringify(last) : 'no reply'));
      }
      header = last.header;
    } else {
      header = (await L.orbit(orbit.yaw, orbit.pitch, orbit.distance)).header;
    }
    frame_ms.push(performance.now() - t);
    engine_ms.push(preview ? null : header.times[method] ?? null);
    if (header.method !== method) throw new Error(`asked for ${method}, the frame shows ${header.method}`);
  }
  const total_ms = performance.now() - start;
  if (preview) await L.send({ type: 'set', quality: 'full' });
  return {
    method, first_ms, first_engine_ms: chosen.header.times[method] ?? null,
    frame_ms, engine_ms, total_ms,
    width: chosen.header.width, height: chosen.header.height, quality: preview ? 'preview' : 'full',
  };
})()
"""


def js(value):
    return json.dumps(value)


def open_viewer(browser, url):
    """Opens the page and waits for its first frame; the scene's facts."""
    browser.goto(url)
    return browser.evaluate(SCENE_JS, timeout=180)


def orbit_method(browser, family, method, frames, quality):
    load_before = load_average()
    result = browser.evaluate(ORBIT_JS % {
        "family": js(family), "method": js(method), "frames": frames,
        "preview": js(quality == "preview")}, timeout=600)
    result["load"] = [load_before, load_average()]
    return summarise(result)


def summarise(result):
    frames = result["frame_ms"]
    engine = [t for t in result["engine_ms"] if t is not None]
    median = statistics.median(frames)
    result["median_ms"] = median
    result["fps_median"] = 1000.0 / median
    result["fps_total"] = 1000.0 * len(frames) / result["total_ms"]
    result["engine_median_ms"] = statistics.median(engine) if engine else None
    return result


def orbit_all(browser, url, methods, frames, quality):
    """The scene's facts and one result per method (those it does not offer skipped)."""
    scene = open_viewer(browser, url)
    family = scene["families"][0]
    if methods is None:
        methods = family["options"]
    # The WebAssembly engine's code tiers up while it runs hot: a first, unmeasured
    # orbit keeps that out of the first method's figures.
    warm_up = next((m for m in methods if m in family["options"]), None)
    if warm_up:
        orbit_method(browser, family["name"], warm_up, frames, quality)
    rows = []
    for method in methods:
        if method not in family["options"]:
            log(f"  {method}: not offered by the scene ({', '.join(family['options'])}), skipped")
            continue
        row = orbit_method(browser, family["name"], method, frames, quality)
        log(f"  {method}: median {row['median_ms']:.1f} ms, load {row['load'][1]:.2f}")
        rows.append(row)
    return scene, rows


def first_picture(url, loads=1 + WARM_LOADS):
    """Navigation start to lumiere.ready: one cold load (fresh profile), then warm ones."""
    results = []
    with Chromium() as browser:
        browser.on_new_document(READY_HOOK)
        for _ in range(loads):
            load_before = load_average()
            browser.goto(url)
            result = browser.evaluate(FIRST_PICTURE_JS % {"timeout_ms": 120000}, timeout=180)
            result["load"] = [load_before, load_average()]
            results.append(result)
    return {"url": url, "cold_ms": results[0]["ready_ms"],
            "warm_ms": statistics.median(r["ready_ms"] for r in results[1:]) if loads > 1 else None,
            "loads": results}


# ---------------------------------------------------------------------------
# Beside the page: the documented figures, the command line's benchmark, sizes


# The retired X11 window's frames per second on the point-lit box at 512 x 512
# (`lumiere view ID --width 512 --height 512 --benchmark 36`, 2 cores), as
# docs/viewer.md gave them before the window made way for the page.
X11_WINDOW_FPS = {
    "none": 56, "ray-cast": 47, "scanline": 56, "shadow-polygons": 46,
    "shadow-volumes": 52, "stencil-shadow-volumes": 48, "shadow-map": 53,
    "umbra-penumbra": 64, "soft-shadow-volumes": 66,
}


def documented_fps():
    """({method: frames/s}, where from): the X11 window's figures."""
    return dict(X11_WINDOW_FPS), "the X11 window (docs/viewer.md before the page)"


def cli_benchmark(lumiere, size, frames):
    """`lumiere view --benchmark N` now: {method: {median_ms, fps}}."""
    load_before = load_average()
    out = subprocess.run(
        [lumiere, "view", SCENE, "--width", str(size), "--height", str(size), "--benchmark", str(frames)],
        capture_output=True, text=True, timeout=1800, check=True, start_new_session=True).stdout
    figures = {}
    for line in out.splitlines():
        m = re.match(r"\|\s*(\S+)\s*\|\s*([\d.]+) ms\s*\|\s*([\d.]+) ms\s*\|\s*(\d+)\s*\|", line)
        if m:
            figures[m.group(1)] = {"first_ms": float(m.group(2)), "median_ms": float(m.group(3)),
                                   "fps": float(m.group(4))}
    return {"figures": figures, "load": [load_before, load_average()], "output": out}


def sizes():
    def measure(names):
        raw = b"".join(open(os.path.join(VIEWER_DIR, n), "rb").read() for n in names)
        return {"raw": len(raw), "gzip9": len(gzip.compress(raw, compresslevel=9, mtime=0))}

    files = {"pkg/lumiere_web_bg.wasm": ["pkg/lumiere_web_bg.wasm"],
             "pkg/lumiere_web.js (glue)": ["pkg/lumiere_web.js"],
             "page scripts (" + ", ".join(PAGE_SCRIPTS) + ")": PAGE_SCRIPTS}
    return {label: measure(names) for label, names in files.items()}


# ---------------------------------------------------------------------------
# Tables


def ms(value):
    return "–" if value is None else f"{value:.1f}"


def ratio(a, b):
    return "–" if not a or not b else f"{a / b:.2f}"


def load_cell(load):
    return f"{load[0]:.2f} → {load[1]:.2f}"


def orbit_table(rows, documented=None, cli=None):
    head = ["method", "first frame (choose) ms", "median frame ms", "frames/s (1/median)",
            "frames/s (N/total)", "engine render median ms", "frame − engine (page, transfer) ms"]
    if documented is not None:
        head += ["docs/viewer.md frames/s", "page / docs"]
    if cli is not None:
        head += ["`--benchmark` now frames/s", "page / `--benchmark`"]
    head.append("load (1 min) before → after")
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        engine = r["engine_median_ms"]
        cells = [r["method"], ms(r["first_ms"]), ms(r["median_ms"]), f"{r['fps_median']:.0f}",
                 f"{r['fps_total']:.0f}", ms(engine),
                 ms(r["median_ms"] - engine) if engine is not None else "–"]
        if documented is not None:
            doc = documented.get(r["method"])
            cells += ["–" if doc is None else f"{doc:.0f}", ratio(r["fps_median"], doc)]
        if cli is not None:
            now = cli["figures"].get(r["method"], {}).get("fps")
            cells += ["–" if now is None else f"{now:.0f}", ratio(r["fps_median"], now)]
        cells.append(load_cell(r["load"]))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def first_picture_table(results):
    if not any(results.values()):
        return "Nothing was timed."
    lines = ["| page | cold ms (fresh profile) | warm ms (median of %d) | viewer in | load (1 min) |" % WARM_LOADS,
             "|---|---|---|---|---|"]
    for label, r in results.items():
        if r is None:
            continue
        first = r["loads"][0]
        where = f"{'iframe' if first['in_iframe'] else 'the page'}, {first['engine']}"
        lines.append(f"| {label} | {ms(r['cold_ms'])} | {ms(r['warm_ms'])} | {where} | "
                     f"{load_cell([r['loads'][0]['load'][0], r['loads'][-1]['load'][1]])} |")
    return "\n".join(lines)


def size(n):
    return f"{n:,} B ({n / 2**20:.2f} MiB)" if n >= 2**20 else f"{n:,} B ({n / 2**10:.1f} KiB)"


def size_table(measured):
    lines = ["| file | raw | gzip -9 |", "|---|---|---|"]
    for label, m in measured.items():
        lines.append(f"| {label} | {size(m['raw'])} | {size(m['gzip9'])} |")
    return "\n".join(lines)


# ---------------------------------------------------------------------------


def run_wasm(args, report, out):
    query = f"scene={SCENE}&sets=camera.width%3D{WASM_SIZE},camera.height%3D{WASM_SIZE}"
    with static_server(VIEWER_DIR) as base:
        url = f"{base}/index.html?{query}"
        log(f"WebAssembly: {url}")
        with Chromium() as browser:
            scene, rows = orbit_all(browser, url, WASM_METHODS, args.frames, args.quality)
        report["wasm"] = {"url": url, "scene": scene, "rows": rows}
        report["first_picture"]["WebAssembly viewer page"] = first_picture(url)
    out(f"## WebAssembly engine (Web Worker), {SCENE} {scene['width']} × {scene['height']}, "
        f"supersample {scene['supersample']}, quality `{args.quality}`, {args.frames} orbit frames\n")
    out(orbit_table(rows) + "\n")


def run_native(args, report, out):
    with native_server(args.lumiere, NATIVE_SIZE) as url:
        log(f"native: {url}")
        with Chromium() as browser:
            scene, rows = orbit_all(browser, url, None, args.frames, args.quality)
        report["first_picture"]["native viewer page (`lumiere view`)"] = first_picture(url)
    log("native: lumiere view --benchmark")
    cli = cli_benchmark(args.lumiere, NATIVE_SIZE, args.frames)
    documented, source = documented_fps()
    report["native"] = {"url": url, "scene": scene, "rows": rows, "documented": documented,
                        "documented_source": source, "cli": cli}
    out(f"## Native engine (`lumiere view`, WebSocket), {SCENE} {scene['width']} × {scene['height']}, "
        f"supersample {scene['supersample']}, quality `{args.quality}`, {args.frames} orbit frames\n")
    out(orbit_table(rows, documented, cli) + "\n")
    out(f"`lumiere view --benchmark {args.frames}` ran after the page (load "
        f"{load_cell(cli['load'])}); the docs column is the first column (point-lit box, "
        f"512 × 512) of the table in {source}.\n")


def run_site(args, report):
    """Time to first picture on every topic page of the site that has a viewer."""
    pages = sorted(name for name in os.listdir(args.site)
                   if name.endswith(".html") and name != "index.html") if os.path.isdir(args.site) else []
    pages = [p for p in pages if "iframe" in open(os.path.join(args.site, p), encoding="utf-8").read()]
    if not pages:
        log(f"no topic page with a viewer in {args.site}: time to first picture skipped")
        report["first_picture"]["site"] = None
        return f"No gallery topic page with a viewer in {args.site}: its time to first picture was skipped.\n"
    with static_server(os.path.abspath(args.site)) as base:
        for page in pages:
            url = f"{base}/{page}"
            log(f"site: {url}")
            report["first_picture"][f"site {page}"] = first_picture(url)
    return ""


def stop_on_sigterm(signum, frame):
    raise SystemExit(128 + signum)  # unwinds: every server and browser is ended


def main():
    signal.signal(signal.SIGTERM, stop_on_sigterm)
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=36, help="orbit frames per method (default 36)")
    parser.add_argument("--site", help="a gallery site's folder (its topic pages embed the viewer)")
    parser.add_argument("--skip-native", action="store_true", help="no `lumiere view` figures")
    parser.add_argument("--skip-wasm", action="store_true", help="no WebAssembly figures")
    parser.add_argument("--lumiere", default=os.path.join(ROOT, "target", "release", "lumiere"),
                        help="the lumiere binary (default target/release/lumiere)")
    parser.add_argument("--quality", choices=["full", "preview"], default="full",
                        help="the orbit frames' quality (default full; preview reports no engine time)")
    parser.add_argument("--json", help="write the raw numbers here")
    args = parser.parse_args()
    if args.frames < 1:
        parser.error("--frames must be at least 1")
    if not args.skip_wasm and not os.path.isfile(os.path.join(VIEWER_DIR, "pkg", "lumiere_web_bg.wasm")):
        parser.error(f"no {VIEWER_DIR}/pkg: run tools/build-web.sh (or --skip-wasm)")
    if not args.skip_native and not os.access(args.lumiere, os.X_OK):
        parser.error(f"no {args.lumiere}: cargo build --release (or --skip-native)")

    lines = []
    out = lines.append
    report = {"frames": args.frames, "quality": args.quality, "cores": os.cpu_count(),
              "uptime_start": uptime(), "first_picture": {}}
    out(f"# The viewer page in headless Chromium ({CHROMIUM}, {os.cpu_count()} cores)\n")
    out(f"At the start: `{report['uptime_start']}`\n")
    if not args.skip_wasm:
        run_wasm(args, report, out)
    if not args.skip_native:
        run_native(args, report, out)
    site_note = run_site(args, report) if args.site else "No `--site`: no topic page was timed.\n"
    out("## Time to first picture (navigation start → `lumiere.ready`, the first frame drawn)\n")
    out(first_picture_table(report["first_picture"]) + "\n")
    out(site_note)
    if not args.skip_wasm:
        report["sizes"] = sizes()
        out("## Download size (target/web/viewer/)\n")
        out(size_table(report["sizes"]) + "\n")
    report["uptime_end"] = uptime()
    out(f"At the end: `{report['uptime_end']}`")
    print("\n".join(lines))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(report, f, indent=1)


if __name__ == "__main__":
    main()
