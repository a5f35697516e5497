#!/usr/bin/python3
"""Records the HighTorque conformance data by running the vendor's own code.

    generate.py --fdcan DIR --board DIR [--out DIR]

--fdcan: a directory holding the files of HighTorque-Robotics/motor_fdcan_h730 listed in
FDCAN_FILES, each at its commit and at its repository path (the repository has no single commit
with all of them; see provenance.json). --board: a checkout of
HighTorque-Robotics/livelybot_hardware_sdk. --out: where the data goes (default: the directory
above this script).

The vendor's sources are compiled on the host, in a temporary directory, with our stand-ins
(fdcan_stubs/, board_stubs/) and our harnesses (fdcan_harness.c, board_harness.cpp); nothing of
the vendor's is written to --out. Each data file holds one JSON object a line, grouped by what
was recorded.
"""

import argparse
import datetime
import json
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent

# The motor_fdcan_h730 files compiled, and the commit each was read at. 1910d4d3 is the newest
# commit the store has for the sources that build and parse frames; hightorque_fdcan.h and
# convert.c did not change in it, so their newest earlier versions are used (they agree with it:
# TINT16_NOHDR, ID_PREFIX_*, no per-model torque table). convert.h of that generation is not
# stored; fdcan_stubs/convert.h declares what these files use.
FDCAN_FILES = {
    "src/hightorque_fdcan/hightorque_fdcan.c": "1910d4d37b9048dfb62d9938ff7823224993583e",
    "src/motor/motor.c": "1910d4d37b9048dfb62d9938ff7823224993583e",
    "src/motor/motor.h": "1910d4d37b9048dfb62d9938ff7823224993583e",
    "src/motor_many/motor_many.c": "1910d4d37b9048dfb62d9938ff7823224993583e",
    "src/motor_many/motor_many.h": "1910d4d37b9048dfb62d9938ff7823224993583e",
    "src/hightorque_fdcan/hightorque_fdcan.h": "1ffbf90df9f40ade817b00ddedd80e8a29a60f3a",
    "src/convert/convert.c": "e5469383ab06e6db45a8b51cd494bc488420f4c4",
}

BOARD_FILES = [
    "src/livelybot_serial/src/hardware/motor.cc",
    "src/livelybot_serial/src/hardware/canport.cc",
    "src/livelybot_serial/src/lively_serial.cc",
    "src/livelybot_serial/src/crc/crc8.cc",
    "src/livelybot_serial/src/crc/crc16.cc",
    "src/livelybot_serial/include/serial_struct.h",
    "src/livelybot_serial/include/lively_serial.h",
    "src/livelybot_serial/include/hardware/motor.h",
    "src/livelybot_serial/include/hardware/canport.h",
]

# Motors per CAN port the block frames are recorded for (motor.h's MOTOR_MAX_NUM: 1…30).
BLOCK_MOTOR_COUNTS = [30, 7]

# group → data file
FILES = {
    "single frames": "fdcan_single_frames.jsonl",
    "system commands": "fdcan_system_commands.jsonl",
    "replies": "fdcan_replies.jsonl",
    "block frames": "fdcan_block_frames.jsonl",
    "board packets": "board_packets.jsonl",
    "board scaling": "board_scaling.jsonl",
    "board replies": "board_replies.jsonl",
    "board models": "board_models.jsonl",
    "board admin packets": "board_admin_packets.jsonl",
    "board start-up": "board_start_up.jsonl",
}


def run(command, **kwargs):
    print("+", " ".join(str(part) for part in command), file=sys.stderr)
    return subprocess.run(command, check=True, **kwargs)


def build_fdcan(source: pathlib.Path, work: pathlib.Path, motors: int) -> pathlib.Path:
    """The firmware SDK with `motors` motors on each of two ports (the user-set lines of motor.h)."""
    build = work / f"fdcan{motors}"
    build.mkdir()
    for path in FDCAN_FILES:
        if not (source / path).is_file():
            sys.exit(f"--fdcan: {source / path} is missing (expected {path} at commit {FDCAN_FILES[path]})")
        shutil.copy(source / path, build)
    header = build / "motor.h"
    text = header.read_text(encoding="utf-8")
    text, ports = re.subn(r"#define\s+MOTOR_PORT_NUM\s+\d+", "#define  MOTOR_PORT_NUM  2", text)
    text, counts = re.subn(r"#define\s+MOTOR_MAX_NUM\s+\d+", f"#define  MOTOR_MAX_NUM   {motors}", text)
    if ports != 1 or counts != 1:
        sys.exit(f"{header}: expected one MOTOR_PORT_NUM and one MOTOR_MAX_NUM line to set")
    header.write_text(text, encoding="utf-8")
    program = build / "harness"
    sources = [build / pathlib.Path(path).name for path in FDCAN_FILES if path.endswith(".c")]
    run(["gcc", "-std=gnu11", "-O1", "-w", f"-I{HERE / 'fdcan_stubs'}", f"-I{build}", *sources,
         HERE / "fdcan_harness.c", "-o", program, "-lm"])
    return program


def build_board(source: pathlib.Path, work: pathlib.Path) -> pathlib.Path:
    for path in BOARD_FILES:
        if not (source / path).is_file():
            sys.exit(f"--board: {source / path} is missing")
    serial = source / "src/livelybot_serial"
    program = work / "board"
    run(["g++", "-std=c++17", "-O1", "-w", "-DRELEASE", f"-I{HERE / 'board_stubs'}", f"-I{serial / 'include'}",
         f"-I{serial / 'include/hardware'}", f"-I{serial / 'include/crc'}", f"-I{serial / 'src'}",
         HERE / "board_harness.cpp", serial / "src/crc/crc8.cc", serial / "src/crc/crc16.cc", "-o", program])
    return program


def output_lines(command, log) -> list:
    result = run([str(part) for part in command], stdout=subprocess.PIPE, stderr=log, text=True)
    return [json.loads(line) for line in result.stdout.splitlines() if line.strip()]


def git_head(path: pathlib.Path) -> str:
    try:
        return subprocess.run(["git", "-C", str(path), "rev-parse", "HEAD"], check=True, capture_output=True,
                              text=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown (not a git checkout)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fdcan", type=pathlib.Path, required=True)
    parser.add_argument("--board", type=pathlib.Path, required=True)
    parser.add_argument("--out", type=pathlib.Path, default=HERE.parent)
    args = parser.parse_args()

    records = []
    with tempfile.TemporaryDirectory() as temporary:
        work = pathlib.Path(temporary)
        with open(work / "vendor-stderr.log", "w", encoding="utf-8") as log:
            for motors in BLOCK_MOTOR_COUNTS:
                program = build_fdcan(args.fdcan.resolve(), work, motors)
                if motors == BLOCK_MOTOR_COUNTS[0]:
                    records += output_lines([program, "single"], log)
                records += output_lines([program, "block"], log)
            records += output_lines([build_board(args.board.resolve(), work)], log)

    by_file = {name: [] for name in FILES.values()}
    for record in records:
        by_file[FILES[record["group"]]].append(record)
    for name, lines in by_file.items():
        with open(args.out / name, "w", encoding="utf-8") as out:
            for line in lines:
                out.write(json.dumps(line, separators=(",", ":"), sort_keys=False) + "\n")

    provenance = {
        "generated": datetime.date.today().isoformat(),
        "command": "tests/conformance/hightorque/generate/generate.py --fdcan <motor_fdcan_h730 files> "
                   "--board <livelybot_hardware_sdk checkout>",
        "sources": [
            {
                "repository": "https://github.com/HighTorque-Robotics/motor_fdcan_h730",
                "what": "CAN-FD motor firmware SDK: single-motor frame builders, one-to-many block frames, "
                        "reply parser, unit conversion",
                "files": [{"path": path, "commit": commit} for path, commit in FDCAN_FILES.items()],
                "configuration": "motor.h MOTOR_PORT_NUM 2 and MOTOR_MAX_NUM 30 (block frames also 7); "
                                 "MOTOR_DATA_TYPE_FLAG RADIAN_2PI (fdcan_stubs/convert.h)",
            },
            {
                "repository": "https://github.com/HighTorque-Robotics/livelybot_hardware_sdk",
                "what": "USB-CDC CAN board host SDK (the PI Plus path): per-port command packets, CRCs, "
                        "receive loop, motor table, acknowledged commands",
                "commit": git_head(args.board),
                "files": BOARD_FILES,
            },
        ],
        "stand_ins": [
            "fdcan_send() records each frame with bit 15 set (the current SDK's fdcan_send sets it; the stored "
            "App/my_fdcan/my_fdcan.c predates that) and the bytes after the caller's buffer as 0",
            "fdcan_stubs/convert.h declares convert.c's functions and data_type_t (TINT16_NOHDR 0, TINT16 1, "
            "TINT32 2, TFLOAT 3 as hightorque_fdcan.h @1ffbf90d documents); MOTOR_ERR() counts",
            "fdcan_stubs/main.h defines MOTOR_ID_MIN 1 and FLAUT_POS_VEL_TQE 0x0E (motor.c @1910d4d3 uses "
            "both; no stored header of that commit defines them)",
            "single-motor frames: the harness converts with convert.c (conv_to_turns, *_float2int) before "
            "calling the int16/int32/float builders, as motor_many.c does",
            "board SDK: ROS parameters from a map, serial::Serial records writes and serves crafted bytes, "
            "each canport is made in zeroed memory (its packet buffer is otherwise uninitialised)",
        ],
        "data": {name: len(lines) for name, lines in by_file.items()},
    }
    with open(args.out / "provenance.json", "w", encoding="utf-8") as out:
        json.dump(provenance, out, indent=2, ensure_ascii=False)
        out.write("\n")
    print(f"wrote {sum(len(lines) for lines in by_file.values())} vectors to {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
