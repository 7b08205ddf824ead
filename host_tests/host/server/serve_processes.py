"""What the tests that start `engraver serve` and `engraver sim` processes share: a free
loopback port, a JSON GET, and stopping the processes at the end."""
import json
import socket
import subprocess
import urllib.request


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def get(base, path):
    """The JSON answer to GET base + path."""
    with urllib.request.urlopen(base + path, timeout=30) as r:
        return json.load(r)


def stop_processes(procs):
    """Terminates the processes, last started first; kills one that has not ended in 20 s."""
    for p in reversed(procs):
        p.terminate()
    for p in procs:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()
