#!/usr/bin/env python3
"""The workshop page in a real browser: headless Chromium loads the page served by
`engraver serve` (with one `engraver sim` machine), enters the token, uploads a drawing
through the page's form, watches the job finish on the page, then uploads a board's three
files (copper, drill, outline) together as one job and watches it finish, then the same
board with "probe first": the page asks for the probe clip, the test clicks its button, the
job probes the simulated warped blank and finishes, and its height map is shown; and keeps a
screenshot. Then, on a second server with a real-time machine, watches a running job's live
preview: the executed part of the path ends where the tool marker is (the machine's
reported position), grows as the job runs, and both stay inside the drawing.

Drives Chromium over the DevTools protocol with a minimal WebSocket client (standard
library only). Exit 77 (ctest: skipped) when Chromium is not installed.
Usage: page_test.py ENGRAVER SCREENSHOT.png
"""
import base64
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request

from serve_processes import free_port, stop_processes

CHROMIUM = "/usr/bin/chromium"
SKIP = 77
BOARD_FILES = [os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", f)
               for f in ("blinky-F.Cu.gbr", "blinky.drl", "blinky-Edge.Cuts.gbr")]
DRAWING = ("G21\nG90\nG0 Z2\nG0 X5 Y5\nG1 Z-0.1 F100\nG1 X25 Y5 F600\nG1 X25 Y25\n"
           "G2 X5 Y25 I-10 J0\nG1 X5 Y5\nG0 Z2\n")


class DevTools:
    """Just enough WebSocket (RFC 6455, client side, text frames) for the DevTools protocol."""

    def __init__(self, url):
        host_port, path = url[len("ws://"):].split("/", 1)
        host, port = host_port.split(":")
        self.sock = socket.create_connection((host, int(port)), timeout=30)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall((f"GET /{path} HTTP/1.1\r\nHost: {host_port}\r\nUpgrade: websocket\r\n"
                           f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                           "Sec-WebSocket-Version: 13\r\n\r\n").encode())
        head = b""
        while b"\r\n\r\n" not in head:
            head += self.sock.recv(1)
        if b" 101 " not in head.split(b"\r\n")[0]:
            raise RuntimeError("DevTools WebSocket refused: " + head.decode(errors="replace"))
        self.next_id = 0

    def _recv_exact(self, n):
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            if not chunk:
                raise RuntimeError("DevTools connection closed")
            data += chunk
        return data

    def _send(self, text):
        payload = text.encode()
        mask = os.urandom(4)
        header = bytes([0x81])
        n = len(payload)
        if n < 126:
            header += bytes([0x80 | n])
        elif n < 65536:
            header += bytes([0x80 | 126]) + n.to_bytes(2, "big")
        else:
            header += bytes([0x80 | 127]) + n.to_bytes(8, "big")
        masked = bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
        self.sock.sendall(header + mask + masked)

    def _recv(self):
        message = b""
        while True:
            b0, b1 = self._recv_exact(2)
            n = b1 & 0x7F
            if n == 126:
                n = int.from_bytes(self._recv_exact(2), "big")
            elif n == 127:
                n = int.from_bytes(self._recv_exact(8), "big")
            message += self._recv_exact(n)
            if b0 & 0x80:
                return json.loads(message)

    def call(self, method, **params):
        self.next_id += 1
        self._send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            reply = self._recv()
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    def js(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True,
                      awaitPromise=True)
        return r["result"].get("value")


def wait(predicate, timeout_s, what):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if predicate():
            return
        time.sleep(0.1)
    raise AssertionError("timed out waiting for " + what)


def live_shot(screenshot):
    return os.path.splitext(screenshot)[0] + "-live.png"


# The executed part as the page drew it: its length (mm, summed over the polylines) and its
# last point, the tool marker's centre, and whether the marker lies inside the drawing.
LIVE_STATE = """(() => {
  const svg = document.querySelector('#live-path-1');
  if (!svg) return null;
  const tool = svg.querySelector('.tool');
  let length = 0, last = null;
  for (const line of svg.querySelectorAll('.done polyline')) {
    const pts = (line.getAttribute('points') || '').trim().split(/\\s+/).filter((p) => p)
      .map((p) => p.split(',').map(Number));
    for (let i = 1; i < pts.length; ++i) {
      length += Math.hypot(pts[i][0] - pts[i - 1][0], pts[i][1] - pts[i - 1][1]);
    }
    if (pts.length) last = pts[pts.length - 1];
  }
  const box = svg.getBoundingClientRect(), t = tool.getBoundingClientRect();
  return { executed_mm: Number(svg.dataset.executedMm || 0), drawn_mm: length, last: last,
           tool: tool.style.display === 'none' ? null
             : [Number(tool.getAttribute('cx')), Number(tool.getAttribute('cy'))],
           inside: t.width > 0 && t.left >= box.left && t.right <= box.right &&
             t.top >= box.top && t.bottom <= box.bottom };
})()"""


def live_preview(dt, engraver, tmp, procs, drawing, screenshot):
    """A job on a real-time machine (slow enough to watch): the live preview follows it."""
    sim_port, http_port = free_port(), free_port()
    procs.append(subprocess.Popen(
        [engraver, "sim", "--realtime", "--listen", f"127.0.0.1:{sim_port}"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    data = os.path.join(tmp, "data-live")
    procs.append(subprocess.Popen(
        [engraver, "serve", "--data", data, "--listen", f"127.0.0.1:{http_port}",
         "--poll-ms", "5", "--machine", f"tcp://127.0.0.1:{sim_port} name=bench-live"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    base = f"http://127.0.0.1:{http_port}"
    wait(lambda: os.path.exists(os.path.join(data, "token")), 10, "the second server's token")
    token = open(os.path.join(data, "token")).read().strip()
    dt.call("Page.navigate", url=base + "/")
    wait(lambda: dt.js("document.readyState") == "complete", 30, "the second page to load")
    wait(lambda: dt.js("document.querySelector('#live').textContent") == "live", 30,
         "the second page's event stream")
    with open(drawing, "rb") as f:
        req = urllib.request.Request(base + "/api/jobs?name=live-square.ngc&feed_mm_s=5",
                                     data=f.read(), method="POST",
                                     headers={"Authorization": "Bearer " + token})
    with urllib.request.urlopen(req, timeout=10) as r:
        assert json.load(r)["id"] == 1
    state = {}

    def cutting():
        state.update(dt.js(LIVE_STATE) or {})
        return state.get("tool") is not None and state.get("executed_mm", 0) > 10
    wait(cutting, 60, "the live preview to show the tool 10 mm into the job")
    first = dict(state)
    for _ in range(5):
        s = dt.js(LIVE_STATE)
        # What is drawn as executed is as long as the server says and ends at the tool.
        assert abs(s["drawn_mm"] - s["executed_mm"]) < 0.05, s
        assert s["last"] is not None and s["tool"] is not None, s
        assert abs(s["last"][0] - s["tool"][0]) < 0.1 and abs(s["last"][1] - s["tool"][1]) < 0.1, s
        assert s["inside"], s
        time.sleep(0.4)
    later = dt.js(LIVE_STATE)
    assert later["executed_mm"] > first["executed_mm"] + 2, (first, later)
    assert later["tool"] != first["tool"], (first, later)
    shot = dt.call("Page.captureScreenshot", format="png")
    with open(live_shot(screenshot), "wb") as f:
        f.write(base64.b64decode(shot["data"]))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    engraver, screenshot = sys.argv[1], sys.argv[2]
    if not os.access(CHROMIUM, os.X_OK):
        print("chromium not installed: skipped")
        return SKIP
    procs = []
    tmp = tempfile.mkdtemp(prefix="engraver-page-")
    try:
        sim_port, http_port = free_port(), free_port()
        procs.append(subprocess.Popen([engraver, "sim", "--listen", f"127.0.0.1:{sim_port}",
                                       "--surface", "tilt=0.05mm,bow=0.03mm"],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        data = os.path.join(tmp, "data")
        procs.append(subprocess.Popen(
            [engraver, "serve", "--data", data, "--listen", f"127.0.0.1:{http_port}",
             "--poll-ms", "5", "--machine", f"tcp://127.0.0.1:{sim_port} name=bench-1"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        base = f"http://127.0.0.1:{http_port}"
        wait(lambda: os.path.exists(os.path.join(data, "token")), 10, "the server's token")
        token = open(os.path.join(data, "token")).read().strip()
        drawing = os.path.join(tmp, "page-square.ngc")
        with open(drawing, "w") as f:
            f.write(DRAWING)

        profile = os.path.join(tmp, "chromium")
        chromium = subprocess.Popen(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             "--no-first-run", "--user-data-dir=" + profile, "--remote-debugging-port=0",
             "--window-size=1200,1000", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        procs.append(chromium)
        active = os.path.join(profile, "DevToolsActivePort")
        wait(lambda: os.path.exists(active) and open(active).read().count("\n") >= 1, 60,
             "Chromium's DevTools port")
        devtools_port = int(open(active).read().split("\n")[0])
        with urllib.request.urlopen(f"http://127.0.0.1:{devtools_port}/json", timeout=10) as r:
            pages = [t for t in json.load(r) if t["type"] == "page"]
        dt = DevTools(pages[0]["webSocketDebuggerUrl"])
        dt.call("Page.enable")
        dt.call("Page.navigate", url=base + "/")
        wait(lambda: dt.js("document.readyState") == "complete", 30, "the page to load")
        # The page shows the machine (from the event stream) and an empty queue.
        wait(lambda: "bench-1" in (dt.js("document.querySelector('#machines').innerText") or ""),
             30, "the machine on the page")
        wait(lambda: dt.js("document.querySelector('#live').textContent") == "live", 30,
             "the live event stream")

        # Upload through the page's own form: token, file, submit.
        dt.js(f"(() => {{ const t = document.querySelector('#token'); t.value = {json.dumps(token)};"
              " t.dispatchEvent(new Event('change')); })()")
        doc = dt.call("DOM.getDocument")
        node = dt.call("DOM.querySelector", nodeId=doc["root"]["nodeId"], selector="#file")
        dt.call("DOM.setFileInputFiles", files=[drawing], nodeId=node["nodeId"])
        dt.js("document.querySelector('#upload').requestSubmit()")
        wait(lambda: "queued as #" in (dt.js("document.querySelector('#upload-result').textContent")
                                       or ""), 30, "the upload to be accepted")
        row = "document.querySelector('#jobs tbody tr')"
        wait(lambda: "completed" in (dt.js(f"{row} ? {row}.innerText : ''") or ""), 60,
             "the job to finish on the page")
        text = dt.js(f"{row}.innerText")
        assert "page-square.ngc" in text and "bench-1" in text, text
        # The preview plot (SVG from the archive) is shown and loaded.
        wait(lambda: dt.js("(() => { const i = document.querySelector('#preview');"
                           " return i.complete && i.naturalWidth > 0; })()"), 30,
             "the preview plot")
        # A board: its three files chosen together in the same form make one job.
        dt.call("DOM.setFileInputFiles", files=BOARD_FILES, nodeId=node["nodeId"])
        assert dt.js("document.querySelector('#file').files.length") == 3
        dt.js("document.querySelector('#upload').requestSubmit()")
        wait(lambda: "queued as #2" in (dt.js("document.querySelector('#upload-result')"
                                              ".textContent") or ""), 30,
             "the board upload to be accepted")
        board_row = ("[...document.querySelectorAll('#jobs tbody tr')]"
                     ".map(r => r.innerText).find(t => t.includes('blinky')) || ''")
        wait(lambda: "completed" in (dt.js(board_row) or ""), 120, "the board to finish on the page")
        wait(lambda: dt.js("(() => { const i = document.querySelector('#preview');"
                           " return i.complete && i.naturalWidth > 0; })()"), 30,
             "the board's preview plot")
        with urllib.request.urlopen(base + "/api/jobs/2/files/board.json", timeout=10) as r:
            manifest = json.load(r)
        assert [f["name"] for f in manifest["files"]] == [
            "blinky-F.Cu.gbr", "blinky.drl", "blinky-Edge.Cuts.gbr"], manifest
        # Probe first: the page asks for the probe clip with a button; once clicked, the job
        # probes, cuts with the map, and its height map picture is shown.
        dt.js("document.querySelector('#probe_first').checked = true")
        dt.js("document.querySelector('#upload').requestSubmit()")
        wait(lambda: "queued as #3" in (dt.js("document.querySelector('#upload-result')"
                                              ".textContent") or ""), 30,
             "the probe-first board to be accepted")
        ask = "document.querySelector('#probe-3')"
        wait(lambda: "probe clip" in (dt.js(f"{ask} ? {ask}.innerText : ''") or ""), 60,
             "the page to ask for the probe clip")
        dt.js(f"{ask}.querySelector('button').click()")
        probe_row = "document.querySelector('#job-3')"
        wait(lambda: "completed" in (dt.js(f"{probe_row} ? {probe_row}.innerText : ''") or ""),
             120, "the probe-first board to finish on the page")
        assert "heightmap.svg" in dt.js(f"{probe_row}.innerText")
        dt.js(f"[...{probe_row}.querySelectorAll('button')]"
              ".find(b => b.textContent === 'Height map').click()")
        wait(lambda: dt.js("(() => { const i = document.querySelector('#preview');"
                           " return i.src.endsWith('/files/heightmap.svg') && i.complete &&"
                           " i.naturalWidth > 0; })()"), 30, "the height map picture")
        dt.js("document.querySelector('#probe_first').checked = false")
        # Without the token the page's request is refused and nothing is queued.
        dt.js("(() => { const t = document.querySelector('#token'); t.value = 'wrong';"
              " t.dispatchEvent(new Event('change')); })()")
        dt.js("document.querySelector('#upload').requestSubmit()")
        wait(lambda: "token" in (dt.js("document.querySelector('#upload-result').textContent")
                                 or ""), 30, "the refusal of a wrong token")
        with urllib.request.urlopen(base + "/api/jobs", timeout=10) as r:
            jobs = json.load(r)["jobs"]
        assert len(jobs) == 3 and all(j["state"] == "completed" for j in jobs), jobs
        assert [j["height_map"] for j in sorted(jobs, key=lambda j: j["id"])] == [
            False, False, True], jobs

        shot = dt.call("Page.captureScreenshot", format="png")
        with open(screenshot, "wb") as f:
            f.write(base64.b64decode(shot["data"]))

        live_preview(dt, engraver, tmp, procs, drawing, screenshot)
        print(f"page test passed; screenshots {screenshot}, {live_shot(screenshot)}")
        return 0
    finally:
        stop_processes(procs)
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
