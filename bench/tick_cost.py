#!/usr/bin/env python3
"""Tick cost: what one tick of a device's loop costs (mailbox, session check, safety and
limiting, sim driver read and write) for 6 and 23 joints. Wall time from Google Benchmark,
and instructions per tick from callgrind, which counts the same on a busy machine as on an
idle one."""
import json
import re
import subprocess
import tempfile

import benchlib as b


def wall_time_ns(programs, min_time_s):
    result = subprocess.run([programs.tool("robotd_bench_tick"), f"--benchmark_min_time={min_time_s}",
                             "--benchmark_format=json"], capture_output=True, text=True, check=True)
    times = {}
    for entry in json.loads(result.stdout)["benchmarks"]:
        joints = int(re.search(r"/(\d+)", entry["name"]).group(1))
        times[joints] = entry["real_time"] if entry["time_unit"] == "ns" else entry["real_time"] * 1000
    return times


def instructions_per_tick(programs, joints, ticks):
    with tempfile.NamedTemporaryFile(suffix=".callgrind") as out:
        subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no", f"--callgrind-out-file={out.name}",
                        programs.tool("robotd_bench_tick"), "--callgrind-ticks", str(ticks), "--joints", str(joints)],
                       capture_output=True, text=True, check=True)
        totals = [line for line in open(out.name) if line.startswith("totals:")]
        return int(totals[0].split()[1]) / ticks


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    min_time_s, ticks = (0.05, 50) if args.quick else (2, 1000)
    wall = wall_time_ns(programs, min_time_s)
    instructions = {joints: instructions_per_tick(programs, joints, ticks) for joints in (6, 23)}
    print("tick cost (ControlLoop::tick with the sim driver, a new command every tick)")
    print(b.table(["joints", "wall ns/tick", "instructions/tick", "target"],
                  [[6, f"{wall[6]:.0f}", f"{instructions[6]:.0f}", "< 5000 ns"],
                   [23, f"{wall[23]:.0f}", f"{instructions[23]:.0f}", "< 15000 ns"]]))
    b.emit({"tick_ns_6": round(wall[6], 1), "tick_ns_23": round(wall[23], 1),
            "tick_instructions_6": round(instructions[6]), "tick_instructions_23": round(instructions[23])})


if __name__ == "__main__":
    main()
