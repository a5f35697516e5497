#!/usr/bin/env python3
"""The plain-DDS example (examples/plain_dds: C, the IDL and the Cyclone C API only) against a real
robotd driving a simulated arm on a DDS domain of its own, on loopback.

Passes when the example exits 0 after reporting that joint 0 moved, and robotctl, a separate
observer, then sees joint 0 where the example left it, every one of the example's commands
accepted (none rejected), and no session left open.

robotd runs under tests/support/robotd_daemon.py, which stops it however this script ends."""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from robotd_daemon import RobotdDaemon, sim_arm  # noqa: E402  (tests/support)


def robotctl(args, domain, *verb):
    result = subprocess.run([args.robotctl, "--domain", str(domain), *verb], capture_output=True, text=True,
                            timeout=20)
    if result.returncode != 0:
        raise AssertionError(f"robotctl {' '.join(verb)} failed:\n{result.stdout}{result.stderr}")
    return result.stdout


def sample(args, domain, topic):
    """The next sample of `topic` as JSON, as robotctl prints it."""
    return json.loads(robotctl(args, domain, "echo", topic, "--json", "--count", "1").splitlines()[0])


def check(args, domain):
    environment = dict(os.environ)
    environment.pop("CYCLONEDDS_URI", None)  # the example's own loopback configuration
    example = subprocess.run([args.example, str(domain), "arm"], capture_output=True, text=True, timeout=60,
                             env=environment)
    print(f"$ {os.path.basename(args.example)} {domain} arm  -> exit {example.returncode}")
    print(example.stdout + example.stderr, end="")
    if example.returncode != 0:
        raise AssertionError(f"the example exited {example.returncode}")
    moved = re.search(r"joint 0: (\S+) rad -> (\S+) rad \(moved ([-+]\S+) rad\)", example.stdout)
    if moved is None or abs(float(moved.group(3))) < 0.15:
        raise AssertionError("the example did not report joint 0 moving by at least 0.15 rad")
    final_rad = float(moved.group(2))

    state = sample(args, domain, "joint_states")
    print(f"robotctl: joint 0 of '{state['header']['frame_id']}' at {state['position'][0]:.3f} rad")
    if abs(state["position"][0]) < 0.15 or abs(state["position"][0] - final_rad) > 0.05:
        raise AssertionError(f"robotctl sees joint 0 at {state['position'][0]}, not moved to {final_rad}")

    commands = sample(args, domain, "device_status")["commands"]
    print(f"robotctl: commands {commands}")
    rejected = {key: value for key, value in commands.items() if key.startswith("rejected_") and value}
    if commands["accepted"] < 100 or rejected or commands["received"] != commands["accepted"]:
        raise AssertionError("robotd did not accept every command of the example")

    sessions = sample(args, domain, "session_status")
    if sessions["state"] != "idle":
        raise AssertionError(f"a session is still open after the example released: {sessions}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--robotd", required=True)
    parser.add_argument("--example", required=True)
    parser.add_argument("--robotctl", required=True)
    args = parser.parse_args()
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(128 + signal.SIGTERM))  # run the with block's exit

    status = 0
    with RobotdDaemon(args.robotd, [sim_arm()]) as daemon:
        try:
            check(args, daemon.domain_id)
        except (AssertionError, subprocess.TimeoutExpired) as failure:
            print(f"FAILED: {failure}")
            status = 1
    if daemon.returncode != 0:
        print(f"FAILED: robotd exited with status {daemon.returncode} (128 + n: killed by signal n)")
        status = 1
    if status != 0:
        print("robotd's log:\n" + daemon.log())
    return status


if __name__ == "__main__":
    sys.exit(main())
