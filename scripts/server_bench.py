#!/usr/bin/env python3
"""Measures the workshop server (docs/performance.md, server section).

Starts N `engraver sim` machines and one `engraver serve` on loopback under a temporary
folder, then measures:
  - latency from upload to the job's first motion (machine state 'running'), on idle machines;
  - jobs per second through the queue: JOBS small jobs uploaded at once, until all completed;
  - the server's memory (VmRSS, VmHWM) with those jobs archived.
Usage: scripts/server_bench.py path/to/engraver [--machines 8] [--jobs 1000] [--latency-runs 20]
"""
import argparse
import json
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

SQUARE = ("G21\nG90\nG0 Z2\nG0 X5 Y5\nG1 Z-0.1 F100\nG1 X15 Y5 F600\nG1 X15 Y15\n"
          "G1 X5 Y15\nG1 X5 Y5\nG0 Z2\n")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def get(base, path):
    with urllib.request.urlopen(base + path, timeout=30) as r:
        return json.load(r)


def upload(base, token, name, body, query=""):
    req = urllib.request.Request(
        f"{base}/api/jobs?name={name}{query}", data=body.encode(), method="POST",
        headers={"Authorization": "Bearer " + token,
                 "Content-Type": "application/octet-stream"})
    with urllib.request.urlopen(req, timeout=60) as r:
        return json.load(r)["id"]


def memory_kb(pid):
    out = {}
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                out[key] = int(value.split()[0])
    return out


def wait(predicate, timeout_s, step_s=0.002):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if predicate():
            return True
        time.sleep(step_s)
    return False


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("engraver")
    ap.add_argument("--machines", type=int, default=8)
    ap.add_argument("--jobs", type=int, default=1000)
    ap.add_argument("--latency-runs", type=int, default=20)
    a = ap.parse_args()

    procs = []
    with tempfile.TemporaryDirectory(prefix="engraver-bench-") as tmp:
        try:
            specs, sim_ports = [], []
            for i in range(a.machines):
                port = free_port()
                sim_ports.append(port)
                specs += ["--machine", f"tcp://127.0.0.1:{port} name=m{i + 1}"]
            http_port = free_port()
            data = os.path.join(tmp, "data")
            serve = subprocess.Popen(
                [a.engraver, "serve", "--data", data, "--listen", f"127.0.0.1:{http_port}",
                 "--poll-ms", "5"] + specs,
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            procs.append(serve)
            base = f"http://127.0.0.1:{http_port}"
            if not wait(lambda: os.path.exists(os.path.join(data, "token")), 10, 0.05):
                sys.exit("server did not start")
            token = open(os.path.join(data, "token")).read().strip()
            if not wait(lambda: os.path.exists(os.path.join(data, "jobs.sqlite")), 10, 0.05):
                sys.exit("server did not start")
            time.sleep(0.5)
            mem_start = memory_kb(serve.pid)

            # Phase 1: uploads while no machine is up (each is planned and plotted at once).
            t0 = time.monotonic()
            for i in range(a.jobs):
                upload(base, token, f"job{i}.ngc", SQUARE, "&feed_mm_s=60")
            upload_rate = a.jobs / (time.monotonic() - t0)

            # Phase 2: the machines come up and drain the queue.
            t_sims = time.monotonic()
            for port in sim_ports:
                procs.append(subprocess.Popen(
                    [a.engraver, "sim", "--listen", f"127.0.0.1:{port}"],
                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))

            def done():
                return not get(base, "/api/jobs?state=queued&limit=1")["jobs"] and \
                    not get(base, "/api/status")["running"]
            wait(done, 3600, 0.05)
            drain_s = time.monotonic() - t_sims

            def all_online():
                return all(m["link"] == "online" for m in get(base, "/api/status")["machines"])
            wait(all_online, 30, 0.05)

            # Phase 3: latency, one job at a time on idle machines.
            claimed, moving = [], []
            for i in range(a.latency_runs):
                t0 = time.monotonic()
                job = upload(base, token, f"lat{i}.ngc", SQUARE)
                seen = {}

                def started():
                    for r in get(base, "/api/status")["running"]:
                        if r["id"] == job:
                            seen.setdefault("claimed", time.monotonic())
                            if r["machine_state"] == "running":
                                seen["moving"] = time.monotonic()
                                return True
                    return get(base, f"/api/jobs/{job}")["state"] == "completed"
                wait(started, 30)
                if "moving" in seen:
                    claimed.append((seen["claimed"] - t0) * 1000)
                    moving.append((seen["moving"] - t0) * 1000)
                wait(lambda: get(base, f"/api/jobs/{job}")["state"] == "completed", 30, 0.01)

            states = {}
            for j in get(base, "/api/jobs?limit=10000")["jobs"]:
                states[j["state"]] = states.get(j["state"], 0) + 1
            per_machine = {}
            for j in get(base, "/api/jobs?limit=10000&state=completed")["jobs"]:
                per_machine[j["machine"]] = per_machine.get(j["machine"], 0) + 1
            mem = memory_kb(serve.pid)
            t_list = time.monotonic()
            get(base, "/api/jobs?limit=10000")
            list_ms = (time.monotonic() - t_list) * 1000

            print(f"machines: {a.machines}, jobs: {a.jobs}, latency runs: {len(moving)}")
            print(f"uploads (import + plan + plot + store, one client): {upload_rate:.1f} jobs/s")
            print(f"queue drained by the machines: {a.jobs / drain_s:.1f} jobs/s "
                  f"({a.jobs} jobs in {drain_s:.1f} s, machines started at the beginning)")
            if moving:
                print(f"upload -> claimed by a machine: median {statistics.median(claimed):.0f} ms, "
                      f"max {max(claimed):.0f} ms")
                print(f"upload -> first motion (machine running): median "
                      f"{statistics.median(moving):.0f} ms, max {max(moving):.0f} ms")
            print(f"job states: {states}")
            print(f"jobs per machine: {dict(sorted(per_machine.items()))}")
            print(f"server memory at start (no job): VmRSS {mem_start['VmRSS'] / 1024:.1f} MB")
            print(f"server memory with {sum(states.values())} archived jobs: "
                  f"VmRSS {mem['VmRSS'] / 1024:.1f} MB, VmHWM {mem['VmHWM'] / 1024:.1f} MB")
            print(f"GET /api/jobs (all {sum(states.values())}): {list_ms:.0f} ms")
            du = subprocess.run(["du", "-sk", data], capture_output=True, text=True).stdout
            print(f"data folder: {int(du.split()[0]) / 1024:.1f} MB")
        finally:
            for p in procs:
                p.terminate()
            for p in procs:
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    p.kill()


if __name__ == "__main__":
    main()
