"""A throw-away PostgreSQL server for the server tests that need one.

initdb + pg_ctl under a temporary folder, as the `postgres` user when run as root (PostgreSQL
refuses to run as root), listening on a Unix socket in that folder, with an empty database
`queue` owned by the user `engraver`.
"""
import glob
import os
import pwd
import shutil
import subprocess
import tempfile

from serve_processes import free_port


class Unavailable(Exception):
    """No PostgreSQL to start here (the test is skipped); str() says why."""


class PgCluster:
    """A cluster under tmp (which must be readable by the postgres user): start(), then
    conninfo for `engraver serve --db`; stop() in a finally."""

    def __init__(self, tmp):
        bins = sorted(glob.glob("/usr/lib/postgresql/*/bin"))
        if not bins or not os.access(os.path.join(bins[-1], "initdb"), os.X_OK):
            raise Unavailable("PostgreSQL not installed")
        self.bin = bins[-1]
        self.run_as = []
        self.user = None
        if os.geteuid() == 0:
            try:
                self.user = pwd.getpwnam("postgres")
            except KeyError:
                raise Unavailable("running as root and no 'postgres' user")
            self.run_as = ["runuser", "-u", "postgres", "--"]
        self.cluster = os.path.join(tmp, "cluster")
        self.sockets = os.path.join(tmp, "sockets")
        self.port = free_port()
        self.started = False
        self.conninfo = f"host={self.sockets} port={self.port} user=engraver dbname=queue"

    def tool(self, name):
        return os.path.join(self.bin, name)

    def start(self):
        os.makedirs(self.sockets)
        if self.user is not None:
            os.chown(self.sockets, self.user.pw_uid, self.user.pw_gid)
            os.makedirs(self.cluster)
            os.chown(self.cluster, self.user.pw_uid, self.user.pw_gid)
        subprocess.run(self.run_as + [self.tool("initdb"), "-D", self.cluster, "-A", "trust",
                                      "-U", "engraver"], check=True, stdout=subprocess.DEVNULL)
        subprocess.run(self.run_as + [self.tool("pg_ctl"), "-D", self.cluster, "-w", "-l",
                                      os.path.join(self.sockets, "log"), "-o",
                                      f"-k {self.sockets} -p {self.port} -c listen_addresses=''",
                                      "start"],
                       check=True, stdout=subprocess.DEVNULL)
        self.started = True
        subprocess.run([self.tool("createdb"), "-h", self.sockets, "-p", str(self.port), "-U",
                        "engraver", "queue"], check=True)

    def psql(self):
        """psql on the queue database, stopping at the first error (SQL on stdin)."""
        return [self.tool("psql"), "-h", self.sockets, "-p", str(self.port), "-U", "engraver",
                "-v", "ON_ERROR_STOP=1", "-q", "queue"]

    def stop(self):
        if self.started:
            subprocess.run(self.run_as + [self.tool("pg_ctl"), "-D", self.cluster, "-m", "fast",
                                          "-w", "stop"], stdout=subprocess.DEVNULL)
            self.started = False


def temporary_cluster(prefix):
    """A new temporary folder and a PgCluster in it, not started yet; (None, None), the reason
    printed, where PostgreSQL cannot run (the caller skips)."""
    tmp = tempfile.mkdtemp(prefix=prefix)
    os.chmod(tmp, 0o755)  # the postgres user reaches its cluster inside
    try:
        return tmp, PgCluster(tmp)
    except Unavailable as e:
        print(f"{e}: skipped")
        shutil.rmtree(tmp, ignore_errors=True)
        return None, None
