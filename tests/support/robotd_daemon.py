"""A robotd for the Python tests, on a DDS domain of its own, on loopback.

    with RobotdDaemon(robotd_binary, devices) as daemon:
        ...daemon.domain_id..., daemon.log()

robotd stops when the with block ends, and also when the test process ends however it ends (an
exception, SIGTERM, Ctrl-C, CTest's timeout, SIGKILL): it runs under a small sh guard whose stdin
is a pipe only the test holds. When the test is gone the kernel closes the pipe and the guard
sends robotd SIGTERM, so robotd ends cleanly (and, in a sanitizer build, runs its leak check)."""
import json
import os
import signal
import subprocess
import tempfile
import time

from test_domain import claim_domain_id

# Runs "$@" (robotd) until its stdin, the pipe from the test, closes; then stops it with SIGTERM
# and exits with its status. An asynchronous command of a non-interactive sh reads /dev/null.
GUARD = '"$@" & robotd=$!; cat > /dev/null; kill -TERM "$robotd" 2>/dev/null; wait "$robotd"'


def sim_arm(name="arm", joints=6):
    """A simulated arm device, as config/robotd.json has one."""
    return {"name": name, "driver": "sim", "rate_hz": 1000, "realtime": "prefer", "params": {"joint_count": joints}}


class RobotdDaemon:
    def __init__(self, robotd, devices):
        self._robotd = robotd
        self._devices = devices
        self.domain_id = None
        self.returncode = None

    def __enter__(self):
        self.domain_id, self._lock = claim_domain_id()
        config = {
            "daemon": {"log_level": "info", "status_rate_hz": 20, "session_status_period_ms": 200},
            "dds": {"domain_id": self.domain_id, "interface": "127.0.0.1", "multicast": False,
                    "peers": ["127.0.0.1"]},
            "devices": self._devices,
        }
        self._config = tempfile.NamedTemporaryFile("w", suffix=".json")
        json.dump(config, self._config)
        self._config.flush()
        self._log = tempfile.TemporaryFile("w+")
        # A session of its own: Ctrl-C on the terminal reaches the test, which stops robotd.
        self._process = subprocess.Popen(
            ["/bin/sh", "-c", GUARD, "robotd-guard", self._robotd, "--config", self._config.name],
            stdin=subprocess.PIPE, stdout=self._log, stderr=subprocess.STDOUT, start_new_session=True)
        return self

    def wait_until_serving(self, timeout=10.0):
        """Returns once robotd says it is ready; raises with its log if it does not."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if "robotd ready" in self.log():
                return
            if self._process.poll() is not None:
                break
            time.sleep(0.05)
        raise AssertionError("robotd did not become ready:\n" + self.log())

    def log(self):
        """What robotd has logged so far (all of it, once the with block has ended)."""
        if self._log.closed:
            return self._final_log
        self._log.seek(0)
        return self._log.read()

    def __exit__(self, *exception):
        self._process.stdin.close()  # the guard stops robotd
        try:
            self._process.wait(timeout=25)
        except subprocess.TimeoutExpired:
            os.killpg(self._process.pid, signal.SIGKILL)
            self._process.wait()
        self.returncode = self._process.returncode
        self._final_log = self.log()
        self._config.close()
        self._log.close()
        self._lock.close()
