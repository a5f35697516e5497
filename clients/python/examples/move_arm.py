#!/usr/bin/env python3
"""Acquire the simulated arm, move it, print its joint states, release it (the Python twin of
clients/cpp/examples/move_arm.cpp).

    build/bin/robotd --config config/robotd.json &                  # robotd with the simulated robots
    PYTHONPATH=clients/python clients/python/examples/move_arm.py   # this program
"""
import math
import sys
import time

import robotd


def main():
    with robotd.Client() as client:
        start = client.joint_state("arm", timeout=2.0)
        # Every motor of "arm"; if this program stops sending for 500 ms, robotd damps the arm.
        with client.session(device="arm", mode="position", on_timeout="damping", timeout=0.5) as session:
            print(f"session {session.session_id} on {len(session.motors)} motors")
            # Stream a smooth 2-second move (cosine blend) of every joint by +0.5 rad, at 100 Hz.
            # robotd rate-limits and interpolates it into its 1 kHz loop.
            t0 = time.monotonic()
            while (elapsed := time.monotonic() - t0) <= 2.0:
                blend = 0.5 - 0.5 * math.cos(math.pi * elapsed / 2.0)
                session.command(positions=[start.position[j] + 0.5 * blend for j in session.motors])
                time.sleep(0.01)
            # Hold the final target a moment, then print where the arm is.
            for _ in range(30):
                session.keepalive()
                time.sleep(0.01)
            end = client.joint_state("arm", timeout=2.0)
            for j, name in enumerate(end.names):
                print(f"{name:<8} {start.position[j]:+.3f} rad -> {end.position[j]:+.3f} rad  ({end.effort[j]:.3f} N·m)")
            session.release("keep")
            print("released")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except robotd.RobotdError as error:
        print(f"{type(error).__name__}: {error}", file=sys.stderr)
        sys.exit(1)
