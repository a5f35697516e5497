#!/usr/bin/env python3
"""Closed-loop PD control of the simulated arm through robotd (the Python twin of
clients/cpp/examples/pd_control.cpp): each tick's state (position q, velocity dq) comes to the loop,
whose torques tau = kp (q_ref - q) - kd dq answer it and are applied on the next tick.

    build/bin/robotd --config config/robotd.json &                    # robotd with the simulated robots
    PYTHONPATH=clients/python clients/python/examples/pd_control.py   # this program
"""
import sys

import robotd

STEP_RAD = 0.3  # each joint's reference: where it started + 0.3 rad
KP = 20.0  # N·m/rad: with the sim arm's 0.05 kg·m², about 3 Hz
KD = 1.0  # N·m·s/rad: damped (ζ ≈ 0.65 with the joint's own damping)


def main():
    with robotd.Client() as client:
        # Torques for every motor of "arm"; robotd damps the arm if the answers stop for 500 ms, and
        # warns when fewer than 90 % of the last 100 ticks were answered in time.
        with client.session(device="arm", mode="torque", on_timeout="damping", timeout=0.5, on_release="damping",
                            closed_loop=True, min_command_success_rate=0.9, on_low_success_rate="warn") as session:
            reference, answered, first, last = None, 0, None, None
            for state in session.ticks(duration=3.0):
                if reference is None:
                    reference = [q + STEP_RAD for q in state.position]
                    first = state.tick
                session.answer(state, torques=[KP * (r - q) - KD * dq for r, q, dq in
                                               zip(reference, state.position, state.velocity)])
                answered, last = answered + 1, state.tick
            print(f"{answered} ticks answered (ticks {first}..{last}, {last - first + 1 - answered} skipped)")
            final = session.next_tick(timeout=1.0)
            for j, (q, r) in enumerate(zip(final.position, reference)):
                print(f"joint {j + 1}: {q:+.3f} rad (reference {r:+.3f})")
            info = session.info()
            print(f"robotd: {info.ticks_answered_in_time} of {info.ticks_to_answer} ticks answered in time "
                  f"(command success rate {100 * info.command_success_rate:.1f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
