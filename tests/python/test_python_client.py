"""The robotd Python package (clients/python) against a real robotd driving a simulated arm on a
DDS domain of its own. CTest runs each TestCase as python.<TestCase> (tests/python/CMakeLists.txt)
with PYTHONPATH, ROBOTD_C_LIBRARY, ROBOTD_BINARY, ROBOTD_ABI_LAYOUT and ROBOTD_PYTHON_EXAMPLE set."""
import json
import math
import os
import subprocess
import sys
import threading
import time
import unittest
from ctypes import sizeof
from pathlib import Path

import robotd
from robotd import _native

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from robotd_daemon import RobotdDaemon, sim_arm  # noqa: E402  (tests/support)
from test_domain import claim_domain_id  # noqa: E402

ROBOTD = os.environ.get("ROBOTD_BINARY", "")


class AbiLayoutTest(unittest.TestCase):
    """ctypes' structs are laid out exactly as the C compiler lays out robotd/robotd.h's."""

    def test_every_struct_and_field_matches_the_header(self):
        layout = json.loads(subprocess.run([os.environ["ROBOTD_ABI_LAYOUT"]], capture_output=True, text=True,
                                           check=True).stdout)
        mirrors = {"robotd_client_options": _native.ClientOptions, "robotd_device_info": _native.DeviceInfoStruct,
                   "robotd_session_request": _native.SessionRequest, "robotd_command": _native.Command,
                   "robotd_joint_state": _native.JointStateStruct,
                   "robotd_device_status": _native.DeviceStatusStruct, "robotd_tick_state": _native.TickStateStruct,
                   "robotd_session_info": _native.SessionInfoStruct, "robotd_move_options": _native.MoveOptions,
                   "robotd_move_report": _native.MoveReportStruct, "robotd_pose": _native.Pose,
                   "robotd_rbtscript_options": _native.RbtscriptOptions,
                   "robotd_rbtscript_problem": _native.RbtscriptProblemStruct,
                   "robotd_rbtscript_outcome": _native.RbtscriptOutcomeStruct}
        self.assertEqual(set(layout), set(mirrors))
        for name, mirror in mirrors.items():
            with self.subTest(struct=name):
                self.assertEqual(sizeof(mirror), layout[name]["size"])
                offsets = {field: getattr(mirror, field).offset for field, _ in mirror._fields_}
                self.assertEqual(offsets, layout[name]["fields"])


class WithoutRobotdTest(unittest.TestCase):
    """What a caller gets before anything reaches robotd."""

    def test_versions(self):
        self.assertEqual(robotd.C_API_VERSION, 5)
        self.assertRegex(robotd.__version__, r"^\d+\.\d+\.\d+$")

    def test_no_robotd_on_the_domain_is_not_available_and_says_what_to_check(self):
        domain_id, lock = claim_domain_id()
        with lock, robotd.Client(domain_id, service_timeout=0.3) as client:
            with self.assertRaises(robotd.NotAvailable) as raised:
                client.devices()
            self.assertIn("is robotd running", str(raised.exception))
            self.assertEqual(raised.exception.status, "ROBOTD_NOT_AVAILABLE")
            self.assertIsInstance(raised.exception, ConnectionError)

    def test_bad_arguments_name_what_is_wrong_and_what_is_expected(self):
        with self.assertRaises(robotd.InvalidArgument) as raised:
            robotd.Client(domain_id=500)
        self.assertIn("out of range", str(raised.exception))
        with self.assertRaisesRegex(ValueError, "'bogus' is not a Mode .*position, torque, mixed"):
            robotd.Session(device="arm", mode="bogus", client=object())
        with self.assertRaisesRegex(ValueError, "timeout is a duration in seconds"):
            robotd.Client(service_timeout=-1)


class ArmDaemonTestCase(unittest.TestCase):
    """One robotd with the simulated arm (planning with the PAROL6 model) and a client, per class."""

    @classmethod
    def setUpClass(cls):
        arm = sim_arm()
        arm["params"]["kinematic_model"] = "parol6"
        cls.daemon = RobotdDaemon(ROBOTD, [arm]).__enter__()
        cls.daemon.wait_until_serving()
        cls.client = robotd.Client(cls.daemon.domain_id, node_name="python_test")

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        cls.daemon.__exit__(None, None, None)


class ClientTest(ArmDaemonTestCase):
    """Sessions, commands, state, callbacks, safety and device operations, for real."""

    def test_devices_describe_the_arm_and_its_limits(self):
        [arm] = self.client.devices()
        self.assertEqual((arm.name, arm.driver, arm.state), ("arm", "sim", robotd.DeviceState.RUNNING))
        self.assertEqual(arm.kinematic_model, "parol6")
        self.assertEqual(arm.joint_names, ("joint1", "joint2", "joint3", "joint4", "joint5", "joint6"))
        self.assertEqual(len(arm.position_max), 6)
        self.assertTrue(all(low < high for low, high in zip(arm.position_min, arm.position_max)))
        self.assertEqual(arm.rate_hz, 1000)

    def test_joint_states_come_one_after_another(self):
        states = self.client.joint_states("arm")
        first, second = next(states), next(states)
        self.assertEqual(first.device, "arm")
        self.assertEqual(len(first.position), 6)
        self.assertGreater(second.stamp_ns, first.stamp_ns)

    def test_a_session_moves_its_motors_and_leaving_the_with_block_releases_them(self):
        start = self.client.joint_state("arm")
        target = (start.position[0] + 0.3, start.position[1] - 0.2)
        with self.client.session(device="arm", motors=[0, 1], timeout=0.5) as session:
            self.assertEqual(session.motors, (0, 1))
            self.assertEqual(session.mode, robotd.Mode.POSITION)
            self.assertRegex(session.uuid, r"^[0-9a-f-]{36}$")
            self.assertRegex(session.session_id, r"^[0-9a-f]{8}$")
            self.assertNotIn(session.session_id, session.uuid)
            self.assertNotIn(session.uuid, repr(session))
            deadline = time.monotonic() + 5
            while time.monotonic() < deadline:
                session.command(positions=target)
                state = self.client.joint_state("arm")
                if abs(state.position[0] - target[0]) < 0.01 and abs(state.position[1] - target[1]) < 0.01:
                    break
                time.sleep(0.01)
            self.assertAlmostEqual(state.position[0], target[0], delta=0.01)
            self.assertAlmostEqual(state.position[1], target[1], delta=0.01)
            self.assertAlmostEqual(state.position[2], start.position[2], delta=1e-6)
        # Released: the motors are free for the next session.
        with self.client.session(device="arm", motors=[0, 1]):
            pass

    def test_a_session_held_elsewhere_is_refused_naming_the_holder(self):
        with self.client.session(device="arm", motors=[2], timeout=2.0):
            with self.assertRaises(robotd.Refused) as raised:
                self.client.session(device="arm", motors=[2, 3])
        self.assertIn("motor(s) 2 held by node 'python_test'", str(raised.exception))

    def test_a_session_may_name_its_policy_within_the_limits(self):
        with self.client.session(device="arm", motors=[2], policy="walk", policy_file="walk_v3.onnx") as session:
            self.assertEqual(session.motors, (2,))
        with self.assertRaisesRegex(robotd.InvalidArgument, "request->policy_name is 256 bytes long"):
            self.client.session(device="arm", motors=[2], policy="p" * 256)

    def test_malformed_commands_raise_before_anything_is_sent(self):
        with self.client.session(device="arm", motors=[4, 5], timeout=1.0) as session:
            with self.assertRaisesRegex(ValueError, "positions: 1 values for 2 motors"):
                session.command(positions=[0.1])
            with self.assertRaisesRegex(TypeError, "positions: a sequence of numbers"):
                session.command(positions=0.1)
            session.release()
            with self.assertRaisesRegex(ValueError, "is closed|released"):
                session.command(positions=[0.0, 0.0])

    def test_a_silent_session_ends_at_its_timeout(self):
        session = self.client.session(device="arm", motors=[3], timeout=0.2, on_timeout="keep")
        time.sleep(0.6)
        with self.client.session(device="arm", motors=[3]):  # free again
            pass
        session.close()

    def test_a_session_without_a_client_connects_one_from_the_environment(self):
        os.environ["ROBOTD_DOMAIN_ID"] = str(self.daemon.domain_id)
        try:
            with robotd.Session(device="arm", motors=[5], timeout=0.5) as session:
                session.keepalive()
                self.assertEqual(session.device, "arm")
        finally:
            del os.environ["ROBOTD_DOMAIN_ID"]

    def test_callbacks_get_every_sample_until_cancelled(self):
        stamps, got_some = [], threading.Event()

        def on_state(state):
            stamps.append(state.stamp_ns)
            if len(stamps) >= 20:
                got_some.set()

        with self.client.on_joint_states(on_state) as subscription:
            self.assertTrue(got_some.wait(5), "no joint states reached the callback")
        self.assertFalse(subscription.active)
        count = len(stamps)
        time.sleep(0.1)
        self.assertEqual(len(stamps), count, "the callback ran after cancel()")
        self.assertEqual(stamps, sorted(stamps))

    def test_a_callback_that_raises_is_reported_and_the_subscription_goes_on(self):
        calls = []

        def failing(_state):
            calls.append(1)
            raise RuntimeError("a bug in the callback")

        with self.client.on_joint_states(failing):
            deadline = time.monotonic() + 5
            while len(calls) < 3 and time.monotonic() < deadline:
                time.sleep(0.01)
        self.assertGreaterEqual(len(calls), 3)

    def test_estop_latches_until_reset(self):
        reply = self.client.estop("arm", reason="python test")
        self.assertRegex(reply, r"^e-stop engaged by 'python_test'; reached 'arm' in \d+\.\d\d ms$")
        deadline = time.monotonic() + 3
        while self.client.device_status("arm").state != robotd.DeviceState.ESTOP and time.monotonic() < deadline:
            time.sleep(0.02)
        status = self.client.device_status("arm")
        self.assertEqual(status.state, robotd.DeviceState.ESTOP)
        self.assertTrue(status.estop_engaged)
        self.client.reset_estop("arm")
        deadline = time.monotonic() + 3
        while self.client.device_status("arm").state != robotd.DeviceState.RUNNING and time.monotonic() < deadline:
            time.sleep(0.02)
        self.assertEqual(self.client.device_status("arm").state, robotd.DeviceState.RUNNING)

    def test_device_status_reports_loop_timing_and_counters(self):
        status = self.client.device_status("arm")
        self.assertEqual(status.device, "arm")
        self.assertGreater(status.loop_period_p50_us, 500)
        self.assertLess(status.loop_period_p50_us, 1500)
        self.assertGreaterEqual(status.commands_accepted, 0)

    def test_device_call_returns_json_and_a_refusal_carries_the_drivers_words(self):
        state = self.client.call("arm", "state")
        self.assertEqual(len(state["joints"]), 6)
        with self.assertRaises(robotd.Refused) as raised:
            self.client.call("arm", "no_such_op", speed=1)
        self.assertIn('unknown op "no_such_op" (the sim driver has:', str(raised.exception))

    def test_release_by_uuid_frees_a_session_held_by_another_client(self):
        with robotd.Client(self.daemon.domain_id, node_name="other") as other:
            held = other.session(device="arm", motors=[1], timeout=5.0)
            with self.assertRaises(robotd.Refused) as raised:
                self.client.release(held.session_id, "keep")
            self.assertIn("is the public id of a session of node 'other'", str(raised.exception))
            self.client.release(held.uuid, "keep")
            with self.client.session(device="arm", motors=[1]):
                pass
            held.close()


class ClosedLoopTest(unittest.TestCase):
    """session.ticks() and session.answer() through a real robotd: a PD law closes the loop."""

    def test_a_pd_law_gets_newer_ticks_and_its_answers_move_the_arm_and_are_counted(self):
        with RobotdDaemon(ROBOTD, [sim_arm()]) as daemon, \
                robotd.Client(daemon.domain_id, node_name="python_test") as client:
            daemon.wait_until_serving()
            with client.session(device="arm", mode="torque", timeout=2.0, on_release="damping", closed_loop=True,
                                min_command_success_rate=0.5, on_low_success_rate="warn") as session:
                reference, ticks, settled = None, [], False
                for state in session.ticks(duration=30.0, state_timeout=5.0):
                    if reference is None:
                        reference = [q + 0.3 for q in state.position]
                    ticks.append(state.tick)
                    session.answer(state, torques=[20.0 * (r - q) - 1.0 * dq for r, q, dq in
                                                   zip(reference, state.position, state.velocity)])
                    errors = [abs(r - q) for r, q in zip(reference, state.position)]
                    if len(ticks) > 200 and max(errors) < 0.01 and abs(state.velocity[0]) < 0.05:
                        settled = True
                        break
                consecutive = sum(1 for a, b in zip(ticks, ticks[1:]) if b == a + 1)
                print(f"[ measured ] {len(ticks)} ticks, {consecutive} the one after the previous", file=sys.stderr)
                # Only the PD law's torques, answering the ticks, brought every joint to its reference.
                self.assertTrue(settled, daemon.log())
                self.assertEqual(ticks, sorted(set(ticks)))
                self.assertGreater(consecutive, 0)
                deadline = time.monotonic() + 10
                info = session.info()
                while info.ticks_answered_in_time + info.ticks_answered_late == 0 and time.monotonic() < deadline:
                    time.sleep(0.1)
                    info = session.info()
                self.assertTrue(info.closed_loop)
                self.assertGreater(info.ticks_answered_in_time + info.ticks_answered_late, 0)
                self.assertAlmostEqual(info.min_command_success_rate, 0.5)
                self.assertEqual(info.on_low_success_rate, robotd.LowRateAction.WARN)

    def test_ticks_end_when_robotd_ends_the_session(self):
        with RobotdDaemon(ROBOTD, [sim_arm()]) as daemon, \
                robotd.Client(daemon.domain_id, node_name="python_test") as client:
            daemon.wait_until_serving()
            with client.session(device="arm", mode="torque", timeout=0.5, closed_loop=True) as session:
                deadline = time.monotonic() + 10
                while time.monotonic() < deadline:  # kept alive until robotd is seen listing it
                    session.keepalive()
                    try:
                        session.info(timeout=0.1)
                        break
                    except robotd.Timeout:
                        pass
                # Not answered: robotd's 500 ms timeout ends the session, and with it the loop.
                count = sum(1 for _ in session.ticks(duration=30.0, state_timeout=5.0))
                self.assertGreater(count, 0)
                with self.assertRaises(robotd.Refused):
                    session.next_tick(timeout=1.0)


class PlannedMotionTest(ArmDaemonTestCase):
    """robotd.run_rbtscript and session.move_joints / move_cartesian: planned in this process on the
    test arm, which plans as a PAROL6, and streamed through a real robotd."""

    # Two postures clear of the PAROL6's singularities, and the tool poses its model puts them at
    # (kinematics::tool_pose and pose_of; as tests/c/c_api_test.c).
    POSTURE_A = (0.3, -1.4, 2.0, -0.4, 0.6, 0.8)
    POSTURE_B = (0.4, -1.3, 1.9, -0.3, 0.7, 0.9)
    POSE_A = (0.205354116, 0.069758867, 0.113302291, 2.473519361, 0.843256677, -3.140308032)
    POSE_B = (0.175020425, 0.090879026, 0.084637194, 2.104167985, 0.749339420, -3.030329488)
    PROGRAM_END = tuple(math.radians(d) for d in (10, -60, 100, 0, 20, 0))


    def assert_arm_at(self, target):
        position = self.client.joint_state("arm").position
        for joint, (q, expected) in enumerate(zip(position, target)):
            self.assertAlmostEqual(q, expected, delta=0.005, msg=f"joint {joint}")

    def test_a_dry_run_reports_a_problem_with_its_line_and_moves_nothing(self):
        start = self.client.joint_state("arm").position
        report = robotd.run_rbtscript(self.client, "Begin()\nMoveJoint(10,-60,100,0,20,0,t=2)\n"
                                      "MoveJoint(0,0,200,0,0,0)\nEnd()\n", device="arm", dry_run=True)
        self.assertEqual((report.device, report.syntax_errors, report.end), ("arm", False, robotd.RunEnd.NOT_RUN))
        self.assertEqual(report.moves_planned, 1)
        [problem] = report.problems
        self.assertEqual((problem.line, problem.column, problem.statement), (3, 1, "MoveJoint(0,0,200,0,0,0)"))
        self.assertTrue(str(problem).startswith("line 3, column 1: MoveJoint(0,0,200,0,0,0): "), str(problem))
        self.assert_arm_at(start)

    def test_a_syntax_error_names_its_line_and_what_was_expected(self):
        report = robotd.run_rbtscript(self.client, "Delay(1)\nMoveJoint(1,2\n")
        self.assertTrue(report.syntax_errors)
        [problem] = report.problems
        self.assertEqual(problem.line, 2)
        self.assertIn("expected", problem.message)
        with self.assertRaisesRegex(ValueError, "loops is 0: expected a number of passes"):
            robotd.run_rbtscript(self.client, "Delay(1)", loops=0)
        with self.assertRaisesRegex(robotd.InvalidArgument, "robotd has no device 'nowhere'"):
            robotd.run_rbtscript(self.client, "Delay(1)", device="nowhere")

    def test_a_program_runs_on_the_arm_statement_by_statement(self):
        seen = []
        report = robotd.run_rbtscript(self.client, "MoveJoint(10,-60,100,0,20,0,t=2)\nDelay(0.1)\nLoop()\n",
                                      loops=2, on_statement=lambda line, text, pass_number: seen.append(
                                          (line, pass_number)))
        self.assertEqual((report.end, report.passes, report.problems), (robotd.RunEnd.LOOP_LIMIT, 2, ()))
        self.assertEqual(seen[:3], [(1, 1), (2, 1), (3, 1)])
        self.assertIn((3, 2), seen)
        self.assert_arm_at(self.PROGRAM_END)

    def test_the_stop_event_ends_a_program_with_the_arm_held(self):
        robotd.run_rbtscript(self.client, "MoveJoint(10,-60,100,0,20,0,t=2)\n")
        stop = threading.Event()
        threading.Timer(0.3, stop.set).start()
        report = robotd.run_rbtscript(self.client, "Delay(30)\nMoveJoint(0,0,0,0,0,0)\n", stop=stop)
        self.assertEqual(report.end, robotd.RunEnd.STOPPED)
        self.assert_arm_at(self.PROGRAM_END)

    def test_joint_and_cartesian_moves_bring_the_arm_and_its_tool_to_their_goals(self):
        with self.client.session(device="arm", timeout=2.0) as session:
            report = session.move_joints(self.POSTURE_A, v=60, a=60)
            self.assertFalse(report.stopped)
            self.assertEqual(report.fraction_done, 1.0)
            self.assertIn("arrived", report.summary)
            self.assert_arm_at(self.POSTURE_A)
            session.move_cartesian(self.POSE_B, t=1.0)
            self.assert_arm_at(self.POSTURE_B)
            session.move_cartesian(self.POSE_A, t=1.0, func="trap", line=True)
            self.assert_arm_at(self.POSTURE_A)

    def test_move_arguments_are_checked_before_anything_moves(self):
        with self.client.session(device="arm", timeout=2.0) as session:
            with self.assertRaisesRegex(robotd.InvalidArgument, "2 joint value\\(s\\); device 'arm' has 6 joints"):
                session.move_joints([0.1, 0.2])
            with self.assertRaisesRegex(ValueError, "t is -1: expected seconds"):
                session.move_joints(self.POSTURE_A, t=-1)
            with self.assertRaisesRegex(ValueError, "'bogus' is not a Shape"):
                session.move_joints(self.POSTURE_A, func="bogus")
            with self.assertRaisesRegex(ValueError, "pose .*: 3 values, expected 6"):
                session.move_cartesian((0.2, 0.0, 0.1))
            with self.assertRaisesRegex(ValueError, "a straight line takes t and func only"):
                session.move_cartesian(self.POSE_A, v=50, line=True)
            with self.assertRaises(robotd.InvalidArgument):
                session.move_cartesian((2.0, 0.0, 0.3, 0.0, 0.0, 0.0))  # out of the PAROL6's reach


class ExampleTest(unittest.TestCase):
    """clients/python/examples/move_arm.py, the Python twin of the C++ example, against robotd."""

    def test_the_example_moves_every_joint_and_releases(self):
        with RobotdDaemon(ROBOTD, [sim_arm()]) as daemon:
            daemon.wait_until_serving()
            result = subprocess.run([sys.executable, os.environ["ROBOTD_PYTHON_EXAMPLE"]], capture_output=True,
                                    text=True, timeout=60,
                                    env=dict(os.environ, ROBOTD_DOMAIN_ID=str(daemon.domain_id)))
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr + daemon.log())
        self.assertRegex(result.stdout, r"session [0-9a-f]{8} on 6 motors")
        moves = [float(moved) for moved in
                 (line.split("->")[1].split()[0] for line in result.stdout.splitlines() if "->" in line)]
        self.assertEqual(len(moves), 6, result.stdout)
        self.assertTrue(all(abs(position - 0.5) < 0.02 for position in moves), result.stdout)
        self.assertIn("released", result.stdout)

    def test_the_pd_example_brings_every_joint_to_its_reference(self):
        example = Path(os.environ["ROBOTD_PYTHON_EXAMPLE"]).with_name("pd_control.py")
        with RobotdDaemon(ROBOTD, [sim_arm()]) as daemon:
            daemon.wait_until_serving()
            result = subprocess.run([sys.executable, str(example)], capture_output=True, text=True, timeout=60,
                                    env=dict(os.environ, ROBOTD_DOMAIN_ID=str(daemon.domain_id)))
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr + daemon.log())
        self.assertRegex(result.stdout, r"\d+ ticks answered \(ticks \d+\.\.\d+, \d+ skipped\)")
        joints = [line for line in result.stdout.splitlines() if line.startswith("joint ")]
        self.assertEqual(len(joints), 6, result.stdout)
        for line in joints:
            position, reference = float(line.split()[2]), float(line.split("reference ")[1].rstrip(")"))
            self.assertAlmostEqual(position, reference, delta=0.02, msg=result.stdout)
        self.assertIn("ticks answered in time (command success rate", result.stdout)


if __name__ == "__main__":
    unittest.main()
