"""The scripted RM_API2 session the generator records (run by generate.py, never by CI).

usage: sdk_session.py PORT PUSH_PORT SESSION   (PYTHONPATH = <RM_API2>/Python)

Drives a controller on 127.0.0.1:PORT with the vendor's Python package (Robotic_Arm, which loads
the vendor's prebuilt libapi_c.so) and prints one JSON line per call: the call, its arguments and
what the SDK returned. SESSION is "full" (3rd-generation controller: connect, queries, planned
moves, a movej_canfd stream, the gripper and the hand, the UDP push) or "connect" (connect and
the software info only, for the 4th generation).
"""

import json
import os
import sys
import time

from Robotic_Arm.rm_robot_interface import (RoboticArm, rm_realtime_arm_state_callback_ptr,
                                             rm_realtime_push_config_t, rm_thread_mode_e)


def plain(value):
    """What the SDK returned, as JSON (tuples → lists, ctypes leftovers → text)."""
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, float):
        return round(value, 6)
    if isinstance(value, (int, str, bool)) or value is None:
        return value
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="backslashreplace")
    return str(value)


def call(arm, name, *args):
    result = getattr(arm, name)(*args)
    print(json.dumps({"call": name, "args": plain(list(args)), "returned": plain(result)}), flush=True)
    return result


def connect(port):
    arm = RoboticArm(rm_thread_mode_e.RM_TRIPLE_MODE_E)
    handle = arm.rm_create_robot_arm("127.0.0.1", port, 3)
    print(json.dumps({"call": "rm_create_robot_arm", "args": ["127.0.0.1", "PORT"], "returned": {"id": handle.id}}),
          flush=True)
    if handle.id == -1:
        raise SystemExit("rm_create_robot_arm failed: the SDK did not accept the controller")
    return arm


def queries(arm):
    for name in ("rm_get_robot_info", "rm_get_arm_software_info", "rm_get_current_arm_state", "rm_get_joint_degree",
                 "rm_get_arm_all_state", "rm_get_controller_state", "rm_get_joint_en_state", "rm_get_joint_err_flag",
                 "rm_get_arm_power_state", "rm_get_joint_min_pos", "rm_get_joint_max_pos", "rm_get_joint_max_speed",
                 "rm_get_joint_max_acc", "rm_get_current_work_frame", "rm_get_current_tool_frame",
                 "rm_get_install_pose", "rm_get_DH_data", "rm_get_init_pose", "rm_get_arm_current_trajectory",
                 "rm_get_realtime_push", "rm_get_gripper_state"):
        call(arm, name)


def push(arm, push_port):
    """Points the UDP push at the SDK's own listener and counts what its callback parses."""
    received = []

    def on_state(state):
        if not received:
            parsed = state.to_dict()
            received.append(plain({key: parsed[key] for key in ("errCode", "joint_status", "err", "waypoint")}))

    callback = rm_realtime_arm_state_callback_ptr(on_state)
    arm.rm_realtime_arm_state_call_back(callback)
    call(arm, "rm_set_realtime_push", rm_realtime_push_config_t(1, True, push_port, 0, "127.0.0.1"))
    time.sleep(0.3)
    print(json.dumps({"call": "rm_realtime_arm_state_call_back", "args": [], "returned": received}), flush=True)
    return callback


def motion(arm):
    # A well-conditioned posture (the flange pointing down), 20 mm up in a line and back.
    call(arm, "rm_movej", [0, 30, 60, 0, 60, 0], 50, 0, 0, 1)
    _, state = call(arm, "rm_get_current_arm_state")
    pose = list(state["pose"])
    call(arm, "rm_movel", pose[:2] + [pose[2] + 0.02] + pose[3:], 20, 0, 0, 1)
    call(arm, "rm_movej_p", pose, 20, 0, 0, 1)
    call(arm, "rm_movej", [0, 0, 0, 0, 0, 0], 50, 0, 0, 1)
    call(arm, "rm_set_joint_step", 6, 5.0, 50, 1)
    call(arm, "rm_get_current_arm_state")


def stream(arm, speed_deg_s=31.0, period_s=0.01, duration_s=1.0):
    """movej_canfd at 100 Hz moving joint 1 at speed_deg_s, each frame sent on its deadline (the
    SDK sets TCP_NODELAY: each frame leaves on its own)."""
    _, state = arm.rm_get_current_arm_state()
    start = list(state["joint"][:6])
    frames = int(duration_s / period_s)
    begin = time.monotonic()
    results = set()
    for i in range(1, frames + 1):
        joints = list(start)
        joints[0] = start[0] + speed_deg_s * period_s * i
        results.add(arm.rm_movej_canfd(joints, True, 0, 0, 0))
        delay = begin + i * period_s - time.monotonic()
        if delay > 0:
            time.sleep(delay)
    print(json.dumps({"call": "rm_movej_canfd", "args": {"frames": frames, "period_s": period_s,
                                                         "joint1_speed_deg_s": speed_deg_s},
                      "returned": sorted(results)}), flush=True)
    time.sleep(0.2)
    call(arm, "rm_get_current_arm_state")


def gripper(arm):
    call(arm, "rm_set_gripper_route", 0, 1000)
    call(arm, "rm_set_gripper_pick", 500, 200, True, 5)
    call(arm, "rm_set_gripper_release", 500, True, 5)
    call(arm, "rm_set_gripper_pick_on", 500, 200, True, 5)
    call(arm, "rm_set_gripper_position", 800, True, 5)
    call(arm, "rm_get_gripper_state")


def hand(arm):
    call(arm, "rm_set_hand_speed", 800)
    call(arm, "rm_set_hand_force", 500)
    call(arm, "rm_set_hand_posture", 10, True, 5)
    call(arm, "rm_set_hand_angle", [1000, 900, 800, 700, 600, 500], True, 5)
    call(arm, "rm_set_hand_seq", 5, True, 5)


def main(port, push_port, session):
    arm = connect(port)
    call(arm, "rm_get_robot_info")
    call(arm, "rm_get_arm_software_info")
    if session == "full":
        queries(arm)
        keep_alive = push(arm, push_port)
        motion(arm)
        stream(arm)
        call(arm, "rm_clear_system_err")
        gripper(arm)
        hand(arm)
        del keep_alive
    call(arm, "rm_delete_robot_arm")
    sys.stdout.flush()
    os._exit(0)  # the SDK's receive threads never end by themselves


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]), sys.argv[3])
