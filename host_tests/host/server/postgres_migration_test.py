#!/usr/bin/env python3
"""A PostgreSQL queue made by the previous version opens in `engraver serve` with its jobs.

Starts a real PostgreSQL server under a temporary folder (initdb + pg_ctl, as the `postgres`
user when run as root), creates the jobs and servers tables as the version before the job
record's field table (host/lib/server/job_record_fields.h) made them, with one interrupted job
in them, and starts one server on that database: the old job reads back field by field, and a
new upload is queued after it with every column the table has.
Exit 77 (ctest: skipped) when PostgreSQL is not installed.
Usage: postgres_migration_test.py ENGRAVER
"""
import json
import os
import shutil
import subprocess
import sys
import time
import urllib.request

from pg_cluster import temporary_cluster
from serve_processes import free_port, get, stop_processes

SKIP = 77
PREVIOUS_SCHEMA = """
CREATE TABLE jobs (
 id BIGSERIAL PRIMARY KEY, key TEXT NOT NULL UNIQUE, name TEXT NOT NULL,
 input_file TEXT NOT NULL, state TEXT NOT NULL, priority INTEGER NOT NULL,
 tag TEXT NOT NULL, feed_mm_s DOUBLE PRECISION NOT NULL,
 tol_mm DOUBLE PRECISION NOT NULL, scale DOUBLE PRECISION NOT NULL,
 margin_mm DOUBLE PRECISION NOT NULL, width_mm DOUBLE PRECISION NOT NULL,
 height_mm DOUBLE PRECISION NOT NULL, planned_s DOUBLE PRECISION NOT NULL,
 machine TEXT NOT NULL DEFAULT '', owner TEXT NOT NULL DEFAULT '',
 message TEXT NOT NULL DEFAULT '', executed BIGINT NOT NULL DEFAULT 0,
 total BIGINT NOT NULL DEFAULT 0, resume_curve INTEGER NOT NULL DEFAULT -1,
 created_ms BIGINT NOT NULL, started_ms BIGINT NOT NULL DEFAULT 0,
 finished_ms BIGINT NOT NULL DEFAULT 0, start_curve INTEGER NOT NULL DEFAULT -1,
 input BYTEA NOT NULL);
CREATE INDEX jobs_queue ON jobs (state, priority DESC, id);
CREATE TABLE servers (name TEXT PRIMARY KEY, seen_ms BIGINT NOT NULL);
ALTER TABLE jobs ADD COLUMN resume_index BIGINT NOT NULL DEFAULT -1;
ALTER TABLE jobs ADD COLUMN resume_point INTEGER NOT NULL DEFAULT 0;
ALTER TABLE jobs ADD COLUMN resume_job_id INTEGER NOT NULL DEFAULT -1;
ALTER TABLE jobs ADD COLUMN lease_epoch BIGINT NOT NULL DEFAULT 0;
ALTER TABLE servers ADD COLUMN epoch BIGINT NOT NULL DEFAULT 0;
ALTER TABLE servers ADD COLUMN revoked INTEGER NOT NULL DEFAULT 0;
ALTER TABLE servers ADD COLUMN holder TEXT NOT NULL DEFAULT '';
INSERT INTO jobs (key, name, input_file, state, priority, tag, feed_mm_s, tol_mm, scale,
 margin_mm, width_mm, height_mm, planned_s, machine, owner, message, executed, total,
 resume_curve, created_ms, started_ms, finished_ms, start_curve, input, resume_index,
 resume_point, resume_job_id, lease_epoch)
 VALUES ('0123abcd', 'old.ngc', 'input.ngc', 'interrupted', 3, 'pen', 7.5, 0.02, 1.5, 2.5,
 40.5, 30.25, 99.5, 'm2', 'old-server', 'link lost', 120, 400, 5, 1600000000000,
 1600000000100, 1600000000200, -1, 'G0 X1'::bytea, 118, 4, 21, 3);
"""
# The old job as GET /api/jobs/1 must give it.
OLD_JOB = {"id": 1, "name": "old.ngc", "input_file": "input.ngc", "state": "interrupted",
           "priority": 3, "tag": "pen", "feed_mm_s": 7.5, "tol_mm": 0.02, "scale": 1.5,
           "margin_mm": 2.5, "size_mm": [40.5, 30.25], "planned_s": 99.5, "machine": "m2",
           "server": "old-server", "message": "link lost", "executed": 120, "total": 400,
           "resume_curve": 5, "start_curve": -1, "created_ms": 1600000000000,
           "started_ms": 1600000000100, "finished_ms": 1600000000200}
SQUARE = "G21\nG90\nG0 Z2\nG0 X5 Y5\nG1 Z-0.1 F100\nG1 X15 Y5 F600\nG0 Z2\n"


def wait(predicate, timeout_s, what):
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        try:
            if predicate():
                return
        except OSError:
            pass
        time.sleep(0.1)
    raise AssertionError("timed out waiting for " + what)


def main():
    engraver = sys.argv[1]
    tmp, pg = temporary_cluster("engraver-pgmig-")
    if pg is None:
        return SKIP
    serve = None
    log_path = os.path.join(tmp, "serve.log")
    try:
        pg.start()
        subprocess.run(pg.psql(), input=PREVIOUS_SCHEMA.encode(), check=True)
        conninfo = pg.conninfo

        http_port = free_port()
        data = os.path.join(tmp, "data")
        base = f"http://127.0.0.1:{http_port}"
        serve = subprocess.Popen(
            [engraver, "serve", "--data", data, "--listen", f"127.0.0.1:{http_port}",
             "--db", conninfo, "--name", "server1"],
            stdout=open(log_path, "w"), stderr=subprocess.STDOUT)
        wait(lambda: os.path.exists(os.path.join(data, "token")), 20, "the server's token")
        wait(lambda: get(base, "/api/status") is not None, 20, "the server to answer")
        token = open(os.path.join(data, "token")).read().strip()

        old = get(base, "/api/jobs/1")
        for key, value in OLD_JOB.items():
            assert old[key] == value, (key, old[key], value)
        req = urllib.request.Request(
            f"{base}/api/jobs?name=new.ngc&margin_mm=1.5&priority=2", data=SQUARE.encode(),
            method="POST", headers={"Authorization": "Bearer " + token})
        with urllib.request.urlopen(req, timeout=60) as r:
            new = json.load(r)
        assert new["id"] == 2 and new["margin_mm"] == 1.5 and new["priority"] == 2, new
        assert [j["id"] for j in get(base, "/api/jobs")["jobs"]] == [2, 1]
        print("a previous version's PostgreSQL queue opened: its job read back, a new one "
              "queued after it")
        return 0
    except Exception:
        if os.path.exists(log_path):
            print("--- serve.log:\n" + open(log_path).read())
        raise
    finally:
        stop_processes([serve] if serve is not None else [])
        pg.stop()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
