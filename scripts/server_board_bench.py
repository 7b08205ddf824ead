#!/usr/bin/env python3
"""Measures boards through the workshop server (docs/performance.md, server section).

Starts one `engraver sim` machine and one `engraver serve` on loopback under a temporary
folder; for each board folder given, uploads its Gerber/Excellon files as one multipart
POST (allow_narrow_gaps=1) and times the answer (read, plan, plot, archive), then times
the job on the simulated machine (virtual time) and compares with `engraver board` on
the same folder (files -> plan).
Usage: scripts/server_board_bench.py path/to/engraver BOARD_DIR...
"""
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def get(base, path):
    with urllib.request.urlopen(base + path, timeout=30) as r:
        return json.load(r)


def upload_board(base, token, folder):
    boundary = "engraver-" + os.urandom(8).hex()
    body = b""
    names = sorted(os.listdir(folder))
    for name in names:
        body += (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
                 f"filename=\"{name}\"\r\nContent-Type: application/octet-stream\r\n\r\n").encode()
        body += open(os.path.join(folder, name), "rb").read() + b"\r\n"
    body += (f"--{boundary}\r\nContent-Disposition: form-data; name=\"allow_narrow_gaps\""
             f"\r\n\r\n1\r\n--{boundary}--\r\n").encode()
    req = urllib.request.Request(
        f"{base}/api/jobs", data=body, method="POST",
        headers={"Authorization": "Bearer " + token,
                 "Content-Type": "multipart/form-data; boundary=" + boundary})
    with urllib.request.urlopen(req, timeout=600) as r:
        return json.load(r), len(body)


def wait(predicate, timeout_s):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(0.01)
    return False


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    engraver, boards = sys.argv[1], sys.argv[2:]
    tmp = tempfile.mkdtemp(prefix="engraver-board-bench-")
    procs = []
    try:
        sim_port, http_port = free_port(), free_port()
        procs.append(subprocess.Popen([engraver, "sim", "--listen", f"127.0.0.1:{sim_port}"],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        data = os.path.join(tmp, "data")
        procs.append(subprocess.Popen(
            [engraver, "serve", "--data", data, "--listen", f"127.0.0.1:{http_port}",
             "--poll-ms", "5", "--machine", f"tcp://127.0.0.1:{sim_port} name=bench"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        base = f"http://127.0.0.1:{http_port}"
        wait(lambda: os.path.exists(os.path.join(data, "token")), 10)
        time.sleep(0.3)
        token = open(os.path.join(data, "token")).read().strip()
        wait(lambda: get(base, "/api/status")["machines"][0]["link"] == "online", 20)
        print("| board | files, bytes | upload -> 201 (read, plan, plot, archive) | "
              "`engraver board` files -> plan | planned | on the simulated machine |")
        print("|---|---|---|---|---|---|")
        for folder in boards:
            t0 = time.monotonic()
            job, size = upload_board(base, token, folder)
            upload_s = time.monotonic() - t0
            t1 = time.monotonic()
            done = wait(lambda: get(base, f"/api/jobs/{job['id']}")["state"]
                        not in ("queued", "running"), 3600)
            run_s = time.monotonic() - t1
            final = get(base, f"/api/jobs/{job['id']}")
            out = subprocess.run([engraver, "board", folder, "--allow-narrow-gaps", "--json",
                                  "--no-plot", "--no-check", "-o", os.path.join(tmp, "cli")],
                                 capture_output=True, text=True)
            cli = json.loads(out.stdout) if out.returncode == 0 else {}
            print(f"| {os.path.basename(os.path.normpath(folder))} | "
                  f"{len(os.listdir(folder))}, {size} | {upload_s:.2f} s | "
                  f"{cli.get('files_to_plan_wall_s', float('nan')):.2f} s | "
                  f"{final['planned_s'] / 60:.1f} min | "
                  f"{final['state'] if done else 'timeout'} in {run_s:.1f} s "
                  f"({final['executed']}/{final['total']} commands) |")
        return 0
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
