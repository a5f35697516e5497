#!/usr/bin/env python3
"""Command latency: from the moment a client publishes a ControlCommand (its CLOCK_MONOTONIC
time, carried in the command) to the moment the driver's write() receives it, for a client
streaming at 1 kHz. Baseline: one-way DDS latency (round trip / 2) of the same message type and
size with the same QoS on the same loopback configuration. Alternating blocks.

A command waits in robotd's mailbox for the next tick, so the latency depends on when, within
robotd's 1 ms period, the client publishes. A client with its own 1 kHz clock keeps one phase
for a whole run, so the streaming client sweeps its phase once through the period over the run
(period 1 ms + 1 ms / (rate × block length)); the distribution then covers every phase."""
import time

import benchlib as b


def robotd_block(programs, seconds):
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, [b.sim_arm()])) as robotd:
        streamer = b.start_tool(programs, "robotd_bench_stream", "--domain", domain, "--device", "arm", "--rate",
                                1000, "--seconds", seconds + 1.5, "--sweep-seconds", seconds)
        time.sleep(1.0)
        robotd.call("arm", "command_latency", {"reset": True})
        time.sleep(seconds)
        latency = robotd.call("arm", "command_latency", {"samples": True})
        stream = b.finish_tool(streamer)
    return [ns / 1000 for ns in latency["samples_ns"]], stream["failed"]


def dds_block(programs, seconds):
    with b.private_domain() as domain:
        pong = b.start_tool(programs, "robotd_bench_pingpong", "--domain", domain, "--role", "pong")
        try:
            ping = b.finish_tool(b.start_tool(programs, "robotd_bench_pingpong", "--domain", domain, "--role", "ping",
                                              "--rate", 1000, "--seconds", seconds))
        finally:
            pong.kill()
            pong.wait()
    return [ns / 1000 for ns in ping["oneway_ns"]], ping["lost"]


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    blocks, seconds = (1, 2) if args.quick else (2, 5)  # 10 s of streaming in total
    robotd_us, dds_us, failed, lost = [], [], 0, 0
    for _ in range(blocks):
        block, block_failed = robotd_block(programs, seconds)
        robotd_us += block
        failed += block_failed
        block, block_lost = dds_block(programs, seconds)
        dds_us += block
        lost += block_lost
    cmd, dds = b.percentiles(robotd_us), b.percentiles(dds_us)
    print(f"command latency: {blocks} × {seconds} s at 1 kHz, client publish → driver write(), alternating with a "
          "DDS ping-pong baseline")
    print(b.table(b.DISTRIBUTION_HEADERS, [b.distribution_row("client → driver write()", cmd),
                                            b.distribution_row("DDS one-way (rtt/2)", dds)]))
    print(f"p50 difference {cmd['p50'] - dds['p50']:.1f} µs (target ≤ 600), p99 {cmd['p99']:.1f} µs "
          f"(target ≤ 1300); commands the client failed to send: {failed}; pings lost: {lost}")
    b.emit({"cmd_latency_p50_us": cmd["p50"], "cmd_latency_p99_us": cmd["p99"], "cmd_latency_p999_us": cmd["p999"],
            "cmd_latency_max_us": cmd["max"], "cmd_latency_samples": cmd["count"],
            "dds_oneway_p50_us": dds["p50"], "dds_oneway_p99_us": dds["p99"], "dds_oneway_p999_us": dds["p999"],
            "dds_oneway_max_us": dds["max"], "cmd_latency_minus_dds_p50_us": round(cmd["p50"] - dds["p50"], 1)})


if __name__ == "__main__":
    main()
