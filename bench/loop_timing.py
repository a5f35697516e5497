#!/usr/bin/env python3
"""Loop timing: the wake-up latency (actual wake − deadline) and execution time per tick of a
device's RT loop at 1 kHz, with robotd running the simulated 6-joint arm and a client streaming
commands at 1 kHz. Baseline: cyclictest at the same priority, interval and duration, run alone.
The two alternate in many short blocks (robotd, cyclictest, robotd, cyclictest, …): a noisy
neighbour on a shared VM comes in bursts of a few seconds, and short blocks let a burst fall on
both sides instead of spoiling one long block. Both hold the same CPU wake-up latency request
(/dev/cpu_dma_latency = 0), cyclictest by default and robotd by daemon.cpu_dma_latency_us."""
import statistics
import time

import benchlib as b

PRIORITY = 80
INTERVAL_US = 1000


def robotd_block(programs, seconds):
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, [b.sim_arm()])) as robotd:
        streamer = b.start_tool(programs, "robotd_bench_stream", "--domain", domain, "--device", "arm", "--rate",
                                1000, "--seconds", seconds + 2)
        time.sleep(1.0)  # the session is up and streaming
        robotd.call("arm", "loop_timing", {"reset": True})
        time.sleep(seconds)
        timing = robotd.call("arm", "loop_timing", {"samples": True})
        b.finish_tool(streamer)
    return ([ns / 1000 for ns in timing["wake_latency_ns"]], [ns / 1000 for ns in timing["execution_ns"]],
            timing["overruns"])


def cyclictest_block(seconds):
    histograms, overflows = b.cyclictest(seconds, PRIORITY, INTERVAL_US)
    return b.histogram_samples_us(histograms[0], overflows[0], 10000)


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    blocks, seconds = (1, 2) if args.quick else (8, 3)
    wake, execution, baseline, per_block, overruns = [], [], [], [], 0
    for block in range(blocks):
        block_wake, block_exec, block_overruns = robotd_block(programs, seconds)
        block_baseline = cyclictest_block(seconds)
        wake += block_wake
        execution += block_exec
        baseline += block_baseline
        overruns += block_overruns
        block_ratio = b.ratio(b.percentiles(block_wake)["p99"], b.percentiles(block_baseline)["p99"])
        per_block.append([block + 1, f"{b.percentiles(block_wake)['p99']:.1f}",
                          f"{b.percentiles(block_baseline)['p99']:.1f}", block_ratio])

    wake_stats, exec_stats, base_stats = b.percentiles(wake), b.percentiles(execution), b.percentiles(baseline)
    print(f"loop timing: {blocks} × {seconds} s blocks, robotd and cyclictest alternating "
          f"(SCHED_FIFO {PRIORITY}, {INTERVAL_US} µs)")
    print(b.table(b.DISTRIBUTION_HEADERS, [b.distribution_row("robotd wake latency", wake_stats),
                                            b.distribution_row("cyclictest latency", base_stats),
                                            b.distribution_row("robotd tick execution", exec_stats)]))
    print(b.table(["block", "robotd wake p99 µs", "cyclictest p99 µs", "ratio"], per_block))
    median_ratio = round(statistics.median(row[3] for row in per_block), 3)
    print(f"wake p99 ratio robotd/cyclictest: pooled {b.ratio(wake_stats['p99'], base_stats['p99'])}, "
          f"median of blocks {median_ratio} (target ≤ 1.25); robotd overruns: {overruns}")
    b.emit({"loop_wake_p50_us": wake_stats["p50"], "loop_wake_p99_us": wake_stats["p99"],
            "loop_wake_p999_us": wake_stats["p999"], "loop_wake_max_us": wake_stats["max"],
            "loop_exec_p50_us": exec_stats["p50"], "loop_exec_p99_us": exec_stats["p99"],
            "loop_exec_p999_us": exec_stats["p999"], "loop_exec_max_us": exec_stats["max"],
            "loop_overruns": overruns,
            "baseline_wake_p50_us": base_stats["p50"], "baseline_wake_p99_us": base_stats["p99"],
            "baseline_wake_p999_us": base_stats["p999"], "baseline_wake_max_us": base_stats["max"],
            "wake_p99_ratio": b.ratio(wake_stats["p99"], base_stats["p99"]),
            "wake_p99_ratio_median_of_blocks": median_ratio,
            "loop_timing_blocks": blocks, "loop_timing_block_seconds": seconds})


if __name__ == "__main__":
    main()
