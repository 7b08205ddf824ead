#!/usr/bin/env python3
"""The double-sided walk-through of docs/user-guide.md exactly as printed: every `engraver`
command of the section's indented code runs from the repository's top folder (as the guide
says) on the shared two-layer sample; each must exit 0, and what the guide shows of its
output (the `alignment hole N at ...` lines, the `double-sided: ...` line of `run`) must be
what it prints. `send` goes to an `engraver sim` on loopback instead of the guide's machine
address, with `--poll-ms 1` (the simulated machine runs fast while the host talks; the job
is the same). The measured holes of step 4 are the ones `run`'s simulated operator finds for
the blank error the guide states, and `--pins-only`'s sentence holds (exit 8, the figure).

Exit 77 (ctest: skipped) without ../shared/samples/pcb/example_board.
Usage: guide_double_sided_test.py ENGRAVER SOURCE_DIR
"""
import json
import math
import os
import re
import shutil
import socket
import subprocess
import sys
import tempfile
import time

SKIP = 77
GUIDE_ADDRESS = "tcp://192.168.1.50:10001"


def section(guide):
    text = open(guide, encoding="utf-8").read()
    start = text.index("### Double-sided boards")
    end = min(i for i in (text.find("\n## ", start), text.find("\n### ", start + 1), len(text))
              if i > 0)
    return text[start:end]


def examples(text):
    """[(command, [shown output lines])] of the section's indented code, in order; a command's
    continuation lines joined, the comment lines after it that show its output (indented
    beyond `#`, not a numbered step) joined into one text per block."""
    out, current, taking = [], None, False
    for line in text.split("\n"):
        if not line.startswith("    "):
            current, taking = None, False
            continue
        code = line.strip()
        if current is not None and current.endswith("\\"):
            current = current[:-1] + " " + code
            out[-1] = (current, [])
            continue
        current = None
        if code.startswith("engraver "):
            current, taking = code, True
            out.append((current, []))
        elif taking and re.match(r"#\s{3,}\S", code):
            out[-1][1].append(code.lstrip("#").strip())
        else:
            taking = False
    return [(re.sub(r"\s+", " ", c), shown) for c, shown in out]


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_port(port, timeout_s):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.2):
                return
        except OSError:
            time.sleep(0.05)
    raise AssertionError("engraver sim did not listen")


def normal(s):
    return re.sub(r"\s+", " ", s).strip()


def main():
    exe, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if not os.path.isdir(os.path.join(source, "..", "shared", "samples", "pcb", "example_board")):
        print("skipped: ../shared/samples/pcb/example_board absent")
        return SKIP
    cases = examples(section(os.path.join(source, "docs", "user-guide.md")))
    commands = [c for c, _ in cases]
    assert sum(c.startswith("engraver board ") for c in commands) == 2, commands
    assert sum(c.startswith("engraver send ") for c in commands) == 2, commands
    assert sum(c.startswith("engraver run ") for c in commands) == 1, commands
    tmp = tempfile.mkdtemp(prefix="guide-double-sided-")
    port = free_port()
    sim = subprocess.Popen([exe, "sim", "--listen", f"127.0.0.1:{port}", "--pause-confirm-ms",
                            "50"], stdout=subprocess.DEVNULL, stderr=open(os.path.join(tmp, "sim.log"), "w"))
    failures = []
    try:
        wait_port(port, 10)
        shown_holes, measured, run_json = [], None, None
        for command, shown in cases:
            line = command.replace(" -o out", " -o " + tmp)
            if GUIDE_ADDRESS in line:
                line = line.replace(GUIDE_ADDRESS, f"tcp://127.0.0.1:{port}") + " --poll-ms 1"
                wait_port(port, 10)  # the simulator listens again once the last link closed
            line = exe + line[len("engraver"):]
            r = subprocess.run(line, shell=True, cwd=source, capture_output=True, text=True,
                               timeout=600)
            print(f"$ {command}\n  exit {r.returncode}")
            if r.returncode != 0:
                failures.append(f"{command}: exit {r.returncode}\n{r.stderr[-2000:]}")
                continue
            if command.startswith("engraver board ") and shown:
                for s in shown:
                    if "  " + s + "\n" not in r.stdout:
                        failures.append(f"{command}: does not print '{s}':\n{r.stdout}")
                shown_holes = [[float(v) for v in re.findall(r"-?\d+\.\d+", s)] for s in shown]
            if command.startswith("engraver send ") and "--align-measured" in command:
                m = re.search(r"--align-measured (\S+) (\S+) (\S+) (\S+)", command)
                measured = [float(v) for v in m.groups()]
            if command.startswith("engraver run "):
                if normal(" ".join(shown)) not in normal(r.stdout):
                    failures.append(f"{command}: does not print '{' '.join(shown)}':\n{r.stdout}")
                name = os.path.basename(command.split()[2].rstrip("/"))
                run_json = json.load(open(os.path.join(tmp, name + ".json")))
                pins = subprocess.run(line + " --pins-only", shell=True, cwd=source,
                                      capture_output=True, text=True, timeout=600)
                if pins.returncode != 8 or "the cuts land 535.9 um (max" not in pins.stdout:
                    failures.append(f"--pins-only: exit {pins.returncode} (8 in the guide), "
                                    f"not cut 535.9 um off:\n{pins.stdout}")
        # Step 4's measured holes: the guide's blank error as the simulated operator finds it,
        # about the holes the guide lists (0.5 degrees between them).
        if measured is None or len(shown_holes) != 2 or run_json is None:
            failures.append("the walk-through lacks its measured holes, hole list or run")
        else:
            if run_json["flip"]["measured_holes_mm"] != measured:
                failures.append(f"step 4 measures {measured}, run's operator "
                                f"{run_json['flip']['measured_holes_mm']}")
            (x1, y1), (x2, y2) = shown_holes
            turn = math.degrees(math.atan2(measured[3] - measured[1], measured[2] - measured[0]) -
                                math.atan2(y2 - y1, x2 - x1))
            if abs(turn - 0.5) > 0.01:
                failures.append(f"the measured holes are turned {turn:.3f} deg, not 0.5")
    finally:
        sim.terminate()
        sim.wait(10)
        if failures:
            print(open(os.path.join(tmp, "sim.log")).read())
        shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
