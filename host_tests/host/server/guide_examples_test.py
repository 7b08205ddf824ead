#!/usr/bin/env python3
"""The API examples of docs/user-guide.md exactly as printed: every `TOKEN=...`, `curl ...`,
`until curl ...` (a wait: it must end, within 60 s) and `NAME=$(curl ...)` line of the `engraver serve` section runs with bash and the real curl
(and jq) against `engraver serve` on loopback (one `engraver sim --realtime` machine); a
NAME=$(...) line's value is kept for the lines after it, as in one shell. Only the data
folder, the port and the files' contents are this test's: the files are made under the
names the examples use (board.ngc larger than 8 KB, the blinky board from data/; the
double-sided example's shared two-layer sample from ../shared/samples/pcb/example_board,
or the blinky board under its names without ../shared). Before the wait for the probe clip
(or, without one, the `probe_ready` example) the test itself
cancels the other queued boards but the bottom side (which waits for the probe-first job's
map) and brings a second machine ('right', a sim at full speed with a warped blank,
--surface) online, which takes the probe-first job to the probe clip; then it aborts job 1:
the bottom side, uploaded before its top side probed, stays queued, waiting for the map,
though 'left' is free. After the `probe_ready` example the top side probes and cuts, and
the bottom side runs with its map on the machine that probed it: the test waits for both to
end `completed` (within BOTH_SIDES_S).

Exit 77 (ctest: skipped) when curl or jq is not installed.
Usage: guide_examples_test.py ENGRAVER USER_GUIDE.md
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

from serve_processes import free_port, stop_processes

SKIP = 77
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
DOC_DATA, DOC_PORT = "/srv/engraver", "127.0.0.1:8080"
BOTH_SIDES_S = 240  # both sides of the double-sided example, probed and cut at full speed


def wait(predicate, timeout_s, what):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if predicate():
            return
        time.sleep(0.05)
    raise AssertionError("timed out waiting for " + what)


def serve_examples(guide):
    """The shell commands of the serve section's indented code: TOKEN= and curl lines,
    continuation lines joined as bash would read them."""
    text = open(guide, encoding="utf-8").read()
    start = text.index("## `engraver serve")
    end = text.find("\n## ", start + 1)
    section = text[start:end if end > 0 else len(text)]
    commands, current = [], None
    for line in section.split("\n"):
        code = line[4:] if line.startswith("    ") else None
        if current is not None:
            current += "\n" + code
            if not code.endswith("\\"):
                commands.append(current)
                current = None
            continue
        if code is None or not re.match(r"(TOKEN=|curl |until curl |[A-Z_]+=\$\(curl )",
                                        code.strip()):
            continue
        if code.endswith("\\"):
            current = code.strip()
        else:
            commands.append(code.strip())
    return commands


def board_ngc():
    """A drawing larger than 8 KB: a circle of 1 500 segments (about 12 s at 10 mm/s)."""
    lines = ["G21", "G90", "G0 Z2", "G0 X45 Y25", "G1 Z-0.1 F100"]
    for i in range(1, 1501):
        a = 2 * math.pi * i / 1500
        lines.append(f"G1 X{25 + 20 * math.cos(a):.4f} Y{25 + 20 * math.sin(a):.4f} F600")
    return "\n".join(lines + ["G0 Z2", ""])


def get(base, path):
    with urllib.request.urlopen(base + path, timeout=10) as r:
        return json.load(r)


def machine_online(base):
    try:
        return get(base, "/api/status")["machines"][0]["link"] == "online"
    except OSError:  # not listening yet
        return False


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    engraver, guide = sys.argv[1], sys.argv[2]
    for tool in ("curl", "jq"):
        if shutil.which(tool) is None:
            print(tool + " not installed: skipped")
            return SKIP
    commands = serve_examples(guide)
    curls = [c for c in commands if not c.startswith("TOKEN=")]
    assert len(curls) >= 4 and commands[0].startswith("TOKEN="), commands
    procs = []
    tmp = tempfile.mkdtemp(prefix="engraver-guide-")
    try:
        sim_port, http_port, right_port = free_port(), free_port(), free_port()
        procs.append(subprocess.Popen(
            [engraver, "sim", "--realtime", "--listen", f"127.0.0.1:{sim_port}",
             "--surface", "tilt=0.05mm,bow=0.03mm"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        data = os.path.join(tmp, "data")
        procs.append(subprocess.Popen(
            [engraver, "serve", "--data", data, "--listen", f"127.0.0.1:{http_port}",
             "--machine", f"tcp://127.0.0.1:{sim_port} name=left",
             "--machine", f"tcp://127.0.0.1:{right_port} name=right"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        base = f"http://127.0.0.1:{http_port}"
        wait(lambda: os.path.exists(os.path.join(data, "token")), 10, "the server's token")
        wait(lambda: machine_online(base), 20, "the server up and its machine online")
        work = os.path.join(tmp, "work")
        os.mkdir(work)
        with open(os.path.join(work, "board.ngc"), "w") as f:
            f.write(board_ngc())
        assert os.path.getsize(os.path.join(work, "board.ngc")) > 8 * 1024
        for name in ("blinky-F.Cu.gbr", "blinky.drl", "blinky-Edge.Cuts.gbr", "blinky.zip"):
            shutil.copy(os.path.join(DATA, name), work)
        shutil.copy(os.path.join(DATA, "blinky-F.Cu.gbr"), os.path.join(work, "blinky-B.Cu.gbr"))
        sample = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(guide))), "..",
                              "shared", "samples", "pcb", "example_board")
        for suffix, blinky in (("-F.Cu.gbr", "blinky-F.Cu.gbr"), ("-B.Cu.gbr", "blinky-F.Cu.gbr"),
                               ("-PTH.drl", "blinky.drl"),
                               ("-Edge.Cuts.gbr", "blinky-Edge.Cuts.gbr")):
            shared = os.path.join(sample, "example_board" + suffix)
            shutil.copy(shared if os.path.exists(shared) else os.path.join(DATA, blinky),
                        os.path.join(work, "example_board" + suffix))

        prelude = [c for c in commands if c.startswith("TOKEN=")]
        values = {}  # NAME=$(...) lines: NAME -> its value, for the lines after it
        jobs_before = 0
        checked_before_probe = False

        def check_held_and_queued():
            # What the first examples did: the drawing on the machine, held; boards queued.
            wait(lambda: get(base, "/api/status")["running"][0]["machine_state"] == "held", 10,
                 "job 1 held")
            jobs = {j["id"]: j for j in get(base, "/api/jobs")["jobs"]}
            assert jobs[1]["name"] == "board.ngc" and jobs[1]["priority"] == 5, jobs[1]
            boards = [j for j in jobs.values() if j["input_file"] == "board.json"]
            assert len(boards) >= 2 and all(j["state"] == "queued" for j in boards), boards
            return jobs

        def control(job, action):
            req = urllib.request.Request(
                f"{base}/api/jobs/{job}/control", data=json.dumps({"action": action}).encode(),
                method="POST", headers={"Authorization": "Bearer " + open(
                    os.path.join(data, "token")).read().strip()})
            with urllib.request.urlopen(req, timeout=10) as r:
                return json.load(r)

        def probe_job_waiting(job):
            for j in get(base, "/api/status")["running"]:
                if j["id"] == job and j["machine_state"] == "probe_clip":
                    return True
            return False

        def job_of(text):
            return values[text[1:]] if text.startswith("$") else int(text)

        for cmd in curls:
            print("$ " + cmd)
            probe_ready = re.search(r"probe_ready.*?/api/jobs/(\d+|\$[A-Z_]+)/control", cmd, re.S)
            # The guide's wait for the clip prompt (`until curl ... probe_clip ...; done`).
            clip_wait = re.search(r"^until curl .*?\.id == (\d+|\$[A-Z_]+)\b.*probe_clip", cmd,
                                  re.S)
            if (probe_ready or clip_wait) and not checked_before_probe:
                # A second machine for the probe-first job, which then asks for the clip.
                job = job_of((probe_ready or clip_wait).group(1))
                jobs = check_held_and_queued()
                checked_before_probe = True
                # The queue first: a machine online claims the next job.
                for j in jobs.values():
                    if j["state"] == "queued" and j["id"] != job and not j["waiting"]:
                        control(j["id"], "cancel")
                procs.append(subprocess.Popen(
                    [engraver, "sim", "--listen", f"127.0.0.1:{right_port}",
                     "--surface", "tilt=0.05mm,bow=0.03mm"],
                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
            if probe_ready:
                wait(lambda: probe_job_waiting(job), 30, f"job {job} asking for the probe clip")
                # 'left' free too: the bottom side still waits for the map.
                control(1, "abort")
                wait(lambda: get(base, "/api/status")["machines"][0]["job"] is None, 20,
                     "job 1 off 'left'")
                time.sleep(1.0)
                bottom = get(base, f"/api/jobs/{values['BOTTOM']}")
                assert bottom["state"] == "queued", bottom
                assert bottom["waiting"] == f"waiting for the height map of job {job}", bottom
            elif "/control" in cmd:
                # A control example steers job 1: it must be on its machine by now.
                wait(lambda: [j["id"] for j in get(base, "/api/status")["running"]] == [1], 20,
                     "job 1 on its machine")
            name = re.match(r"([A-Z_]+)=\$\(", cmd)
            shown = [f'echo "${name.group(1)}"'] if name else []
            script = "\n".join(prelude + [cmd] + shown).replace(DOC_DATA, data).replace(
                DOC_PORT, f"127.0.0.1:{http_port}")
            assert DOC_PORT not in script and DOC_DATA not in script, script
            run = subprocess.run(["bash", "-c", script], cwd=work, capture_output=True,
                                 text=True, timeout=60)
            print(run.stdout)
            assert run.returncode == 0, run.stderr
            if clip_wait:  # it ended when, and only when, the job asked for the clip
                assert probe_job_waiting(job), get(base, "/api/status")
                continue
            answer = json.loads(run.stdout)
            if name:  # the job's id, from the upload's answer
                assert isinstance(answer, int), (cmd, run.stdout)
                values[name.group(1)] = answer
                prelude.append(f"{name.group(1)}={answer}")
                answer = {"id": answer}
            assert "error" not in answer, answer
            if re.search(r"/api/jobs(\?|[\s']|$)", cmd):
                jobs_before += 1
                assert answer["id"] == jobs_before, answer
        if not checked_before_probe:
            check_held_and_queued()
        else:
            # The confirm was taken: the top side probes and cuts, then the bottom side runs
            # with its map where it was probed; both to the end.
            top, bottom_id = values["TOP"], values["BOTTOM"]
            final = ("completed", "failed", "aborted", "cancelled", "interrupted")
            started = time.monotonic()
            wait(lambda: get(base, f"/api/jobs/{bottom_id}")["state"] in final, BOTH_SIDES_S,
                 f"the bottom side (job {bottom_id}) to end")
            top_job, bottom = get(base, f"/api/jobs/{top}"), get(base, f"/api/jobs/{bottom_id}")
            assert top_job["state"] == "completed" and top_job["height_map"], top_job
            assert bottom["state"] == "completed", bottom
            assert bottom["height_map"] and bottom["waiting"] == "", bottom
            assert bottom["machine"] == top_job["machine"] == "right", (top_job, bottom)
            print(f"both sides completed {time.monotonic() - started:.0f} s after the confirm")
        print(f"guide examples passed: {len(curls)} curl commands")
        return 0
    finally:
        stop_processes(procs)
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
