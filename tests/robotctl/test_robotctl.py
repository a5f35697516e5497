#!/usr/bin/env python3
"""robotctl against a real robotd: one simulated 6-joint arm on a DDS domain of its own.

    test_robotctl.py --robotd build/bin/robotd --robotctl build/bin/robotctl [unittest args]

The DDS domain id is claimed with an exclusive lock on /tmp/robotd-test-domain-<id>.lock,
held for the whole run, so tests running in parallel never share a domain.
"""

import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from cli_test import read_line, run_tests, stop_process  # noqa: E402  (tests/support)
from test_domain import claim_domain_id  # noqa: E402  (tests/support)

ROBOTD = ""
ROBOTCTL = ""
ARM_JOINTS = 6

def robotd_config(domain_id):
    """config/robotd.json reduced to its arm, on loopback and on `domain_id`."""
    return {
        "daemon": {"node_name": "robotd", "log_level": "info", "status_rate_hz": 10,
                   "session_status_period_ms": 1000},
        "dds": {"domain_id": domain_id, "interface": "127.0.0.1", "multicast": False, "peers": ["127.0.0.1"]},
        "devices": [{
            "name": "arm",
            "driver": "sim",
            "rate_hz": 1000,
            # Tests need no real-time priority, and must not take the CPU from tests beside them.
            "realtime": "off",
            "limit_policy": "reject",
            "safe_behavior": "DAMPING",
            "shutdown_behavior": "DAMPING",
            "params": {
                "model": "robotd simulated 6-joint arm",
                "kinematic_model": "parol6",
                "joint_count": ARM_JOINTS,
                "joint_defaults": {
                    "position_min_rad": -2.6, "position_max_rad": 2.6,
                    "velocity_max_rad_s": 2.0, "acceleration_max_rad_s2": 8.0,
                    "effort_max_nm": 40, "kp_max": 500, "kd_max": 50,
                    "default_kp": 200, "default_kd": 8,
                    "inertia_kg_m2": 0.05, "damping_nm_s_rad": 0.3,
                },
            },
        }],
    }


class Robotd:
    """A robotd process on its own domain, stopped on close()."""

    def __init__(self, domain_id, workdir):
        self.domain_id = domain_id
        config_path = os.path.join(workdir, "robotd.json")
        with open(config_path, "w") as config:
            json.dump(robotd_config(domain_id), config, indent=2)
        self.log_path = os.path.join(workdir, "robotd.log")
        self._log = open(self.log_path, "w")
        self.process = subprocess.Popen([ROBOTD, "--config", config_path], stdout=self._log,
                                        stderr=subprocess.STDOUT)

    def log(self):
        with open(self.log_path) as log:
            return log.read()

    def wait_until_ready(self, timeout_s=10.0):
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"robotd exited with {self.process.returncode}:\n{self.log()}")
            if robotctl("--timeout-ms", "500", "devices", domain_id=self.domain_id).returncode == 0:
                return
            time.sleep(0.2)
        raise RuntimeError(f"robotctl devices did not succeed within {timeout_s} s:\n{self.log()}")

    def close(self):
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self._log.close()


def robotctl(*args, domain_id, timeout_s=20):
    return subprocess.run([ROBOTCTL, "--domain", str(domain_id), *args], capture_output=True, text=True,
                          timeout=timeout_s)


def start_robotctl(*args, domain_id):
    return subprocess.Popen([ROBOTCTL, "--domain", str(domain_id), *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


class RobotctlTest(unittest.TestCase):
    daemon = None
    workdir = None
    domain_lock = None

    @classmethod
    def setUpClass(cls):
        cls.domain_id, cls.domain_lock = claim_domain_id()
        cls.workdir = tempfile.TemporaryDirectory(prefix="robotctl-test-")
        try:
            cls.daemon = Robotd(cls.domain_id, cls.workdir.name)
            cls.daemon.wait_until_ready()
        except Exception:
            cls.tearDownClass()
            raise

    @classmethod
    def tearDownClass(cls):
        if cls.daemon:
            cls.daemon.close()
        cls.workdir.cleanup()
        cls.domain_lock.close()

    def robotctl(self, *args, timeout_s=20):
        return robotctl(*args, domain_id=self.domain_id, timeout_s=timeout_s)

    def start_robotctl(self, *args):
        process = start_robotctl(*args, domain_id=self.domain_id)
        self.addCleanup(stop_process, process)
        return process

    def assertSucceeded(self, result):
        self.assertEqual(result.returncode, 0, f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}")

    def acquire(self, *args):
        """Starts `robotctl acquire arm ARGS`; returns (process, uuid, public session id) once it holds the session."""
        process = self.start_robotctl("acquire", "arm", *args)
        line = read_line(process.stdout)
        match = re.match(r"uuid (\S+)  session ([0-9a-f]{8})  ", line)
        if not match:
            process.kill()
            self.fail(f"acquire printed {line!r}; stderr: {process.communicate()[1]}")
        return process, match.group(1), match.group(2)

    def poll_robotctl(self, *args, until, timeout_s=3.0):
        """Runs robotctl ARGS until its output satisfies `until` or the timeout passes; returns the last output.

        robotd publishes what these verbs show asynchronously: device status at 10 Hz, session
        status on each change (and every second)."""
        deadline = time.monotonic() + timeout_s
        while True:
            result = self.robotctl(*args)
            if until(result.stdout) or time.monotonic() > deadline:
                return result.stdout
            time.sleep(0.1)

    def test_devices_lists_arm_with_six_joints(self):
        result = self.robotctl("devices")
        self.assertSucceeded(result)
        arm_rows = [line.split() for line in result.stdout.splitlines() if line.startswith("arm ")]
        self.assertEqual(len(arm_rows), 1, result.stdout)
        self.assertIn(str(ARM_JOINTS), arm_rows[0])
        self.assertIn("RUNNING", arm_rows[0])
        self.assertIn("parol6", arm_rows[0])  # KINEMATIC MODEL

        devices = json.loads(self.robotctl("devices", "--json").stdout)
        self.assertEqual([device["name"] for device in devices], ["arm"])
        self.assertEqual(len(devices[0]["joint_names"]), ARM_JOINTS)
        self.assertEqual(devices[0]["kinematic_model"], "parol6")

    def test_status_shows_running_and_loop_stats(self):
        result = self.robotctl("status")
        self.assertSucceeded(result)
        self.assertRegex(result.stdout, r"(?m)^arm\s+RUNNING")
        self.assertRegex(result.stdout, r"wake\s+p50 [\d.]+\s+p99 [\d.]+\s+max [\d.]+ µs")
        self.assertRegex(result.stdout, r"execution\s+p50 [\d.]+\s+p99 [\d.]+\s+max [\d.]+ µs")
        self.assertRegex(result.stdout, r"\d+ ticks, \d+ overruns")
        self.assertIn("sessions", result.stdout)
        self.assertRegex(result.stdout, r"dds surface\n  commands\s+0 commands named no active session")
        self.assertRegex(result.stdout, r"requests\s+request_control \d+( \(\d+ refused\))?, release_control \d+")

        status = json.loads(self.robotctl("status", "--json").stdout)
        self.assertEqual(status["devices"][0]["state"], "RUNNING")
        self.assertGreater(status["devices"][0]["loop"]["ticks"], 0)
        services = [service["service"] for service in status["sessions"]["surface"]["services"]]
        self.assertEqual(services, ["request_control", "release_control", "get_available_motors", "reset_zero",
                                    "estop", "list_devices", "device_call"])

    def test_move_arrives_and_joint_states_show_the_target(self):
        target = [0.3, -0.2, 0.1, 0.0, 0.25, -0.1]
        tolerance = 0.02
        result = self.robotctl("move", "arm", "--to", ",".join(map(str, target)), "--speed", "1.0",
                               "--tolerance", str(tolerance))
        self.assertSucceeded(result)
        self.assertRegex(result.stdout, r"arrived in \d+\.\d\d s, max error [\d.]+ rad")

        echoed = self.robotctl("echo", "joint_states", "--count", "1", "--json")
        self.assertSucceeded(echoed)
        lines = echoed.stdout.splitlines()
        self.assertEqual(len(lines), 1, echoed.stdout)
        positions = json.loads(lines[0])["position"]
        for joint, (position, wanted) in enumerate(zip(positions, target)):
            self.assertAlmostEqual(position, wanted, delta=tolerance, msg=f"joint {joint}")

    def test_move_interrupted_releases_the_motors_and_exits_130(self):
        process = self.start_robotctl("move", "arm", "--to", "1,1,1,1,1,1", "--speed", "0.1")
        self.assertIn("moving", read_line(process.stderr))
        process.send_signal(signal.SIGINT)
        self.assertEqual(process.wait(timeout=10), 130)
        self.assertIn("no active sessions",
                      self.poll_robotctl("sessions", until=lambda out: "no active sessions" in out))

    def test_acquire_holds_a_session_that_release_by_uuid_ends(self):
        process, uuid, session_id = self.acquire("--motors", "0,1", "--timeout-ms", "500")
        sessions = self.poll_robotctl("sessions", until=lambda out: session_id in out)
        self.assertRegex(sessions, rf"{session_id}\s+robotctl\s+arm\s+0-1\s+POSITION")
        self.assertNotIn(uuid, sessions)
        self.assertNotIn(uuid, self.robotctl("sessions", "--json").stdout)

        by_id = self.robotctl("release", session_id)
        self.assertEqual(by_id.returncode, 1)
        self.assertIn("is the public id of a session of node 'robotctl'", by_id.stderr)
        released = self.robotctl("release", uuid)
        self.assertSucceeded(released)
        self.assertIn("released 2 motor(s)", released.stdout)
        # The holder notices robotd no longer lists its session, and says so.
        self.assertEqual(process.wait(timeout=10), 1)
        self.assertIn("has ended", process.stderr.read())
        self.assertNotIn(session_id, self.poll_robotctl("sessions", until=lambda out: session_id not in out))

    def test_second_acquire_on_the_same_motors_is_refused_naming_the_holder(self):
        holder, uuid, session_id = self.acquire("--motors", "2,3", "--node-name", "first-holder")
        refused = self.robotctl("acquire", "arm", "--motors", "3,4")
        self.assertEqual(refused.returncode, 1)
        self.assertIn("first-holder", refused.stderr)
        self.assertIn(f"session {session_id}", refused.stderr)
        self.assertNotIn(uuid, refused.stderr)

        holder.send_signal(signal.SIGINT)
        self.assertEqual(holder.wait(timeout=10), 0)
        self.assertIn("released 2 motor(s)", holder.stdout.read())

    def test_estop_refuses_moves_until_reset(self):
        self.addCleanup(self.robotctl, "estop", "--reset", "arm")
        self.assertSucceeded(self.robotctl("estop", "arm", "--reason", "robotctl test"))
        self.assertRegex(self.poll_robotctl("status", until=lambda out: "ESTOP" in out),
                         r"(?m)^arm\s+ESTOP.*robotctl test")

        refused = self.robotctl("move", "arm", "--to", "0,0,0,0,0,0")
        self.assertEqual(refused.returncode, 1)
        self.assertIn("e-stop", refused.stderr)

        self.assertSucceeded(self.robotctl("estop", "--reset", "arm"))
        self.assertRegex(self.poll_robotctl("status", until=lambda out: "RUNNING" in out), r"(?m)^arm\s+RUNNING")
        self.assertSucceeded(self.robotctl("move", "arm", "--to", "0,0,0,0,0,0", "--speed", "2.0"))

    def test_call_arm_state_returns_json(self):
        result = self.robotctl("call", "arm", "state")
        self.assertSucceeded(result)
        state = json.loads(result.stdout)
        self.assertEqual(len(state["joints"]), ARM_JOINTS)

    def test_call_with_an_unknown_op_fails(self):
        result = self.robotctl("call", "arm", "no_such_op")
        self.assertEqual(result.returncode, 1)
        self.assertIn("no_such_op", result.stderr)
        self.assertEqual(result.stdout, "")

    def test_top_once_prints_the_device(self):
        result = self.robotctl("top", "--once")
        self.assertSucceeded(result)
        self.assertRegex(result.stdout, r"(?m)^arm\s+RUNNING")
        self.assertNotIn("\x1b[", result.stdout)

    def test_no_robotd_on_the_domain_says_so_within_the_timeout(self):
        empty_domain_id, lock = claim_domain_id(taken={self.domain_id})
        self.addCleanup(lock.close)
        started = time.monotonic()
        result = robotctl("--timeout-ms", "1000", "devices", domain_id=empty_domain_id)
        elapsed_s = time.monotonic() - started
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"no robotd answers on DDS domain {empty_domain_id}", result.stderr)
        self.assertIn("is robotd running?", result.stderr)
        self.assertLess(elapsed_s, 5.0)

    def test_bad_arguments_exit_2(self):
        for args in (
            [],
            ["frobnicate"],
            ["move", "arm"],
            ["move", "arm", "--to", "0.1,0.2"],
            ["move", "arm", "--to", "9,0,0,0,0,0"],
            ["acquire", "arm", "--mode", "sideways"],
            ["acquire", "arm", "--motors", "3-1"],
            ["release"],
            ["echo", "no_such_topic"],
            ["echo", "policy_data", "--device", "arm"],
            ["record"],
            ["record", "run.rdrec", "--topics", "imu"],
            ["record", "run.rdrec", "--seconds", "0"],
            ["replay", "run.rdrec"],
            ["replay", "run.rdrec", "--device", "arm", "--speed", "0"],
            ["call", "arm", "state", "[1, 2]"],
            ["top", "--interval-ms", "0"],
        ):
            with self.subTest(args=args):
                result = self.robotctl(*args)
                self.assertEqual(result.returncode, 2, result.stderr)
                self.assertNotEqual(result.stderr.strip(), "")


def take_binaries(robotd, robotctl):
    global ROBOTD, ROBOTCTL
    ROBOTD, ROBOTCTL = robotd, robotctl


def main():
    run_tests(__doc__, take_binaries)


if __name__ == "__main__":
    main()
