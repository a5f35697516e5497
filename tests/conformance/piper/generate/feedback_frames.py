"""Crafted arm → host frames fed to the SDK's ParseCANFrame, each with the getter that reads what
it decoded. Values straddle the SDK's abnormal-data filter (|x|, |y|, |z| > 1e6 µm, |rx|, |ry|,
|rz| > 361000 m°, |joint| > 3000000 m°, |gripper| > 150000 µm)."""
import struct


def i32_pair(a, b):
    return struct.pack(">ii", a, b)


def status(*fields):
    return bytes(fields)


JOINT_VALUES = [(0, 0), (12345, -67890), (3000000, -3000000), (3000001, 0), (0, -3000001),
                (2147483647, -2147483648), (-154000, 195000)]
POSITION_VALUES = [(0, 0), (56128, -213266), (1000000, -1000000), (1000001, 0), (0, -1000001),
                   (2147483647, 5)]
ANGLE_VALUES = [(0, 0), (180000, -90000), (361000, -361000), (361001, 0), (0, -361001)]

FRAMES = []  # (id, data bytes, getter name)

for payload in [status(1, 0, 1, 0, 0, 0, 0, 0), status(1, 1, 4, 0, 1, 3, 0x05, 0x22),
                status(1, 0, 6, 0, 0, 0, 0, 0), status(0, 2, 0, 1, 1, 0, 0xFF, 0x3F),
                status(6, 0, 2, 7, 0, 255, 0x20, 0x01), status(7, 0x0F, 5, 3, 0, 2, 0, 0),
                status(2, 0x10, 3, 8, 1, 0, 0, 0), status(5, 0, 7, 0, 0, 0, 0, 0),
                status(8, 0xFE, 0xFF, 0xAA, 2, 0, 0, 0)]:
    FRAMES.append((0x2A1, payload, "GetArmStatus"))
for x, y in POSITION_VALUES:
    FRAMES.append((0x2A2, i32_pair(x, y), "GetArmEndPoseMsgs"))
for (z, _), (rx, _) in zip(POSITION_VALUES, ANGLE_VALUES + [(-180000, 0)]):
    FRAMES.append((0x2A3, i32_pair(z, rx), "GetArmEndPoseMsgs"))
for ry, rz in ANGLE_VALUES:
    FRAMES.append((0x2A4, i32_pair(ry, rz), "GetArmEndPoseMsgs"))
for can_id in (0x2A5, 0x2A6, 0x2A7):
    for a, b in JOINT_VALUES:
        FRAMES.append((can_id, i32_pair(a, b), "GetArmJointMsgs"))
for stroke, effort, code in [(0, 0, 0), (50000, 1000, 0x40), (150000, -1500, 0xC0), (150001, 0, 0x01),
                             (-150001, 0, 0), (-5000, 32767, 0x3F), (70000, -32768, 0xFF)]:
    FRAMES.append((0x2A8, struct.pack(">ihBB", stroke, effort, code, 0), "GetArmGripperMsgs"))
for joint in range(6):
    for speed, current, pos in [(0, 0, 0), (1234, -567, 890123), (-32768, 32767, -2147483648)]:
        FRAMES.append((0x251 + joint, struct.pack(">hhi", speed, current, pos), "GetArmHighSpdInfoMsgs"))
for joint in range(6):
    for vol, foc, motor, code, bus in [(240, 35, 30, 0x40, 1500), (0, -20, -5, 0x00, 0),
                                       (65535, 32767, 127, 0xFF, 65535)]:
        FRAMES.append((0x261 + joint, struct.pack(">hhbBH", vol - 65536 if vol > 32767 else vol, foc, motor, code, bus),
                       "GetArmLowSpdInfoMsgs"))
for joint, hi, lo, spd in [(1, 1500, -1500, 3000), (3, 0, -1750, 0), (6, 32767, -32768, 65535)]:
    FRAMES.append((0x473, struct.pack(">BhhH", joint, hi, lo, spd) + b"\0", "GetCurrentMotorAngleLimitMaxVel"))
for values in [(1000, 2000, 500, 1500), (0x7FFF, 0, 65535, 1)]:
    FRAMES.append((0x478, struct.pack(">HHHH", *values), "GetCurrentEndVelAndAccParam"))
for levels in [(0, 1, 2, 3, 4, 5), (8, 8, 8, 8, 8, 8)]:
    FRAMES.append((0x47B, bytes(levels) + b"\0\0", "GetCrashProtectionLevelFeedback"))
for joint, acc in [(1, 500), (6, 0), (2, 65535)]:
    FRAMES.append((0x47C, struct.pack(">BH", joint, acc) + b"\0" * 5, "GetCurrentMotorMaxAccLimit"))
for params in [(100, 70, 1), (200, 100, 10), (150, 0, 5)]:
    FRAMES.append((0x47E, bytes(params) + b"\0" * 5, "GetGripperTeachingPendantParamFeedback"))
for command, zero in [(0x71, 0), (0x75, 1), (0x50, 0)]:
    FRAMES.append((0x476, bytes([command, zero, 0, 0, 0, 0, 0, 0]), "GetRespInstruction"))
# What a master (leader) arm sends, which the SDK reads back.
for payload in [status(1, 1, 50, 0, 0, 0, 0, 0), status(1, 4, 100, 0xAD, 0, 0, 0, 0), status(6, 2, 30, 0, 3, 0, 0, 0)]:
    FRAMES.append((0x151, payload, "GetArmModeCtrl"))
for can_id in (0x155, 0x156, 0x157):
    for a, b in [(10000, -20000), (3000001, 0)]:
        FRAMES.append((can_id, i32_pair(a, b), "GetArmJointCtrl"))
for stroke, effort, code, zero in [(50000, 1000, 1, 0), (0, 0, 2, 0xAE)]:
    FRAMES.append((0x159, struct.pack(">iHBB", stroke, effort, code, zero), "GetArmGripperCtrl"))

# Chunks of the 0x4AF firmware reply, fed one by one; the version is read after each.
FIRMWARE_SCENARIOS = [
    [b"S-V1.6-3", b"\0" * 8],
    [b"xxxxxS-V", b"1.8-2\0\0\0"],
    [b"HW-V1.2\0", b"S-V1.8-8", b"\0" * 8],
    [b"abcdefS-", b"V1.7-", b"3\0\0"],
    [b"S-V1.", b"10-1"],
    [b"no versi", b"on here\0"],
    [b"S-V1.6\0\0", b"-3"],
]
