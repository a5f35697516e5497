#!/usr/bin/env python3
"""State fan-out: 1, 4 and 16 subscriber processes on /joint_states while robotd publishes the
simulated arm's state at 1 kHz. For each subscriber, the fraction of the samples robotd
published in the measured window that it received; the loop's overruns and robotd's CPU use
over the same window.

robotd reports its /joint_states publish count together with the header stamp of the last
sample that count covers (device_call loop_timing) at the start and end of the window; stamps
are unique, so each subscriber counts exactly the samples published in the window."""
import tempfile
import time
from pathlib import Path

import benchlib as b


def run(programs, subscribers, seconds):
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, [b.sim_arm()])) as robotd, \
            tempfile.TemporaryDirectory(prefix="robotd-fanout-") as scratch:
        outputs = [Path(scratch) / f"subscriber{i}.txt" for i in range(subscribers)]
        processes = [b.start_tool(programs, "robotd_bench_subscribe", "--domain", domain, "--device", "arm",
                                  "--seconds", seconds + 4, "--output", output) for output in outputs]
        time.sleep(2.0)  # discovery: every subscriber matched before the window opens
        start = robotd.call("arm", "loop_timing")
        cpu_start, wall_start = robotd.cpu_seconds(), time.monotonic()
        time.sleep(seconds)
        end = robotd.call("arm", "loop_timing")
        cpu_end, wall_end = robotd.cpu_seconds(), time.monotonic()
        for process in processes:
            b.finish_tool(process)
        published = end["joint_states_published"] - start["joint_states_published"]
        fractions = []
        for output in outputs:
            stamps = [int(line) for line in output.read_text().split()]
            first, last = start["last_published_stamp_ns"], end["last_published_stamp_ns"]
            received = sum(1 for stamp in stamps if first < stamp <= last)
            fractions.append(received / published if published else 0.0)
        return {"published": published, "fractions": fractions, "overruns": end["overruns"] - start["overruns"],
                "cpu_cores": (cpu_end - cpu_start) / (wall_end - wall_start)}


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    seconds = 2 if args.quick else 10
    rows, figures = [], {}
    for subscribers in (1, 4, 16):
        result = run(programs, subscribers, seconds)
        low, mean = min(result["fractions"]), sum(result["fractions"]) / len(result["fractions"])
        rows.append([subscribers, result["published"], f"{low:.4f}", f"{mean:.4f}", result["overruns"],
                     f"{result['cpu_cores']:.3f}"])
        figures.update({f"fanout{subscribers}_min_fraction": round(low, 5),
                        f"fanout{subscribers}_mean_fraction": round(mean, 5),
                        f"fanout{subscribers}_published": result["published"],
                        f"fanout{subscribers}_overruns": result["overruns"],
                        f"fanout{subscribers}_robotd_cpu_cores": round(result["cpu_cores"], 4)})
    print(f"state fan-out: /joint_states of a 6-joint arm at 1 kHz, {seconds} s window per run")
    print(b.table(["subscribers", "published", "min fraction", "mean fraction", "loop overruns", "robotd CPU cores"],
                  rows))
    print("target: every subscriber ≥ 0.99 with no extra overruns")
    b.emit(figures)


if __name__ == "__main__":
    main()
