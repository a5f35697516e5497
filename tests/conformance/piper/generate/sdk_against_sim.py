#!/usr/bin/env python3
"""Drives robotd-piper-sim with the vendor's PiPER SDK over python-can (standin_bus.py) and
records what happened: each step's SDK calls with the frames they put on the bus, and what the
SDK's getters then reported. CI replays the frames against the simulator
(tests/drivers/piper/piper_sim_test.cpp, TheSdkTranscriptReplays) and keeps the checks at the
end as simulator tests.

usage: /usr/bin/python3 sdk_against_sim.py --sdk PIPER_SDK_CHECKOUT --sim build/bin/robotd-piper-sim
                                           [--out tests/conformance/piper/sdk_sim_transcript.json]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import capture_bus  # noqa: E402
import standin_bus  # noqa: E402

MILLI_DEG = 180000 / math.pi


def wait_for(condition, timeout_s):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.005)
    return False


class Session:
    def __init__(self, piper, bus):
        self.piper = piper
        self.bus = bus
        self.steps = []

    def joints(self):
        state = self.piper.GetArmJointMsgs().joint_state
        return [state.joint_1, state.joint_2, state.joint_3, state.joint_4, state.joint_5, state.joint_6]

    def status(self):
        status = self.piper.GetArmStatus().arm_status
        return {"arm_status": int(status.arm_status.value), "mode_feed": int(status.mode_feed.value),
                "motion_status": int(status.motion_status.value), "err_code": status.err_code}

    def step(self, name, calls, until=None, timeout_s=5.0, settle_s=0.05):
        sent_from = len(self.bus.transcript)
        for call, args in calls:
            getattr(self.piper, call)(*args)
        reached = wait_for(until, timeout_s) if until else True
        time.sleep(settle_s)
        frames = [{"id": i, "data": d} for _, direction, i, d in self.bus.transcript[sent_from:] if direction == "tx"]
        record = {"step": name, "calls": [[c, list(a)] for c, a in calls], "sent": frames, "reached": reached,
                  "joints_mdeg": self.joints(), "status": self.status()}
        self.steps.append(record)
        return record


def run(sdk_module, bus_path):
    piper = sdk_module.C_PiperInterface_V2(bus_path, judge_flag=False, can_auto_init=False)
    piper.CreateCanBus(bus_path, bustype=standin_bus.BUS_TYPE, judge_flag=False)
    piper.ConnectPort()  # PiperInit: limit, acceleration and firmware queries; read threads
    bus = piper.GetCanBus().bus
    s = Session(piper, bus)
    s.step("connect", [], until=lambda: isinstance(piper.GetPiperFirmwareVersion(), str))
    s.steps[-1]["firmware"] = piper.GetPiperFirmwareVersion()
    s.step("enable", [("EnableArm", (7,))], until=lambda: all(piper.GetArmEnableStatus()))
    target = [20000, 30000, -30000, 10000, 20000, -10000]
    s.step("move j", [("MotionCtrl_2", (1, 1, 100, 0)), ("JointCtrl", tuple(target))],
           until=lambda: all(abs(a - b) < 50 for a, b in zip(s.joints(), target)))
    s.step("gripper", [("GripperCtrl", (50000, 1000, 1, 0))],
           until=lambda: abs(piper.GetArmGripperMsgs().gripper_state.grippers_angle - 50000) < 100)
    s.step("mit", [("MotionCtrl_2", (1, 4, 0, 0xAD)), ("JointMitCtrl", (6, 0.5, 0.0, 10.0, 0.8, 0.0))],
           until=lambda: abs(s.joints()[5] - 0.5 * MILLI_DEG) < 600)
    # E-stop while J2 runs fast toward its lower limit (0), high-follow.
    s.step("high-follow j2 up", [("MotionCtrl_2", (1, 1, 100, 0xAD)), ("JointCtrl", (0, 1200000 // 17, 0, 0, 0, 0))],
           until=lambda: abs(s.joints()[1] - 1200000 // 17) < 100)
    s.step("high-follow j2 down", [("JointCtrl", (0, 0, 0, 0, 0, 0))], until=lambda: s.joints()[1] < 30000,
           settle_s=0)
    s.step("e-stop", [("EmergencyStop", (1,))], until=lambda: s.status()["arm_status"] == 1, settle_s=0.5)
    s.step("resume", [("EmergencyStop", (2,))], until=lambda: s.status()["arm_status"] != 1, settle_s=0.3)
    # MOVE P 20 mm from a pose by the wrist singularity (J5 = 0.02 rad).
    start = [0, round(0.5 * MILLI_DEG), round(-1.0 * MILLI_DEG), round(0.8 * MILLI_DEG), round(0.02 * MILLI_DEG),
             round(-0.8 * MILLI_DEG)]
    s.step("enable again", [("EnableArm", (7,))], until=lambda: all(piper.GetArmEnableStatus()))
    s.step("to the wrist singularity", [("MotionCtrl_2", (1, 1, 100, 0)), ("JointCtrl", tuple(start))],
           until=lambda: all(abs(a - b) < 50 for a, b in zip(s.joints(), start)), timeout_s=10)
    time.sleep(0.1)
    pose = piper.GetArmEndPoseMsgs().end_pose
    goal = (pose.X_axis, pose.Y_axis - 20000, pose.Z_axis, pose.RX_axis, pose.RY_axis, pose.RZ_axis)
    s.step("move p 20 mm", [("MotionCtrl_2", (1, 0, 100, 0)), ("EndPoseCtrl", goal)],
           until=lambda: s.status()["motion_status"] == 1, timeout_s=1, settle_s=0)
    s.step("move p arrived", [], until=lambda: s.status()["motion_status"] == 0, timeout_s=5)
    s.steps[-1]["start_mdeg"] = start
    piper.DisconnectPort()
    return s.steps


def checks(steps):
    by_name = {step["step"]: step for step in steps}
    stopped = by_name["e-stop"]["joints_mdeg"][1]
    resumed = by_name["resume"]["status"]
    moved = by_name["move p arrived"]
    swing = max(abs(a - b) for a, b in zip(moved["joints_mdeg"], moved["start_mdeg"])) / 1000
    return {
        "firmware reported": by_name["connect"]["firmware"] == "S-V1.8-2",
        "every move arrived": all(step["reached"] for step in steps),
        "e-stop leaves J2 within its limit (>= 0)": stopped >= 0,
        "resume clears every error (arm status 0, no limit bits)": resumed["arm_status"] == 0
                                                                      and resumed["err_code"] == 0,
        "MOVE P 20 mm by the wrist singularity moves no joint more than 60 deg": swing < 60,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sdk", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "sdk_sim_transcript.json"))
    args = parser.parse_args()
    sys.path.insert(0, os.path.abspath(args.sdk))
    capture_bus.install({standin_bus.BUS_TYPE: standin_bus.StandInBus})
    import piper_sdk  # noqa: E402

    with tempfile.TemporaryDirectory() as tmp:
        bus_path = os.path.join(tmp, "piper.sock")
        sim = subprocess.Popen([args.sim, "--standin", bus_path, "--quiet"], stdout=subprocess.PIPE, text=True)
        try:
            if sim.stdout.readline().strip() != "ready":
                sys.exit("robotd-piper-sim did not start")
            steps = run(piper_sdk, bus_path)
        finally:
            sim.terminate()
            sim.wait(5)
    result = {"steps": steps, "checks": checks(steps)}
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    for name, ok in result["checks"].items():
        print(("ok      " if ok else "FAILED  ") + name)
    return 0 if all(result["checks"].values()) else 1


if __name__ == "__main__":
    sys.exit(main())
