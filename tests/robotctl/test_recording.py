#!/usr/bin/env python3
"""robotctl record and replay, and robotd.plot, against real robotds: simulated 6-joint arms, each
on a DDS domain of its own. The recordings are read with robotd.recording (clients/python).

    PYTHONPATH=clients/python test_recording.py --robotd build/bin/robotd --robotctl build/bin/robotctl \\
        [TestCase ...]

CTest runs each TestCase as robotctl.recording.<TestCase> (tests/robotctl/CMakeLists.txt).
"""
import bisect
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

from robotd import recording

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from cli_test import read_line, run_tests, stop_process  # noqa: E402  (tests/support)
from robotd_daemon import RobotdDaemon  # noqa: E402  (tests/support)

ROBOTD = ""
ROBOTCTL = ""
ARM_JOINTS = 6
# Peak joint speed of the recorded moves: at --speed 2 the replay stays well inside the arm's
# velocity and acceleration limits, so it can follow the recording.
RECORDED_SPEED_RAD_S = 0.6
FIRST_TARGET = [0.4, -0.3, 0.2, 0.0, 0.3, -0.1]
SECOND_TARGET = [-0.2, 0.3, 0.5, 0.2, 0.0, 0.1]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def arm(position_limit_rad=2.6, velocity_max_rad_s=2.0):
    """A simulated arm whose joints all have these limits."""
    return {
        "name": "arm", "driver": "sim", "rate_hz": 1000,
        # Tests need no real-time priority, and must not take the CPU from tests beside them.
        "realtime": "off", "limit_policy": "reject", "safe_behavior": "DAMPING", "shutdown_behavior": "DAMPING",
        "params": {
            "joint_count": ARM_JOINTS,
            "joint_defaults": {
                "position_min_rad": -position_limit_rad, "position_max_rad": position_limit_rad,
                "velocity_max_rad_s": velocity_max_rad_s, "acceleration_max_rad_s2": 8.0,
                "effort_max_nm": 40, "kp_max": 500, "kd_max": 50, "default_kp": 200, "default_kd": 8,
                "inertia_kg_m2": 0.05, "damping_nm_s_rad": 0.3,
            },
        },
    }


class Robotctl:
    """robotctl on one robotd's domain."""

    def __init__(self, domain_id):
        self.domain_id = domain_id

    def run(self, *args, timeout_s=30):
        return subprocess.run([ROBOTCTL, "--domain", str(self.domain_id), *args], capture_output=True, text=True,
                              timeout=timeout_s)

    def start(self, *args):
        return subprocess.Popen([ROBOTCTL, "--domain", str(self.domain_id), *args], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)

    def start_recording(self, path, *args):
        """robotctl record PATH ARGS, once it has subscribed."""
        recorder = self.start("record", str(path), *args)
        line = read_line(recorder.stderr)
        if not line.startswith("recording "):
            stop_process(recorder)
            raise AssertionError(f"robotctl record printed {line!r}")
        time.sleep(0.3)  # its readers match robotd's writers
        return recorder

    def stop_recording(self, recorder):
        """Ends robotctl record with Ctrl-C; returns its summary line."""
        recorder.send_signal(signal.SIGINT)
        stdout, stderr = recorder.communicate(timeout=10)
        if recorder.returncode != 0:
            raise AssertionError(f"robotctl record exited {recorder.returncode}: {stderr}")
        return stdout.strip()

    def move(self, target, speed_rad_s=RECORDED_SPEED_RAD_S):
        result = self.run("move", "arm", "--to", ",".join(map(str, target)), "--speed", str(speed_rad_s))
        if result.returncode != 0:
            raise AssertionError(f"robotctl move exited {result.returncode}: {result.stdout}{result.stderr}")

    def poll(self, *args, until, timeout_s=3.0):
        """Whether robotctl ARGS prints what satisfies `until` within the timeout (robotd publishes
        /session_status on each change, asynchronously)."""
        deadline = time.monotonic() + timeout_s
        while not until(self.run(*args).stdout):
            if time.monotonic() > deadline:
                return False
            time.sleep(0.1)
        return True

    def joint_positions(self):
        result = self.run("echo", "joint_states", "--device", "arm", "--count", "1", "--json")
        return json.loads(result.stdout)["position"]

    def record_moves(self, path, *targets):
        """Records robotctl moving the arm through `targets`; returns record's summary line."""
        recorder = self.start_recording(path)
        try:
            for target in targets:
                self.move(target)
            time.sleep(0.3)
            return self.stop_recording(recorder)
        finally:
            stop_process(recorder)


class RobotdTestCase(unittest.TestCase):
    """A robotd with an arm(**arm_limits), and a temporary directory, for the whole TestCase."""
    arm_limits = {}

    @classmethod
    def setUpClass(cls):
        cls.directory = tempfile.TemporaryDirectory(prefix="robotctl-recording-test-")
        cls.daemon = RobotdDaemon(ROBOTD, [arm(**cls.arm_limits)]).__enter__()
        try:
            cls.daemon.wait_until_serving()
            cls.robotctl = Robotctl(cls.daemon.domain_id)
            cls.robotctl.move([0.0] * ARM_JOINTS, speed_rad_s=2.0)
        except Exception:
            cls.tearDownClass()
            raise

    @classmethod
    def tearDownClass(cls):
        cls.daemon.__exit__(None, None, None)
        cls.directory.cleanup()

    @classmethod
    def path(cls, name):
        return Path(cls.directory.name) / name

    def assertSucceeded(self, result):
        self.assertEqual(result.returncode, 0, f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}")


class RecordTest(RobotdTestCase):
    """robotctl record while robotctl move streams a known move, read back with robotd.recording."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.recorded = cls.path("move.rdrec")
        cls.summary = cls.robotctl.record_moves(cls.recorded, FIRST_TARGET)
        cls.contents = recording.read(cls.recorded)

    def test_summary_gives_duration_size_and_records_per_topic(self):
        match = re.fullmatch(r"recorded ([\d.]+) s to (\S+) \((\d+) bytes\): joint_states (\d+), control_command "
                             r"(\d+), session_status (\d+), device_status (\d+)", self.summary)
        self.assertTrue(match, self.summary)
        seconds, path, size, states, commands, sessions, statuses = match.groups()
        self.assertEqual(path, str(self.recorded))
        self.assertEqual(int(size), os.path.getsize(self.recorded))
        self.assertEqual(int(states), len(self.contents.joint_states))
        self.assertEqual(int(commands), len(self.contents.commands))
        self.assertEqual(int(sessions), len(self.contents.session_status))
        self.assertEqual(int(statuses), len(self.contents.device_status))
        self.assertGreater(float(seconds), 1.0)

    def test_header_describes_the_arm_with_its_joint_names_and_limits(self):
        devices = json.loads(self.robotctl.run("devices", "--json").stdout)
        self.assertTrue(self.contents.closed)
        self.assertEqual(self.contents.problems, [])
        self.assertEqual(self.contents.version[0], recording.MAJOR_VERSION)
        self.assertEqual(self.contents.description["topics"],
                         ["joint_states", "control_command", "session_status", "device_status"])
        self.assertEqual(self.contents.description["domain_id"], self.daemon.domain_id)
        arm_device = self.contents.device("arm")
        self.assertEqual(list(arm_device.joint_names), devices[0]["joint_names"])
        self.assertEqual(arm_device.position_max, (2.6,) * ARM_JOINTS)
        self.assertEqual(arm_device.velocity_max, (2.0,) * ARM_JOINTS)
        self.assertAlmostEqual(self.contents.start_time_ns * 1e-9, time.time(), delta=120)

    def test_joint_states_arrive_in_time_order_and_end_at_the_target(self):
        states = self.contents.joint_states
        self.assertGreater(len(states), 500)  # robotd publishes /joint_states at its loop rate
        self.assertTrue(all(state.device == "arm" for state in states))
        self.assertTrue(all(len(state.position) == ARM_JOINTS for state in states))
        receive_times = [state.time_ns for state in states]
        self.assertEqual(receive_times, sorted(receive_times))
        stamps = [state.stamp_ns for state in states]
        self.assertTrue(all(later > earlier for earlier, later in zip(stamps, stamps[1:])), "robotd's stamps")
        for joint, (position, target) in enumerate(zip(states[-1].position, FIRST_TARGET)):
            self.assertAlmostEqual(position, target, delta=0.03, msg=f"joint {joint}")

    def test_commands_are_the_moves_position_commands(self):
        commands = [command for command in self.contents.commands if command.positions]
        self.assertGreater(len(commands), 50)  # robotctl move streams at 100 Hz
        receive_times = [command.time_ns for command in commands]
        self.assertEqual(receive_times, sorted(receive_times))
        self.assertTrue(all(command.device == "arm" for command in commands))
        self.assertTrue(all(command.motor_ids == tuple(range(ARM_JOINTS)) for command in commands))
        self.assertRegex(commands[0].session, r"^[0-9a-f]{8}$")
        for joint, (position, target) in enumerate(zip(commands[-1].positions, FIRST_TARGET)):
            self.assertAlmostEqual(position, target, delta=1e-6, msg=f"joint {joint}")
        # The status names the session by its public id, which tells nothing of the uuid the
        # commands carry (their tag is its first 8 hex digits).
        ids = [session["uuid"] for status in self.contents.session_status for session in status.message["sessions"]]
        self.assertTrue(ids)
        self.assertTrue(all(re.fullmatch(r"[0-9a-f]{8}", session_id) for session_id in ids), ids)
        self.assertNotIn(commands[0].session, ids)

    def test_truncated_file_reads_up_to_the_last_complete_record(self):
        truncated = self.path("truncated.rdrec")
        shutil.copy(self.recorded, truncated)
        # The end record is 13 bytes: cut 20 more, inside the last sample.
        os.truncate(truncated, os.path.getsize(truncated) - 33)
        run = recording.read(truncated)
        complete = len(run.joint_states) + len(run.commands) + len(run.session_status) + len(run.device_status)
        recorded = (len(self.contents.joint_states) + len(self.contents.commands) + len(self.contents.session_status)
                    + len(self.contents.device_status))
        self.assertEqual(complete, recorded - 1)
        self.assertFalse(run.closed)
        self.assertEqual(len(run.problems), 1)
        self.assertIn("is cut short", run.problems[0])

    def test_record_killed_leaves_every_flushed_record_readable(self):
        killed = self.path("killed.rdrec")
        recorder = self.robotctl.start_recording(killed, "--topics", "joint_states")
        time.sleep(1.0)
        recorder.kill()
        stop_process(recorder)
        run = recording.read(killed)
        self.assertGreater(len(run.joint_states), 100)
        self.assertFalse(run.closed)
        self.assertRegex(run.problems[0], "no end record|is cut short")

    def test_seconds_topics_and_device_choose_what_is_recorded(self):
        path = self.path("states.rdrec")
        started = time.monotonic()
        result = self.robotctl.run("record", str(path), "--seconds", "0.5", "--topics", "/joint_states",
                                   "--device", "arm")
        self.assertSucceeded(result)
        self.assertLess(time.monotonic() - started, 5.0)
        run = recording.read(path)
        self.assertEqual(run.description["topics"], ["joint_states"])
        self.assertEqual([device.name for device in run.devices], ["arm"])
        self.assertGreater(len(run.joint_states), 100)
        self.assertEqual((run.commands, run.session_status, run.device_status), ([], [], []))
        self.assertLessEqual(run.duration_ns, 1.5e9)

    def test_record_refuses_unknown_device_and_unwritable_file(self):
        unknown = self.robotctl.run("record", str(self.path("x.rdrec")), "--device", "gripper", "--seconds", "1")
        self.assertEqual(unknown.returncode, 1)
        self.assertIn("unknown device 'gripper'", unknown.stderr)
        unwritable = self.robotctl.run("record", "/nonexistent/x.rdrec", "--seconds", "1")
        self.assertEqual(unwritable.returncode, 1)
        self.assertIn("cannot create /nonexistent/x.rdrec: No such file or directory", unwritable.stderr)

    def test_dry_run_within_the_limits_reports_each_motor_and_passes(self):
        result = self.robotctl.run("replay", str(self.recorded), "--device", "arm", "--dry-run", "--speed", "2")
        self.assertSucceeded(result)
        self.assertRegex(result.stdout, r"position commands for motors 0-5 of 'arm' over [\d.]+ s, paced by the "
                                        r"senders' stamps")
        self.assertRegex(result.stdout, r"replay at speed 2\.00: [\d.]+ s")
        self.assertIn("check: every command is within the current limits of 'arm'", result.stdout)
        rows = [line.split() for line in result.stdout.splitlines() if re.match(r"^\d\s", line)]
        self.assertEqual([int(row[0]) for row in rows], list(range(ARM_JOINTS)))
        # motor 0 moved 0.4 rad at 0.6 rad/s peak: 1.2 rad/s at speed 2, against 2.00.
        self.assertAlmostEqual(float(rows[0][3]), 2 * RECORDED_SPEED_RAD_S, delta=0.2)
        self.assertEqual(rows[0][4], "2.00")

    def test_replay_says_what_is_wrong_with_a_file_it_cannot_replay(self):
        text_file = self.path("samples.jsonl")
        text_file.write_text('{"position": [0.1]}\n')
        newer = self.path("newer.rdrec")
        data = bytearray(self.recorded.read_bytes())
        data[8] = 2  # format version 2.0
        newer.write_bytes(bytes(data))
        states_only = self.path("states-only.rdrec")
        self.assertSucceeded(self.robotctl.run("record", str(states_only), "--seconds", "0.3", "--topics",
                                               "joint_states"))
        for path, device, expected in (
                (text_file, "arm", "is not a robotd recording"),
                (newer, "arm", "is a robotd recording of format version 2.0; this robotctl reads version 1.x"),
                (self.recorded, "gripper", "recorded no device 'gripper' (it recorded 'arm')"),
                (states_only, "arm", "has no position commands for 'arm'"),
                (self.path("missing.rdrec"), "arm", "cannot be opened")):
            with self.subTest(path=path.name, device=device):
                result = self.robotctl.run("replay", str(path), "--device", device, "--dry-run")
                self.assertEqual(result.returncode, 1, result.stdout)
                self.assertIn(expected, result.stderr)


class ReplayTest(RobotdTestCase):
    """robotctl replay moves the arm along the recorded trajectory, at the recorded pace times --speed."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.recorded = cls.path("moves.rdrec")
        cls.robotctl.record_moves(cls.recorded, FIRST_TARGET, SECOND_TARGET)
        cls.contents = recording.read(cls.recorded)
        commands = [command for command in cls.contents.commands if command.positions]
        cls.recorded_s = (commands[-1].stamp_ns - commands[0].stamp_ns) * 1e-9  # replay's pace

    def replay_and_record(self, name, *args):
        """Moves the arm away, replays the recording while recording that; returns (replay result, recording)."""
        self.robotctl.move([0.1] * ARM_JOINTS, speed_rad_s=2.0)
        path = self.path(name)
        recorder = self.robotctl.start_recording(path, "--topics", "joint_states,control_command")
        try:
            result = self.robotctl.run("replay", str(self.recorded), "--device", "arm", *args)
            self.robotctl.stop_recording(recorder)
        finally:
            stop_process(recorder)
        self.assertSucceeded(result)
        return result, recording.read(path)

    def assertFollows(self, replayed, speed, tolerance_rad):
        """The replayed joint states match the recorded ones at the recorded pace divided by `speed`,
        counted from a command sent in mid-move (the replay sends the recorded values). Times are
        the stamps of the senders and of robotd (one clock on one machine), which the recorder
        being busy does not shift."""
        recorded_commands = [command for command in self.contents.commands if command.positions]
        start = recorded_commands[0].positions
        anchor = next(command for command in recorded_commands
                      if max(abs(a - b) for a, b in zip(command.positions, start)) > 0.1)
        replayed_anchor = next((command for command in replayed.commands if command.positions == anchor.positions),
                               None)
        self.assertIsNotNone(replayed_anchor, "the replay did not send the recorded commands")
        replayed_stamps = [state.stamp_ns for state in replayed.joint_states]
        compared, worst = 0, 0.0
        for state in self.contents.joint_states[::5]:
            if state.stamp_ns < recorded_commands[0].stamp_ns:
                continue
            at_ns = replayed_anchor.stamp_ns + (state.stamp_ns - anchor.stamp_ns) / speed
            position = position_at(replayed.joint_states, replayed_stamps, at_ns)
            if position is not None:
                compared += 1
                worst = max(worst, max(abs(a - b) for a, b in zip(position, state.position)))
        self.assertGreater(compared, 300)
        self.assertLess(worst, tolerance_rad)

    def test_replay_follows_the_recorded_trajectory(self):
        result, replayed = self.replay_and_record("replayed.rdrec")
        self.assertRegex(result.stdout, r"replayed \d+ commands in [\d.]+ s, max error at the end [\d.]+ rad")
        self.assertIn("moving to the recording's first positions", result.stderr)
        self.assertFollows(replayed, 1.0, tolerance_rad=0.05)
        for joint, (position, target) in enumerate(zip(replayed.joint_states[-1].position, SECOND_TARGET)):
            self.assertAlmostEqual(position, target, delta=0.03, msg=f"joint {joint}")

    def test_speed_2_takes_about_half_the_time(self):
        normal = replay_seconds(self.replay_and_record("speed1.rdrec")[0])
        result, replayed = self.replay_and_record("speed2.rdrec", "--speed", "2")
        fast = replay_seconds(result)
        self.assertAlmostEqual(normal, self.recorded_s, delta=0.3)
        self.assertAlmostEqual(fast / normal, 0.5, delta=0.1)
        # A time offset between the two recordings costs position error in proportion to the
        # joints' speed: at twice the speed, twice the tolerance.
        self.assertFollows(replayed, 2.0, tolerance_rad=0.1)

    def test_ctrl_c_releases_the_motors_and_exits_130(self):
        replay = self.robotctl.start("replay", str(self.recorded), "--device", "arm", "--speed", "0.1")
        try:
            deadline = time.monotonic() + 15
            while "replaying" not in read_line(replay.stderr) and time.monotonic() < deadline:
                pass
            time.sleep(0.3)
            replay.send_signal(signal.SIGINT)
            self.assertEqual(replay.wait(timeout=10), 130)
            self.assertRegex(replay.stderr.read(), r"interrupted after \d+ of \d+ commands; released 6 motor")
        finally:
            stop_process(replay)
        self.assertTrue(self.robotctl.poll("sessions", until=lambda out: "no active sessions" in out))

    def test_motors_held_by_another_session_are_refused_naming_the_holder(self):
        holder = self.robotctl.start("acquire", "arm", "--motors", "2", "--node-name", "other-holder")
        try:
            self.assertTrue(read_line(holder.stdout).startswith("uuid "))
            result = self.robotctl.run("replay", str(self.recorded), "--device", "arm")
            self.assertEqual(result.returncode, 1)
            self.assertIn("other-holder", result.stderr)
            holder.send_signal(signal.SIGINT)
            self.assertEqual(holder.wait(timeout=10), 0)
        finally:
            stop_process(holder)


class ReplayLimitsTest(RobotdTestCase):
    """A recording made on an arm with wide limits, replayed against one with narrow limits:
    refused before anything moves, with every violation listed."""
    arm_limits = {"position_limit_rad": 0.35, "velocity_max_rad_s": 0.3}

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.recorded = cls.path("wide.rdrec")
        with RobotdDaemon(ROBOTD, [arm()]) as wide:
            wide.wait_until_serving()
            wide_robotctl = Robotctl(wide.domain_id)
            wide_robotctl.move([0.0] * ARM_JOINTS, speed_rad_s=2.0)
            wide_robotctl.record_moves(cls.recorded, FIRST_TARGET)

    def test_dry_run_lists_every_violation_with_joint_time_value_and_limit(self):
        result = self.robotctl.run("replay", str(self.recorded), "--device", "arm", "--dry-run")
        self.assertEqual(result.returncode, 1, result.stdout)
        self.assertIn("replay refused", result.stderr)
        self.assertIn("nothing moved", result.stderr)
        violations = [line.strip() for line in result.stdout.splitlines() if line.startswith("  motor ")]
        # Joint 0 goes to 0.4 rad (max 0.35), joint 1 to -0.3 (within); every joint that moves
        # more than 0.3 rad in ~1.2 s goes faster than 0.3 rad/s at its peak.
        self.assertRegex(result.stdout, r"\d+ violation\(s\) of the current limits of 'arm'")
        position = [v for v in violations if v.startswith("motor 0 ") and "position" in v]
        self.assertEqual(len(position), 1, violations)
        self.assertRegex(position[0], r"^motor 0 \(\S+\): position 0\.35\d rad is beyond its maximum 0\.350 rad at "
                                      r"t=[\d.]+ s \(worst 0\.400 rad at t=[\d.]+ s; \d+ commands until t=[\d.]+ s\)$")
        velocity = [v for v in violations if v.startswith("motor 0 ") and "velocity" in v]
        self.assertTrue(velocity, violations)
        self.assertIn("is beyond its velocity_max 0.300 rad/s", velocity[0])
        self.assertFalse([v for v in violations if v.startswith("motor 3 ")], "joint 3 does not move")

    def test_replay_refuses_and_the_arm_does_not_move(self):
        before = self.robotctl.joint_positions()
        result = self.robotctl.run("replay", str(self.recorded), "--device", "arm")
        self.assertEqual(result.returncode, 1, result.stdout)
        self.assertIn("replay refused", result.stderr)
        self.assertNotIn("moving to", result.stderr)
        after = self.robotctl.joint_positions()
        for joint, (a, b) in enumerate(zip(before, after)):
            self.assertAlmostEqual(a, b, delta=1e-3, msg=f"joint {joint}")

    def test_motors_option_limits_the_check_to_those_motors(self):
        result = self.robotctl.run("replay", str(self.recorded), "--device", "arm", "--dry-run", "--motors", "3")
        self.assertSucceeded(result)
        self.assertIn("position commands for motors 3 of 'arm'", result.stdout)


class PlotTest(RobotdTestCase):
    """python3 -m robotd.plot renders a recording's joint trajectories to a PNG."""

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.recorded = cls.path("plot.rdrec")
        cls.robotctl.record_moves(cls.recorded, FIRST_TARGET)

    def plot(self, *args):
        return subprocess.run([sys.executable, "-m", "robotd.plot", *map(str, args)], capture_output=True, text=True,
                              timeout=120)

    def test_plot_writes_a_png_of_every_joint(self):
        image = self.path("plot.png")
        result = self.plot(self.recorded, "-o", image, "--device", "arm")
        self.assertSucceeded(result)
        self.assertRegex(result.stdout, rf"wrote {re.escape(str(image))}: {ARM_JOINTS} joints of 'arm' over [\d.]+ s")
        data = image.read_bytes()
        self.assertEqual(data[:8], PNG_SIGNATURE)
        self.assertGreater(len(data), 20_000)

    def test_plot_says_what_is_wrong(self):
        not_a_recording = self.path("not.rdrec")
        not_a_recording.write_text("hello\n")
        for args, expected in (((self.recorded, "-o", self.path("x.png"), "--device", "gripper"),
                                "recorded no device 'gripper'"),
                               ((not_a_recording, "-o", self.path("x.png")), "is not a robotd recording")):
            with self.subTest(expected=expected):
                result = self.plot(*args)
                self.assertEqual(result.returncode, 1)
                self.assertIn(expected, result.stderr)


def position_at(states, times, time_ns):
    """Positions at `time_ns` on `times` (one per state, ascending), linearly interpolated; None
    outside them."""
    index = bisect.bisect_left(times, time_ns)
    if index == 0 or index >= len(states):
        return None
    share = (time_ns - times[index - 1]) / max(times[index] - times[index - 1], 1)
    return [a + (b - a) * share for a, b in zip(states[index - 1].position, states[index].position)]


def replay_seconds(result):
    return float(re.search(r"replayed \d+ commands in ([\d.]+) s", result.stdout).group(1))


def take_binaries(robotd, robotctl):
    global ROBOTD, ROBOTCTL
    ROBOTD, ROBOTCTL = robotd, robotctl


def main():
    run_tests(__doc__, take_binaries)


if __name__ == "__main__":
    main()
