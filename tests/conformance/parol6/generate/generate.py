#!/usr/bin/python3
"""Records what the two PAROL6 host codebases do with the same inputs, for robotd's replay test.

  generate.py --api CHECKOUT [--api-commit SHA] --commander CHECKOUT [--commander-commit SHA]
              [--out DIR]

CHECKOUT: a checkout (or `git archive` export) of PCrnjak/PAROL6-python-API and of
PCrnjak/PAROL-commander-software. Needs numpy and pyserial (scripts/install-deps.sh
--conformance). Writes tx_frames.jsonl, rx_frames.jsonl, joint_units.jsonl, framing.jsonl and
provenance.json into DIR (default: the directory above this script).

Every recorded output comes from running the vendors' functions (vendor_code.py loads them); this
script only chooses inputs and writes down what came back.
"""
import argparse
import datetime
import json
import math
import random
import subprocess
import sys
import types
from pathlib import Path

import numpy as np

import vendor_code

FRAME_START = bytes([0xFF, 0xFF, 0xFF])
STANDBY_STEPS = [10240, -32000, 57905, 0, 0, 32000]


def hex_text(data):
    return " ".join(f"{b:02x}" for b in data)


def ints(values):
    return [int(v) for v in values]


# --- TX: the host's 56-byte frame ---------------------------------------------------------------

def tx_inputs():
    """(name, positions, speeds, command, affected bits, io bits, timeout, gripper[6])."""
    zeros, ones = [0] * 8, [1] * 8
    base = dict(positions=STANDBY_STEPS, speeds=[0] * 6, command=255, affected=ones, io=zeros, timeout=0,
                gripper=[0, 0, 0, 0, 0, 0])
    cases = [("idle at standby", base)]

    def vary(name, **fields):
        cases.append((name, dict(base, **fields)))

    int24 = [0, 1, -1, 255, 256, -256, 65535, 65536, -65536, 8388607, -8388608, 8388608, -8388609,
             16777215, 16777216, -16777216, 0x7FFF00]
    for k in range(0, len(int24), 6):
        chunk = (int24[k:k + 6] + [0] * 6)[:6]
        vary(f"positions int24 edges {k // 6}", positions=chunk, command=156)
        vary(f"speeds int24 edges {k // 6}", speeds=chunk, command=123)
    for command in (0, 69, 100, 101, 102, 103, 123, 156, 255):
        vary(f"command {command}", command=command)
    for name, bits in (("none", zeros), ("J1", [1] + [0] * 7), ("J6", [0] * 5 + [1, 0, 0]),
                       ("alternate", [1, 0] * 4), ("last", [0] * 7 + [1])):
        vary(f"affected {name}", affected=bits)
    for name, bits in (("OUT1", [0, 0, 1, 0, 0, 0, 0, 0]), ("OUT2", [0, 0, 0, 1, 0, 0, 0, 0]),
                       ("OUT1+OUT2", [0, 0, 1, 1, 0, 0, 0, 0]), ("all", ones)):
        vary(f"io {name}", io=bits)
    for timeout in (1, 100, 255):
        vary(f"timeout {timeout}", timeout=timeout)
    grippers = [
        ("activate move", [255, 255, 1000, 0xC0, 0, 0]),
        ("half", [128, 50, 500, 0xC0, 0, 3]),
        ("current 1300", [100, 100, 1300, 0xC0, 0, 15]),
        ("current 0", [100, 100, 0, 0x80, 0, 0]),
        ("estop", [0, 0, 100, 0xA0, 0, 0]),
        ("release direction", [10, 20, 300, 0xD0, 0, 0]),
        ("calibrate", [0, 0, 0, 0, 1, 0]),
        ("clear error", [0, 0, 0, 0, 2, 0]),
        ("negative", [-1, -222, -32768, 0x40, 0, 1]),
        ("int16 max", [32767, 32767, 32767, 0xFF, 0xFF, 0xFF]),
    ]
    for name, gripper in grippers:
        vary(f"gripper {name}", gripper=gripper)
    rng = random.Random(19)
    for k in range(30):
        cases.append((f"random {k}", dict(
            positions=[rng.randint(-8388608, 8388607) for _ in range(6)],
            speeds=[rng.randint(-50000, 50000) for _ in range(6)],
            command=rng.choice((100, 101, 102, 103, 123, 156, 255)),
            affected=[rng.randint(0, 1) for _ in range(8)], io=[rng.randint(0, 1) for _ in range(8)],
            timeout=rng.randint(0, 255),
            gripper=[rng.randint(0, 255), rng.randint(0, 255), rng.randint(0, 1300), rng.randint(0, 255),
                     rng.randint(0, 2), rng.randint(0, 15)])))
    return cases


def api_tx(api, case):
    out = bytearray(56)
    api.wire["pack_tx_frame_into"](
        memoryview(out), np.array(case["positions"], dtype=np.int32), np.array(case["speeds"], dtype=np.int32),
        case["command"], np.array(case["affected"], dtype=np.uint8), np.array(case["io"], dtype=np.uint8),
        case["timeout"], np.array(case["gripper"], dtype=np.int32))
    return bytes(out)


def commander_tx(commander, case):
    pieces = commander.sender["Pack_data"](
        list(case["positions"]), list(case["speeds"]), types.SimpleNamespace(value=case["command"]),
        list(case["affected"]), list(case["io"]), types.SimpleNamespace(value=case["timeout"]),
        list(case["gripper"]))
    return b"".join(pieces)


def record_tx(api, commander):
    for name, case in tx_inputs():
        yield {"name": name, "input": case, "api": hex_text(api_tx(api, case)),
               "commander": hex_text(commander_tx(commander, case))}


# --- RX: the board's reply body (the 56 bytes after LEN) ----------------------------------------

def reply_body(positions=STANDBY_STEPS, speeds=(0,) * 6, homed=0xFF, io=0x0F, temperature=0x03,
               position_error=0x03, timing=7031, timeout_error=100, echoed=255, gripper_id=0,
               gripper_position=0, gripper_speed=1, gripper_current=2, status=1, object_detection=1, crc=212):
    """A reply body as the board firmware lays it out (int24 and int16 big-endian)."""
    body = bytearray()
    for value in list(positions) + list(speeds):
        body += (value & 0xFFFFFF).to_bytes(3, "big")
    body += bytes([homed, io, temperature, position_error]) + (timing & 0xFFFF).to_bytes(2, "big")
    body += bytes([timeout_error, echoed, gripper_id])
    for value in (gripper_position, gripper_speed, gripper_current):
        body += (value & 0xFFFF).to_bytes(2, "big")
    body += bytes([status, object_detection, crc, 0x01, 0x02])
    assert len(body) == 56
    return bytes(body)


def rx_inputs():
    cases = [("standby", reply_body()),
             ("power-up", reply_body(positions=(0,) * 6, homed=0x03, timing=0, echoed=0)),
             ("int24 edges", reply_body(positions=(8388607, -8388608, -1, 1, 0x10000, -0x10000),
                                        speeds=(50000, -50000, 255, -256, 0x7FFF, -0x8000))),
             ("homed J1-J3", reply_body(homed=0xE3)), ("homed none", reply_body(homed=0x00)),
             ("estop pressed", reply_body(io=0x07)), ("inputs", reply_body(io=0xCF)),
             ("io all", reply_body(io=0xFF)), ("temperature errors", reply_body(temperature=0xA7)),
             ("position errors", reply_body(position_error=0x5F)),
             ("timing max", reply_body(timing=0xFFFF)), ("timing sign bit", reply_body(timing=0x8000)),
             ("timeout error 0", reply_body(timeout_error=0)), ("echoed 123", reply_body(echoed=123)),
             ("gripper id 15", reply_body(gripper_id=15)),
             ("gripper values", reply_body(gripper_position=200, gripper_speed=255, gripper_current=-250)),
             ("gripper int16 edges", reply_body(gripper_position=-1, gripper_speed=-32768, gripper_current=32767)),
             ("object byte 0", reply_body(object_detection=0)), ("object byte 3", reply_body(object_detection=3)),
             ("crc 0", reply_body(crc=0))]
    # The gripper status byte: the firmware's bits one by one, and the combinations that tell the
    # object-detection readings apart.
    for status in (0x00, 0x01, 0x02, 0x04, 0x08, 0x0C, 0x10, 0x20, 0x30, 0x40, 0x80, 0xC1, 0xE1, 0xD1, 0xF1,
                   0x89, 0x85, 0xFF):
        cases.append((f"gripper status {status:#04x}", reply_body(status=status)))
    rng = random.Random(6)
    for k in range(20):
        body = bytearray(rng.randrange(256) for _ in range(54)) + b"\x01\x02"
        cases.append((f"random {k}", bytes(body)))
    return cases


def api_rx(api, body):
    pos, spd = np.zeros(6, dtype=np.int32), np.zeros(6, dtype=np.int32)
    bitfields = [np.zeros(8, dtype=np.uint8) for _ in range(4)]
    timing, grip = np.zeros(1, dtype=np.int32), np.zeros(6, dtype=np.int32)
    # The transport hands the unpacker the first 52 payload bytes (serial_transport.py).
    ok = api.wire["unpack_rx_frame_into"](memoryview(bytes(body[:52])), pos, spd, *bitfields, timing, grip)
    homed, io, temperature, position_error = (ints(b) for b in bitfields)
    return {"ok": bool(ok), "positions": ints(pos), "speeds": ints(spd), "homed": homed, "io": io,
            "temperature_error": temperature, "position_error": position_error, "timing": int(timing[0]),
            "gripper": dict(zip(("id", "position", "speed", "current", "status", "object_detection"), ints(grip)))}


class Value:
    """The commander's multiprocessing.Value stand-in."""

    def __init__(self):
        self.value = None


def commander_rx(commander, body):
    data_buffer = [bytes([b]) for b in body]  # Get_data stores one ser.read() (bytes) per byte
    pos, spd, homed, io, temperature, position_error = [0] * 6, [0] * 6, [0] * 8, [0] * 8, [0] * 8, [0] * 8
    timeout_error, timing, xtr, gripper = Value(), Value(), Value(), [0] * 6
    commander.sender["Unpack_data"](data_buffer, pos, spd, homed, io, temperature, position_error, timeout_error,
                                    timing, xtr, gripper)
    return {"positions": pos, "speeds": spd, "homed": homed, "io": io, "temperature_error": temperature,
            "position_error": position_error, "timing": timing.value, "timeout_error": timeout_error.value,
            "xtr2": xtr.value,
            "gripper": dict(zip(("id", "position", "speed", "current", "status", "object_detection"), gripper))}


def record_rx(api, commander):
    for name, body in rx_inputs():
        yield {"name": name, "body": hex_text(body), "api": api_rx(api, body),
               "commander": commander_rx(commander, body)}


# --- joint units --------------------------------------------------------------------------------

def unit_inputs(api):
    """Per joint: angles (rad) and speeds (rad/s) at whole steps, quarter steps, around the half
    step (the exact double and its neighbours), both signs, and plain values."""
    radian_per_step = api.config["_radian_per_step"]
    ratios = api.config["_joint_ratio"]
    rng = random.Random(60)
    for joint in range(6):
        per_step = radian_per_step / float(ratios[joint])
        values = [0.0, 0.1, -0.1, 1.0, -1.0, math.pi / 2, -math.pi / 3, math.pi, 2.0, -2.5]
        for steps in (0, 1, 2, 7, 100, 1001, 12345, STANDBY_STEPS[joint], 51559, 99999):
            for fraction in (0.0, 0.25, 0.5, 0.75):
                for sign in (1, -1):
                    x = sign * (steps + fraction) * per_step
                    values.append(x)
                    if fraction == 0.5:
                        values += [math.nextafter(x, math.inf), math.nextafter(x, -math.inf)]
        values += [rng.uniform(-6.5, 6.5) for _ in range(20)]
        for value in values:
            yield joint, value


def one_joint(joint, value):
    vector = np.zeros(6, dtype=np.float64)
    vector[joint] = value
    return vector


def record_units(api, commander):
    cfg, robot = api.config, commander.robot
    for joint, value in unit_inputs(api):
        steps_vector = cfg["rad_to_steps"](one_joint(joint, value), np.zeros(6, dtype=np.int32))
        speed_vector = cfg["speed_rad_to_steps"](one_joint(joint, value), np.zeros(6, dtype=np.int32))
        position_float = robot["RAD2STEPS"](value, joint)
        speed_float = robot["SPEED_RAD2STEP"](value, joint)
        yield {"kind": "to_steps", "joint": joint, "rad": value,
               "api": {"position_steps": int(steps_vector[joint]),
                       "position_steps_scalar": int(cfg["rad_to_steps_scalar"](value, joint)),
                       "speed_steps_s": int(speed_vector[joint]),
                       "speed_steps_s_scalar": int(cfg["speed_rad_to_steps_scalar"](value, joint))},
               # The commander's callers truncate with int() (Serial_sender_good_latest.py 359, 885, 888).
               "commander": {"position_steps": int(position_float), "speed_steps_s": int(speed_float),
                             "position_float": float(position_float), "speed_float": float(speed_float)}}
    for joint in range(6):
        for steps in (0, 1, -1, 7, -7, 100, 12345, -12345, STANDBY_STEPS[joint], 64000, -51559, 8388607, -8388608):
            counts = np.zeros(6, dtype=np.int32)
            counts[joint] = steps
            yield {"kind": "to_rad", "joint": joint, "steps": steps,
                   "api": {"position_rad": float(cfg["steps_to_rad"](counts, np.zeros(6))[joint]),
                           "speed_rad_s": float(cfg["speed_steps_to_rad"](counts, np.zeros(6))[joint])},
                   "commander": {"position_rad": float(commander.robot["STEPS2RADS"](steps, joint)),
                                 "speed_rad_s": float(commander.robot["SPEED_STEP2RAD"](steps, joint))}}


# --- framing: byte streams through both host parsers --------------------------------------------

def framed(body, length=None):
    return FRAME_START + bytes([len(body) if length is None else length]) + body


def framing_inputs():
    a = framed(reply_body())
    b = framed(reply_body(positions=(-1, 1, 2, 3, 4, 5), speeds=(-1,) * 6))  # FF FF FF inside the payload
    c = framed(reply_body(gripper_position=77))
    broken_end = a[:-1] + b"\x03"
    host = FRAME_START + bytes([52]) + bytes(range(50)) + b"\x01\x02"
    lost_byte = a[:20] + a[21:]
    return [
        ("one frame", a),
        ("two frames back to back", a + c),
        ("garbage before a frame", bytes([0x00, 0x12, 0xFF, 0x34, 0xFF, 0xFF, 0x01, 0x02]) + a),
        ("FF inside the payload", b + a),
        ("truncated frame, then FF FF FF inside the next payload", b[:30] + b + a),
        ("broken end marker, then a frame", broken_end + c),
        ("broken end marker, then two frames", broken_end + a + c),
        ("truncated frame, then a frame", a[:30] + c),
        ("truncated frame, then two frames", a[:30] + c + a),
        ("a lost byte, then two frames", lost_byte + c + a),
        ("FF FF FF FF before a frame", bytes([0xFF]) + a + c),
        ("FF FF FF FF FF before a frame", bytes([0xFF, 0xFF]) + a + c),
        ("FF FF FF FF then garbage", bytes([0xFF] * 4) + bytes(range(1, 100)) + a + c + a + c),
        ("a 52-byte host frame", host + a),
        ("LEN 60 with the end bytes at its end", framed(reply_body()[:54] + b"\x00\x00\x00\x00\x01\x02") + a),
        ("LEN 2, then a frame", FRAME_START + bytes([2, 0x01, 0x02]) + a),
        ("only the end of a frame", a[30:] + c),
        ("three frames", a + b + c),
    ]


class ApiLine:
    """Stands in for the API transport's pyserial port: hands over `data` in chunks of `chunk`."""

    is_open = True

    def __init__(self, data, chunk):
        self.data, self.chunk = data, chunk

    @property
    def in_waiting(self):
        return min(len(self.data), self.chunk)

    def readinto(self, view):
        n = min(len(view), len(self.data), self.chunk)
        view[:n] = self.data[:n]
        self.data = self.data[n:]
        return n


def api_frames(api, stream, chunk):
    """Feeds `stream` to the API's SerialTransport in reads of `chunk` bytes. After each read, if
    the transport published frames (its frame version moved), records how many and the 52-byte
    buffer get_latest_frame_view returns: the API keeps only the latest frame."""
    transport = api.transport["SerialTransport"](port=None)
    transport.serial = ApiLine(stream, chunk)
    published, version = [], 0
    while transport.serial.data:
        transport.poll_read()
        view, new_version, _ = transport.get_latest_frame_view()
        if new_version != version:
            published.append({"count": new_version - version, "frame": hex_text(bytes(view))})
            version = new_version
    return published


class CommanderLine:
    """Stands in for the commander's `ser`: Get_data reads one byte at a time while inWaiting()."""

    def __init__(self):
        self.data = b""

    def inWaiting(self):  # noqa: N802 - the name Get_data calls
        return len(self.data)

    def read(self):
        byte, self.data = self.data[:1], self.data[1:]
        return byte


def commander_frames(checkout, stream):
    """Feeds `stream` to the commander's Get_data in a fresh module state and lists the bodies it
    hands to Unpack_data (end bytes checked), with Unpack_data's error if it raised."""
    line = CommanderLine()
    commander = vendor_code.load_commander(checkout, line)
    unpack = commander.sender["Unpack_data"]
    frames = []

    def recording_unpack(data_buffer, *outputs):
        length = commander.sender["data_len"]
        frame = {"body": hex_text(b"".join(b for b in data_buffer[:length]))}
        try:
            unpack(data_buffer, *outputs)
        except Exception as error:  # noqa: BLE001 - what the vendor code raised is the data
            frame["unpack_error"] = type(error).__name__
        frames.append(frame)

    commander.sender["Unpack_data"] = recording_unpack
    line.data = stream
    outputs = [[0] * 6, [0] * 6, [0] * 8, [0] * 8, [0] * 8, [0] * 8, Value(), Value(), Value(), [0] * 6]
    result = {"frames": frames}
    try:
        commander.sender["Get_data"](*outputs)
    except Exception as error:  # noqa: BLE001
        result["error"] = f"{type(error).__name__}: {error}"
    return result


def record_framing(api, commander_checkout):
    for name, stream in framing_inputs():
        byte_by_byte = api_frames(api, stream, 1)
        commander = commander_frames(commander_checkout, stream)
        api_count = sum(published["count"] for published in byte_by_byte)
        api_last = byte_by_byte[-1]["frame"] if byte_by_byte else None
        commander_last = commander["frames"][-1]["body"][:len(api_last)] if commander["frames"] and api_last else None
        yield {"name": name, "stream": hex_text(stream),
               "api": {"byte_by_byte": byte_by_byte, "at_once": api_frames(api, stream, len(stream))},
               "commander": commander,
               "vendors_agree": api_count == len(commander["frames"]) and api_last == commander_last}


# --- output --------------------------------------------------------------------------------------

def git_commit(checkout, given):
    if given:
        return given
    try:
        return subprocess.run(["git", "-C", str(checkout), "rev-parse", "HEAD"], check=True,
                              capture_output=True, text=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        sys.exit(f"{checkout} is not a git checkout: give its commit with --api-commit/--commander-commit")


def write_lines(path, records):
    count = 0
    with open(path, "w", encoding="utf-8") as out:
        for record in records:
            out.write(json.dumps(record, sort_keys=True) + "\n")
            count += 1
    return count


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--api", required=True, type=Path)
    parser.add_argument("--api-commit")
    parser.add_argument("--commander", required=True, type=Path)
    parser.add_argument("--commander-commit")
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve().parent.parent)
    args = parser.parse_args()

    api = vendor_code.load_api(args.api)
    commander = vendor_code.load_commander(args.commander, CommanderLine())
    counts = {
        "tx_frames.jsonl": write_lines(args.out / "tx_frames.jsonl", record_tx(api, commander)),
        "rx_frames.jsonl": write_lines(args.out / "rx_frames.jsonl", record_rx(api, commander)),
        "joint_units.jsonl": write_lines(args.out / "joint_units.jsonl", record_units(api, commander)),
        "framing.jsonl": write_lines(args.out / "framing.jsonl", record_framing(api, args.commander)),
    }
    provenance = {
        "vendors": {
            "api": {"repository": "https://github.com/PCrnjak/PAROL6-python-API",
                    "commit": git_commit(args.api, args.api_commit), "files_run": vendor_code.FILES_RUN["api"]},
            "commander": {"repository": "https://github.com/PCrnjak/PAROL-commander-software",
                          "commit": git_commit(args.commander, args.commander_commit),
                          "files_run": vendor_code.FILES_RUN["commander"]},
        },
        "how": ("tests/conformance/parol6/generate/vendor_code.py parses each vendor file and executes, unchanged, "
                "only the top-level definitions the generator calls (the packers, unpackers, stream parsers and unit "
                "conversions), because neither vendor module imports without numba/msgspec/pinokin (API) or a "
                "serial port and GUI (commander). numba's njit is replaced by an identity decorator, so the API's "
                "JIT functions run as the plain Python source numba would compile. The API's serial parser runs "
                "inside its SerialTransport class fed by a stand-in port; the commander's Get_data runs on its own "
                "module globals with a stand-in `ser`. The commander's callers truncate conversions with int() "
                "(Serial_sender_good_latest.py lines 359, 885, 888); the generator applies that int()."),
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "regenerate": ("/usr/bin/python3 tests/conformance/parol6/generate/generate.py --api <PAROL6-python-API "
                       "checkout> --commander <PAROL-commander-software checkout>"),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
        "vectors": counts,
    }
    (args.out / "provenance.json").write_text(json.dumps(provenance, indent=2) + "\n", encoding="utf-8")
    print(json.dumps(counts))


if __name__ == "__main__":
    main()
