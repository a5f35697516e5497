#!/usr/bin/env python3
"""Records the AgileX PiPER SDK's own behaviour for robotd's conformance replay
(tests/conformance/piper, docs/drivers/piper.md "Conformance").

usage: /usr/bin/python3 generate.py --sdk PIPER_SDK_CHECKOUT [--out DIR]

PIPER_SDK_CHECKOUT is a checkout (or `git archive` extraction) of agilexrobotics/piper_sdk: the
directory holding the `piper_sdk` package. Needs python-can (Debian python3-can). Writes, in DIR
(default: this generator's parent directory):
  encodes.jsonl   every public send call with its arguments: the frames sent, or the exception
  decodes.jsonl   crafted feedback frames through ParseCANFrame: what the getter then reports
  firmware.jsonl  0x4AF reply chunks and GetPiperFirmwareVersion after each
  fk.jsonl        C_PiperForwardKinematics.CalFK link poses for a grid of joint vectors
  provenance.json repository, commit, files run, command, date
"""
import argparse
import datetime
import enum
import json
import math
import os
import subprocess
import sys

import can

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import capture_bus  # noqa: E402
import feedback_frames  # noqa: E402
import sdk_calls  # noqa: E402

SDK_FILES = [
    "piper_sdk/interface/piper_interface_v2.py",
    "piper_sdk/protocol/protocol_v2/piper_protocol_v2.py",
    "piper_sdk/protocol/piper_protocol_base.py",
    "piper_sdk/hardware_port/can_encapsulation_v0_4_0.py",
    "piper_sdk/kinematics/piper_fk.py",
    "piper_sdk/piper_msgs/msg_v2/",
]


def plain(value, depth=0):
    """A getter's result as JSON: enums by value, objects by their public attributes."""
    if isinstance(value, enum.Enum):
        return value.value
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, (bytes, bytearray)):
        return value.hex(" ")
    if isinstance(value, (list, tuple)):
        return [plain(v, depth + 1) for v in value]
    if depth > 4:
        return str(value)
    fields = {}
    for name in dir(value):
        if name.startswith("_") or name in ("Hz", "time_stamp"):
            continue
        attribute = getattr(value, name)
        if callable(attribute) and not isinstance(attribute, enum.Enum):
            continue
        fields[name] = plain(attribute, depth + 1)
    return fields


class Sdk:
    def __init__(self, sdk_module):
        self.module = sdk_module
        self.count = 0

    def interface(self, **kwargs):
        """A fresh C_PiperInterface_V2 (it is a singleton per CAN name) on a capture bus."""
        self.count += 1
        name = f"robotd_conformance_{self.count}"
        piper = self.module.C_PiperInterface_V2(name, judge_flag=False, can_auto_init=False, **kwargs)
        piper.CreateCanBus(name, bustype=capture_bus.BUS_TYPE, judge_flag=False)
        piper.ConnectPort(piper_init=False, start_thread=False)
        return piper


def record_encodes(sdk, out):
    with open(os.path.join(out, "encodes.jsonl"), "w", encoding="utf-8") as f:
        for call, args in sdk_calls.CALLS:
            piper = sdk.interface()
            bus = piper.GetCanBus().bus
            vector = {"call": call, "args": list(args)}
            try:
                getattr(piper, call)(*args)
                vector["frames"] = bus.take()
            except Exception as e:  # the SDK's refusal is the recorded result
                vector["rejected"] = {"type": type(e).__name__, "message": str(e)}
                vector["frames"] = bus.take()
            f.write(json.dumps(vector) + "\n")


def record_decodes(sdk, out):
    with open(os.path.join(out, "decodes.jsonl"), "w", encoding="utf-8") as f:
        for can_id, data, getter in feedback_frames.FRAMES:
            piper = sdk.interface()
            before = getattr(piper, getter)().time_stamp
            piper.ParseCANFrame(can.Message(arbitration_id=can_id, data=data, timestamp=1.0))
            result = getattr(piper, getter)()
            vector = {"id": can_id, "data": data.hex(" "), "getter": getter,
                      "accepted": result.time_stamp != before, "result": plain(result)}
            f.write(json.dumps(vector) + "\n")


def record_firmware(sdk, out):
    with open(os.path.join(out, "firmware.jsonl"), "w", encoding="utf-8") as f:
        for chunks in feedback_frames.FIRMWARE_SCENARIOS:
            piper = sdk.interface()
            versions = []
            for chunk in chunks:
                piper.ParseCANFrame(can.Message(arbitration_id=0x4AF, data=chunk, dlc=len(chunk), timestamp=1.0))
                versions.append(piper.GetPiperFirmwareVersion())
            f.write(json.dumps({"chunks": [c.hex(" ") for c in chunks], "versions": versions}) + "\n")


def joint_grid():
    """Zero, the home pose, wrist singularities (J5 = 0), pitch ±90°, and a fixed spread."""
    grid = [[0.0] * 6, [0.0, 1.57, -1.3485, 0.0, 1.2, 0.0], [0.3, 0.8, -0.9, 0.0, 0.0, 0.4],
            [0.0, 0.0, 0.0, 0.0, math.pi / 2, 0.0], [0.0, 0.0, 0.0, 0.0, -math.pi / 2, 0.0],
            [-2.6, 3.1, -2.9, 1.8, -1.2, 3.0], [2.6, 0.1, -0.1, -1.8, 1.2, -3.0]]
    for i in range(24):  # deterministic spread over the joint ranges
        grid.append([round(math.sin(1.7 * i + k) * r, 6)
                     for k, r in enumerate((2.6, 1.6, 1.4, 1.8, 1.2, 3.0))])
    return grid


def record_fk(sdk_fk, out):
    with open(os.path.join(out, "fk.jsonl"), "w", encoding="utf-8") as f:
        for dh in (0, 1):
            fk = sdk_fk.C_PiperForwardKinematics(dh)
            for q in joint_grid():
                f.write(json.dumps({"dh_is_offset": dh, "joints_rad": q, "links": fk.CalFK(q)}) + "\n")


def commit_of(path):
    try:
        return subprocess.run(["git", "-C", path, "rev-parse", "HEAD"], capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sdk", required=True, help="directory holding the piper_sdk package")
    parser.add_argument("--commit", help="the piper_sdk commit (read with git when --sdk is a checkout)")
    parser.add_argument("--out", default=os.path.dirname(HERE))
    args = parser.parse_args()
    sdk_path = os.path.abspath(args.sdk)
    if not os.path.isfile(os.path.join(sdk_path, "piper_sdk", "__init__.py")):
        sys.exit(f"--sdk {sdk_path}: no piper_sdk package there (expected a piper_sdk checkout)")
    commit = args.commit or commit_of(sdk_path)
    if not commit:
        sys.exit("--commit is needed when --sdk is not a git checkout")
    sys.path.insert(0, sdk_path)
    capture_bus.install({capture_bus.BUS_TYPE: capture_bus.CaptureBus})
    import piper_sdk  # noqa: E402
    from piper_sdk.kinematics import piper_fk  # noqa: E402
    import piper_sdk.version  # noqa: E402

    sdk = Sdk(piper_sdk)
    record_encodes(sdk, args.out)
    record_decodes(sdk, args.out)
    record_firmware(sdk, args.out)
    record_fk(piper_fk, args.out)
    provenance = {
        "repository": "https://github.com/agilexrobotics/piper_sdk",
        "commit": commit,
        "sdk_version": sdk.interface().GetCurrentSDKVersion().value,
        "python_can": can.__version__,
        "python": sys.version.split()[0],
        "files_run": SDK_FILES,
        "command": "/usr/bin/python3 tests/conformance/piper/generate/generate.py --sdk <piper_sdk checkout>"
                   + ("" if not args.commit else f" --commit {commit}"),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
    }
    with open(os.path.join(args.out, "provenance.json"), "w", encoding="utf-8") as f:
        json.dump(provenance, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
