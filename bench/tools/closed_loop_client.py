#!/usr/bin/env python3
"""The Python twin of robotd_bench_closed_loop: a torque session on every motor of a device, a PD
law (each joint held at where it started plus a slow sine) answering each state of
`session.ticks()` for --seconds, timed per tick on CLOCK_MONOTONIC (time.monotonic_ns(), the clock
robotd stamps TickState with). Then robotd's SessionInfo for the session. Prints one JSON line
with the same fields as robotd_bench_closed_loop."""
import argparse
import json
import math
import sys
import time

import robotd


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--domain", type=int, required=True)
    parser.add_argument("--device", default="arm")
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--kp", type=float, default=20.0)  # N·m/rad
    parser.add_argument("--kd", type=float, default=1.0)  # N·m·s/rad
    args = parser.parse_args()

    fields = ("tick", "deadline_ns", "ready_ns", "published_ns", "received_ns", "sent_ns")
    records = {field: [] for field in fields}
    seen, skipped, first, last = 0, 0, 0, 0
    with robotd.Client(args.domain, node_name="bench_closed_loop_py") as client:
        with client.session(device=args.device, mode="torque", on_timeout="damping", timeout=0.2,
                            on_release="damping", closed_loop=True) as session:
            start = None
            for state in session.ticks(duration=args.seconds):
                received = time.monotonic_ns()
                if start is None:
                    start, first = state.position, state.tick
                else:
                    skipped += state.tick - last - 1
                t = state.deadline_steady_ns * 1e-9
                offset = 0.2 * math.sin(2.0 * math.pi * 0.5 * t)
                torques = [args.kp * (q0 + offset - q) - args.kd * dq
                           for q0, q, dq in zip(start, state.position, state.velocity)]
                sent = time.monotonic_ns()
                session.answer(state, torques=torques)
                seen, last = seen + 1, state.tick
                for field, value in zip(fields, (state.tick, state.deadline_steady_ns, state.state_ready_steady_ns,
                                                 state.published_steady_ns, received, sent)):
                    records[field].append(value)
            # Right after the loop: the newest /session_status still speaks of the run.
            info = session.info(timeout=2.0)
    result = {"device": args.device,
              "report": {"ticks_seen": seen, "ticks_answered": seen, "ticks_skipped": skipped, "first_tick": first,
                         "last_tick": last},
              "info": {"closed_loop": info.closed_loop, "ticks_to_answer": info.ticks_to_answer,
                       "ticks_answered_in_time": info.ticks_answered_in_time,
                       "ticks_answered_late": info.ticks_answered_late, "ticks_unanswered": info.ticks_unanswered,
                       "command_success_rate": info.command_success_rate},
              **records}
    print(json.dumps(result), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
