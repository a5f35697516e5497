#!/usr/bin/env python3
"""Command flood: the owner of a session streams position commands at 1 kHz while 0, 1, 8 and 32
foreign writers each publish 10 kHz of commands under a uuid robotd never gave out (0 is the
baseline, in the same run). Per configuration, on a fresh robotd with the simulated arm:

- the owner's delivered fraction: commands robotd accepted / commands the owner sent;
- the forged commands sent per second, and the fraction of them robotd counted as rejected
  (rejected_unknown_session) — the rest never reached it;
- robotd's CPU per command received, for its command intake thread ("cmd-intake"), for Cyclone's
  receive threads ("recv*") and for the whole process, over the owner's stream;
- the arm's loop overruns over the run.

Flooders run as min(N, 8) processes (robotd_bench_flood) sharing the N writers, so that 32 of
them do not spend the 2-core VM on 32 DDS participants. Exit status 1 only when the owner's
fraction is catastrophically low (< 0.5): the figures are reported, not judged."""
import json
import subprocess
import sys
import time
from pathlib import Path

import benchlib as b

OWNER_HZ = 1000
FLOOD_HZ = 10000
FLOODERS = (0, 1, 8, 32)
CATASTROPHIC = 0.5


def device_status(robotd):
    """The arm's DeviceStatus as robotctl status --json prints it."""
    result = subprocess.run(robotd.robotctl_command("status", "--json"), capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"robotctl status failed: {result.stdout}{result.stderr}")
    return json.loads(result.stdout)["devices"][0]


def thread_cpu_seconds(pid):
    """CPU seconds per thread name of process `pid` (schedstat: nanoseconds, not clock ticks), summed
    over the threads of one name."""
    seconds = {}
    for task in Path(f"/proc/{pid}/task").iterdir():
        try:
            name = (task / "comm").read_text().strip()
            on_cpu_ns = int((task / "schedstat").read_text().split()[0])
        except OSError:  # the thread ended
            continue
        seconds[name] = seconds.get(name, 0.0) + on_cpu_ns / 1e9
    return seconds


def cpu_by_role(before, after):
    delta = {name: after.get(name, 0.0) - before.get(name, 0.0) for name in after}
    return {"intake": delta.get("cmd-intake", 0.0),
            "receive": sum(value for name, value in delta.items() if name.startswith("recv")),
            "process": sum(delta.values())}


def run(programs, flooders, seconds):
    """One configuration on a fresh robotd (its counters start at zero). The CPU figures cover the
    owner's run, the flood going on throughout."""
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, [b.sim_arm()])) as robotd:
        processes = min(flooders, 8)
        flood = [b.start_tool(programs, "robotd_bench_flood", "--domain", domain, "--writers",
                              flooders // processes + (1 if i < flooders % processes else 0), "--rate", FLOOD_HZ,
                              "--seconds", seconds + 2) for i in range(processes)]
        time.sleep(1.0 if flooders else 0.0)  # discovery: the flood is on before the owner starts
        owner = b.start_tool(programs, "robotd_bench_stream", "--domain", domain, "--rate", OWNER_HZ,
                             "--seconds", seconds)
        before = device_status(robotd)
        cpu_before, wall_before = thread_cpu_seconds(robotd.process.pid), time.monotonic()
        owner = b.finish_tool(owner)
        cpu_after, wall_after = thread_cpu_seconds(robotd.process.pid), time.monotonic()
        during = device_status(robotd)
        forged = sum(b.finish_tool(process)["sent"] for process in flood)
        time.sleep(0.3)  # the intake takes what is left
        end = device_status(robotd)
    received = during["commands"]["received"] - before["commands"]["received"]
    cpu = cpu_by_role(cpu_before, cpu_after)
    per_command_us = {role: round(1e6 * value / received, 2) if received else 0.0 for role, value in cpu.items()}
    return {"owner_sent": owner["sent"], "owner_accepted": end["commands"]["accepted"], "forged": forged,
            "forged_per_s": round(forged / (seconds + 2)), "rejected": end["commands"]["rejected_unknown_session"],
            "cpu_us_per_command": per_command_us, "cpu_cores": round(cpu["process"] / (wall_after - wall_before), 3),
            "overruns": end["loop"]["overruns"]}


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    seconds = 1 if args.quick else 4
    rows, figures, catastrophic = [], {}, []
    for flooders in FLOODERS:
        result = run(programs, flooders, seconds)
        fraction = result["owner_accepted"] / result["owner_sent"] if result["owner_sent"] else 0.0
        counted = result["rejected"] / result["forged"] if result["forged"] else 1.0
        cpu = result["cpu_us_per_command"]
        rows.append([flooders, result["owner_sent"], result["owner_accepted"], f"{fraction:.4f}",
                     result["forged_per_s"], f"{counted:.4f}", cpu["intake"], cpu["receive"], cpu["process"],
                     result["cpu_cores"], result["overruns"]])
        key = f"flood{flooders}"
        figures.update({f"{key}_owner_fraction": round(fraction, 5), f"{key}_owner_sent": result["owner_sent"],
                        f"{key}_forged_per_s": result["forged_per_s"],
                        f"{key}_forged_counted_fraction": round(counted, 5),
                        f"{key}_intake_cpu_us_per_command": cpu["intake"],
                        f"{key}_receive_cpu_us_per_command": cpu["receive"],
                        f"{key}_robotd_cpu_us_per_command": cpu["process"],
                        f"{key}_robotd_cpu_cores": result["cpu_cores"], f"{key}_overruns": result["overruns"]})
        if fraction < CATASTROPHIC:
            catastrophic.append(f"{flooders} flooders: the owner got {fraction:.3f} of its commands through")
    print(f"command flood: the owner at {OWNER_HZ} Hz for {seconds} s beside N foreign writers at {FLOOD_HZ} Hz each")
    print(b.table(["flooders", "owner sent", "accepted", "owner fraction", "forged/s", "forged counted",
                   "intake µs/cmd", "recv µs/cmd", "robotd µs/cmd", "robotd cores", "overruns"], rows))
    if catastrophic:
        print("catastrophic: " + "; ".join(catastrophic))
        sys.exit(1)
    b.emit(figures)


if __name__ == "__main__":
    main()
