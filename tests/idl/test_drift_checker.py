#!/usr/bin/env python3
"""check_ros2_matches_idl.py fails on every kind of drift between the IDL and the ROS package.

Each test copies idl/*.idl and idl/ros2/robotd_msgs into a temporary directory, changes one
thing in the copy and runs the checker on it, the way CTest runs it on the real files.
"""

import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
CHECKER = Path(__file__).resolve().parent / "check_ros2_matches_idl.py"


class DriftCheckerTest(unittest.TestCase):
    def setUp(self):
        self.scratch = Path(tempfile.mkdtemp(prefix="robotd_idl_drift_"))
        self.addCleanup(shutil.rmtree, self.scratch)
        self.idl_dir = self.scratch / "idl"
        self.idl_dir.mkdir()
        for name in ("ros_common.idl", "robotd_msgs.idl"):
            shutil.copy(REPO / "idl" / name, self.idl_dir / name)
        self.package = self.scratch / "robotd_msgs"
        shutil.copytree(REPO / "idl" / "ros2" / "robotd_msgs", self.package)

    # helpers

    def run_checker(self):
        return subprocess.run(
            [sys.executable, str(CHECKER), "--idl-dir", str(self.idl_dir), "--package-dir", str(self.package)],
            capture_output=True, text=True, check=False, timeout=60)

    def edit(self, relative_path, old, new):
        """Replaces `old` (which must occur exactly once, so a mutation never silently misses)."""
        path = self.scratch / relative_path
        text = path.read_text(encoding="utf-8")
        self.assertEqual(text.count(old), 1, f"{old!r} should occur once in {relative_path}")
        path.write_text(text.replace(old, new), encoding="utf-8")

    def assert_drift(self, *expected_text):
        result = self.run_checker()
        self.assertEqual(result.returncode, 1, f"checker should report drift\n{result.stdout}{result.stderr}")
        for text in expected_text:
            self.assertIn(text, result.stderr)
        return result.stderr

    # the unmodified copy

    def test_unmodified_copy_passes(self):
        result = self.run_checker()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("OK", result.stdout)

    def test_constants_and_comments_are_not_compared(self):
        self.edit("robotd_msgs/msg/ControlCommand.msg", "string uuid             # session uuid",
                  "int32 NEW_CONSTANT=7  # a constant is not on the wire\n"
                  "string uuid  # a different comment")
        self.assertEqual(self.run_checker().returncode, 0)

    # drift in the ROS package

    def test_swapped_fields_fail(self):
        self.edit("robotd_msgs/msg/ControlCommand.msg", "float32[] positions     # target positions, rad\n"
                  "float32[] velocities    # target velocities, rad/s\n",
                  "float32[] velocities    # target velocities, rad/s\n"
                  "float32[] positions     # target positions, rad\n")
        self.assert_drift("robotd_msgs/msg/ControlCommand: fields differ",
                          "field 4: IDL `float32[] positions`, ROS `float32[] velocities`")

    def test_changed_type_fails(self):
        self.edit("robotd_msgs/msg/ControlCommand.msg", "float32[] kp ", "float64[] kp ")
        self.assert_drift("robotd_msgs/msg/ControlCommand", "-float32[] kp", "+float64[] kp")

    def test_dropped_field_fails(self):
        self.edit("robotd_msgs/msg/ControlCommand.msg", "string device           # target device;",
                  "# string device removed;")
        self.assert_drift("11 in the IDL, 10 in ROS", "-string device")

    def test_added_field_fails(self):
        self.edit("robotd_msgs/msg/SessionInfo.msg", "uint64 commands_accepted",
                  "float32 extra_gain\nuint64 commands_accepted")
        self.assert_drift("robotd_msgs/msg/SessionInfo", "+float32 extra_gain")

    def test_renamed_field_fails(self):
        self.edit("robotd_msgs/srv/ResetZero.srv", "int32 timeout_ms", "int32 timeout")
        self.assert_drift("robotd_msgs/srv/ResetZero request", "-int32 timeout_ms", "+int32 timeout")

    def test_drift_in_a_service_response_fails(self):
        self.edit("robotd_msgs/srv/GetAvailableMotors.srv", "bool success ", "int32 success ")
        self.assert_drift("robotd_msgs/srv/GetAvailableMotors response", "+int32 success")

    def test_deleted_msg_file_fails(self):
        (self.package / "msg" / "KeyValue.msg").unlink()
        self.assert_drift("robotd_msgs::msg::dds_::KeyValue_", "no ROS counterpart", "msg/KeyValue.msg")

    def test_interface_without_idl_struct_fails(self):
        (self.package / "msg" / "Extra.msg").write_text("int32 value  # no IDL struct\n", encoding="ascii")
        self.assert_drift("robotd_msgs/msg/Extra", "no IDL struct robotd_msgs::msg::dds_::Extra_")

    def test_file_missing_from_rosidl_generate_interfaces_fails(self):
        self.edit("robotd_msgs/CMakeLists.txt", '  "msg/KeyValue.msg"\n', "")
        self.assert_drift("does not list msg/KeyValue.msg")

    def test_missing_package_dependency_fails(self):
        self.edit("robotd_msgs/package.xml", "<depend>builtin_interfaces</depend>", "")
        self.assert_drift("fields use builtin_interfaces")

    def test_non_ascii_comment_fails(self):
        self.edit("robotd_msgs/msg/ControlCommand.msg", "torques, N*m", "torques, N\u00b7m")
        self.assert_drift("ControlCommand.msg:12: non-ASCII")

    def test_field_name_breaking_rosidl_rules_fails(self):
        self.edit("robotd_msgs/msg/KeyValue.msg", "string key ", "string Key ")
        self.edit("idl/robotd_msgs.idl", "string key;", "string Key;")
        self.assert_drift("field name 'Key' breaks the rosidl rule")

    # drift in the IDL

    def test_removed_service_header_fails(self):
        self.edit("idl/robotd_msgs.idl", "  struct RequestControl_Request_ {\n    uint64 client_guid;\n"
                  "    int64 sequence_number;\n", "  struct RequestControl_Request_ {\n")
        self.assert_drift("robotd_msgs::srv::dds_::RequestControl_Request_",
                          "must start with the rmw_cyclonedds request header")

    def test_member_added_to_idl_only_fails(self):
        self.edit("idl/robotd_msgs.idl", "    string args_json;\n", "    string args_json;\n    double deadline_s;\n")
        self.assert_drift("robotd_msgs/srv/DeviceCall request", "-float64 deadline_s")

    def test_idl_struct_without_ros_file_fails(self):
        self.edit("idl/robotd_msgs.idl", "  struct KeyValue_ {", "  struct Orphan_ {\n    int32 a;\n  };\n  struct KeyValue_ {")
        self.assert_drift("robotd_msgs::msg::dds_::Orphan_", "expected msg/Orphan.msg")

    def test_standard_type_drift_fails(self):
        self.edit("idl/ros_common.idl", "    sequence<double> position;", "    sequence<float> position;")
        self.assert_drift("sensor_msgs/msg/JointState", "-float32[] position")

    def test_unparsable_idl_is_an_error_not_a_pass(self):
        self.edit("idl/robotd_msgs.idl", "  struct KeyValue_ {", "  union KeyValue_ {")
        result = self.run_checker()
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn("robotd_msgs.idl", result.stderr)


if __name__ == "__main__":
    unittest.main()
