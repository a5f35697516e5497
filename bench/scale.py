#!/usr/bin/env python3
"""Scale: 1, 4 and 8 simulated 6-joint devices, and the 23-motor humanoid, each in its own
1 kHz loop: wake-up latency p99 per device, overruns per minute, and robotd's CPU use (user +
system seconds per wall second). Baseline: cyclictest with as many threads at the same
priority and interval. Late wake-ups (≥ one period, the ones that make a loop overrun) are
counted per minute the same way on both sides: per thread, from every sample. robotd and cyclictest alternate in short blocks per case,
so a stall of the shared VM (which makes every thread late at once) falls on both sides."""
import time

import benchlib as b

INTERVAL_US = 1000
HUMANOID = {"name": "humanoid", "driver": "sim", "rate_hz": 1000, "rt_priority": 80, "realtime": "prefer",
            "params": {"model": "bench 23-motor humanoid", "joint_count": 23, "imu": True}}


def robotd_block(programs, devices, seconds):
    """Per device: every wake-up latency sample (µs); overruns; robotd CPU cores."""
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, devices)) as robotd:
        names = [device["name"] for device in devices]
        before = {name: robotd.call(name, "loop_timing", {"reset": True})["overruns"] for name in names}
        cpu_start, wall_start = robotd.cpu_seconds(), time.monotonic()
        time.sleep(seconds)
        after = {name: robotd.call(name, "loop_timing", {"samples": True}) for name in names}
        cpu = (robotd.cpu_seconds() - cpu_start) / (time.monotonic() - wall_start)
    wake_us = {name: [ns / 1000 for ns in after[name]["wake_latency_ns"]] for name in names}
    overruns = sum(after[name]["overruns"] - before[name] for name in names)
    return wake_us, overruns, cpu


def cyclictest_block(threads, seconds):
    """Per thread: every latency sample (µs); late wake-ups (≥ one period)."""
    histograms, overflows = b.cyclictest(seconds, 80, INTERVAL_US, threads)
    samples = [b.histogram_samples_us(h, o, 10000) for h, o in zip(histograms, overflows)]
    late = sum(count for h in histograms for value, count in h.items() if value >= INTERVAL_US) + sum(overflows)
    return samples, late


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    blocks, seconds = (1, 2) if args.quick else (3, 4)
    cases = [("scale1", [b.sim_arm("arm0")]),
             ("scale4", [b.sim_arm(f"arm{i}") for i in range(4)]),
             ("scale8", [b.sim_arm(f"arm{i}") for i in range(8)]),
             ("humanoid", [HUMANOID])]
    rows, figures = [], {}
    for key, devices in cases:
        wake = {device["name"]: [] for device in devices}
        baseline = [[] for _ in devices]
        overruns = late = 0
        cpu = []
        for _ in range(blocks):
            block_wake, block_overruns, block_cpu = robotd_block(programs, devices, seconds)
            block_baseline, block_late = cyclictest_block(len(devices), seconds)
            for name, samples in block_wake.items():
                wake[name] += samples
            for thread, samples in enumerate(block_baseline):
                baseline[thread] += samples
            overruns += block_overruns
            late += block_late
            cpu.append(block_cpu)
        wake_p99 = {name: b.percentiles(samples)["p99"] for name, samples in wake.items()}
        robotd_late = sum(1 for samples in wake.values() for value in samples if value >= INTERVAL_US)
        base_p99 = max(b.percentiles(samples)["p99"] for samples in baseline)
        minutes = blocks * seconds / 60
        worst = max(wake_p99.values())
        mean_cpu = sum(cpu) / len(cpu)
        rows.append([key, len(devices), f"{worst:.1f}", f"{base_p99:.1f}", f"{overruns / minutes:.1f}",
                     f"{robotd_late / minutes:.1f}", f"{late / minutes:.1f}", f"{mean_cpu:.3f}"])
        figures.update({f"{key}_wake_p99_us": wake_p99, f"{key}_worst_wake_p99_us": worst,
                        f"{key}_baseline_wake_p99_us": base_p99,
                        f"{key}_overruns_per_min": round(overruns / minutes, 2),
                        f"{key}_late_per_min": round(robotd_late / minutes, 2),
                        f"{key}_baseline_late_per_min": round(late / minutes, 2),
                        f"{key}_robotd_cpu_cores": round(mean_cpu, 4)})
    print(f"scale: per case {blocks} × {seconds} s blocks, robotd and cyclictest (same thread count, SCHED_FIFO 80, "
          f"{INTERVAL_US} µs) alternating")
    print(b.table(["case", "devices", "worst wake p99 µs", "cyclictest p99 µs", "overruns/min", "late/min",
                   "cyclictest late/min", "robotd CPU cores"], rows))
    print("target: 8 devices with no more late wake-ups than cyclictest, robotd under 0.5 core")
    b.emit(figures)


if __name__ == "__main__":
    main()
