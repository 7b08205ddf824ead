#!/usr/bin/env python3
"""Two `engraver serve` processes on one PostgreSQL queue: every job runs exactly once.

Starts a real PostgreSQL server under a temporary folder (initdb + pg_ctl, as the
`postgres` user when run as root: the server refuses to run as root), four `engraver sim`
machines, and two servers with two machines each and their own data folders. Jobs are
uploaded to both servers alternately; each must complete once, on one server, and both
servers must have taken some. A board (three Gerber/Excellon files) uploaded to one server
and tagged for machines only the other one has online runs there from the files the
database keeps. Each server serves the files of the jobs it ran; the other answers 404
naming it. With --shared-archive both servers keep their jobs' folders in one archive
(`serve --archive`) and each serves every job's files.
Exit 77 (ctest: skipped) when PostgreSQL is not installed.
Usage: postgres_test.py ENGRAVER [--shared-archive]
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import time
import urllib.error
import urllib.request

from pg_cluster import temporary_cluster
from serve_processes import free_port, get, stop_processes

SKIP = 77
JOBS = 40
BOARD_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
BOARD_FILES = ("blinky-F.Cu.gbr", "blinky.drl", "blinky-Edge.Cuts.gbr")
SQUARE = ("G21\nG90\nG0 Z2\nG0 X5 Y5\nG1 Z-0.1 F100\nG1 X15 Y5 F600\nG1 X15 Y15\n"
          "G1 X5 Y15\nG1 X5 Y5\nG0 Z2\n")


def upload(base, token, name):
    req = urllib.request.Request(
        f"{base}/api/jobs?name={name}&feed_mm_s=30", data=SQUARE.encode(), method="POST",
        headers={"Authorization": "Bearer " + token,
                 "Content-Type": "application/octet-stream"})
    with urllib.request.urlopen(req, timeout=60) as r:
        return json.load(r)["id"]


def upload_board(base, token, tag):
    """One multipart POST with the board's files as several `file` parts."""
    boundary = "engraver-" + os.urandom(8).hex()
    body = b""
    for name in BOARD_FILES:
        body += (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
                 f"filename=\"{name}\"\r\nContent-Type: application/octet-stream\r\n\r\n").encode()
        body += open(os.path.join(BOARD_DIR, name), "rb").read() + b"\r\n"
    body += (f"--{boundary}\r\nContent-Disposition: form-data; name=\"tag\"\r\n\r\n{tag}\r\n"
             f"--{boundary}--\r\n").encode()
    req = urllib.request.Request(
        f"{base}/api/jobs", data=body, method="POST",
        headers={"Authorization": "Bearer " + token,
                 "Content-Type": "multipart/form-data; boundary=" + boundary})
    with urllib.request.urlopen(req, timeout=60) as r:
        return json.load(r)["id"]


def wait(predicate, timeout_s, what):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if predicate():
            return
        time.sleep(0.1)
    raise AssertionError("timed out waiting for " + what)


def fetch(base, path):
    """(HTTP status, body) of a GET."""
    try:
        with urllib.request.urlopen(base + path, timeout=30) as r:
            return r.status, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.read()


def main():
    engraver = sys.argv[1]
    shared = sys.argv[2:] == ["--shared-archive"]
    tmp, pg = temporary_cluster("engraver-pg-")
    if pg is None:
        return SKIP
    procs = []
    try:
        pg.start()
        conninfo = pg.conninfo

        servers = []
        for s in range(2):
            specs = []
            for m in range(2):
                sim_port = free_port()
                procs.append(subprocess.Popen([engraver, "sim", "--listen",
                                               f"127.0.0.1:{sim_port}"],
                                              stdout=subprocess.DEVNULL,
                                              stderr=subprocess.DEVNULL))
                # Only server 2's machines take boards (tag pcb); untagged jobs go anywhere.
                tags = " tags=pcb" if s == 1 else ""
                specs += ["--machine",
                          f"tcp://127.0.0.1:{sim_port} name=s{s + 1}m{m + 1}{tags}"]
            if s == 0:
                # Server 1 lists a pcb machine that is never on (its intake then takes
                # boards), so a board uploaded there can only run on server 2.
                specs += ["--machine", f"tcp://127.0.0.1:{free_port()} name=s1off tags=pcb"]
            http_port = free_port()
            data = os.path.join(tmp, f"data{s + 1}")
            archive = os.path.join(tmp, "shared") if shared else os.path.join(data, "jobs")
            log = open(os.path.join(tmp, f"serve{s + 1}.log"), "w")
            procs.append(subprocess.Popen(
                [engraver, "serve", "--data", data, "--listen", f"127.0.0.1:{http_port}",
                 "--db", conninfo, "--name", f"server{s + 1}", "--poll-ms", "5",
                 "--stale-s", "8"] + (["--archive", archive] if shared else []) + specs,
                stdout=log, stderr=subprocess.STDOUT))
            servers.append((f"http://127.0.0.1:{http_port}", data, archive))
        tokens = []
        for base, data, _ in servers:
            wait(lambda: os.path.exists(os.path.join(data, "token")), 20, "a server's token")
            time.sleep(0.3)
            tokens.append(open(os.path.join(data, "token")).read().strip())

            def up():
                try:
                    get(base, "/api/status")
                    return True
                except OSError:
                    return False
            wait(up, 20, "a server to answer")

        ids = [upload(servers[i % 2][0], tokens[i % 2], f"job{i}.ngc") for i in range(JOBS)]
        assert len(set(ids)) == JOBS, ids  # one id sequence for both servers

        def all_done():
            jobs = get(servers[0][0], "/api/jobs?limit=1000")["jobs"]
            return len(jobs) == JOBS and all(j["state"] == "completed" for j in jobs)
        try:
            wait(all_done, 300, "every job to complete")
        except AssertionError:
            jobs = get(servers[0][0], "/api/jobs?limit=1000")["jobs"]
            raise AssertionError("timed out waiting for every job to complete: " + ", ".join(
                f'{j["id"]} {j["state"]} on {j["server"] or "-"}' for j in jobs))

        jobs = get(servers[1][0], "/api/jobs?limit=1000")["jobs"]  # the other server agrees
        assert len(jobs) == JOBS and all(j["state"] == "completed" for j in jobs), jobs
        by_server = {}
        for j in jobs:
            by_server[j["server"]] = by_server.get(j["server"], 0) + 1
        assert set(by_server) == {"server1", "server2"}, by_server
        # Exactly once: one report per job over both archives, from the server that ran it.
        for j in jobs:
            reports = []
            for archive in sorted(set(a for _, _, a in servers)):
                for path in glob.glob(os.path.join(archive, "*", "runs", "*", "report.json")):
                    report = json.load(open(path))
                    if report["id"] == j["id"]:
                        reports.append(report)
            assert len(reports) == 1, (j, reports)
            assert reports[0]["server"] == j["server"] and reports[0]["state"] == "completed"
            # The job's report through each server: the one that ran it serves it; the other
            # too when the archive is shared, else it answers 404 naming where it ran.
            for base, _, _ in servers:
                status, body = fetch(base, f"/api/jobs/{j['id']}/files/report.json")
                if shared or base == servers[int(j["server"][-1]) - 1][0]:
                    assert status == 200 and json.loads(body)["id"] == j["id"], (status, body)
                else:
                    assert status == 404 and f"server '{j['server']}'".encode() in body, body

        # A board uploaded to server 1 runs on server 2: its files come from the database.
        board_id = upload_board(servers[0][0], tokens[0], "pcb")
        wait(lambda: get(servers[0][0], f"/api/jobs/{board_id}")["state"] in
             ("completed", "failed"), 120, "the board job to finish")
        board = get(servers[0][0], f"/api/jobs/{board_id}")
        assert board["state"] == "completed" and board["server"] == "server2", board
        key = [p for p in glob.glob(os.path.join(servers[1][2], "*", "runs", "1",
                                                 "report.json"))
               if json.load(open(p))["id"] == board_id]
        assert len(key) == 1, key
        run = os.path.dirname(key[0])
        archive = os.path.dirname(os.path.dirname(run))
        for name, kept in zip(BOARD_FILES, ("copper.top.gbr", "drill.drl", "outline.gbr")):
            assert (open(os.path.join(archive, kept), "rb").read() ==
                    open(os.path.join(BOARD_DIR, name), "rb").read()), kept
        for kept in ("board.json", "plan.json", "plot.svg", "plot.png", "runs/1/machine.log"):
            assert os.path.getsize(os.path.join(archive, kept)) > 0, kept
        print(f"board job {board_id} uploaded to server1 ran on server2 from the "
              + ("shared archive" if shared else "database"))

        # A server dies mid-job (kill -9): the other one marks its running jobs interrupted
        # (--stale-s 8: at 3 a debug server on a loaded machine was once taken for dead
        # while its jobs ran, and they were interrupted); re-queued, they run there.
        slow = ("G21\nG90\nG0 Z2\nG0 X5 Y5\nG1 Z-0.1 F100\nG1 X95 Y5 F600\nG1 X95 Y95\n"
                "G1 X5 Y95\nG1 X5 Y5\nG0 Z2\n")
        serves = {"server1": (procs[2], servers[0][0]), "server2": (procs[5], servers[1][0])}
        req = urllib.request.Request(
            f"{servers[0][0]}/api/jobs?name=slow.ngc&feed_mm_s=0.5", data=slow.encode(),
            method="POST", headers={"Authorization": "Bearer " + tokens[0]})
        with urllib.request.urlopen(req, timeout=60) as r:
            slow_id = json.load(r)["id"]
        wait(lambda: get(servers[0][0], f"/api/jobs/{slow_id}")["state"] == "running", 30,
             "the slow job to start")
        runner = get(servers[0][0], f"/api/jobs/{slow_id}")["server"]
        other = "server2" if runner == "server1" else "server1"
        victim, _ = serves[runner]
        base, token = serves[other][1], tokens[0 if other == "server1" else 1]
        victim.kill()
        victim.wait()
        wait(lambda: get(base, f"/api/jobs/{slow_id}")["state"] == "interrupted", 30,
             "the dead server's job to be marked interrupted")
        req = urllib.request.Request(
            f"{base}/api/jobs/{slow_id}/control", data=b'{"action": "requeue"}', method="POST",
            headers={"Authorization": "Bearer " + token})
        urllib.request.urlopen(req, timeout=30).close()
        wait(lambda: get(base, f"/api/jobs/{slow_id}")["server"] == other and
             get(base, f"/api/jobs/{slow_id}")["state"] == "running", 30,
             "the re-queued job to run on the other server")
        print(f"{runner} killed mid-job: {other} marked its job interrupted and ran it again")
        print(f"{JOBS} jobs, each run once; per server: {by_server}")
        return 0
    except Exception:
        for name in ("serve1.log", "serve2.log"):
            path = os.path.join(tmp, name)
            if os.path.exists(path):
                print(f"--- {name}:\n" + open(path).read())
        raise
    finally:
        stop_processes(procs)
        pg.stop()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
