#!/usr/bin/env python3
"""The plain-DDS example (examples/plain_dds: C, the IDL and the Cyclone C API only) against a real
robotd driving a simulated arm on a DDS domain of its own, on loopback.

Passes when the example exits 0 after reporting that joint 0 moved, and robotctl, a separate
observer, then sees joint 0 where the example left it, every one of the example's commands
accepted (none rejected), and no session left open.

robotd stops when this script ends, however it ends (an exception, SIGTERM, Ctrl-C, CTest's
timeout, SIGKILL): it runs under a small sh guard whose stdin is a pipe only this script holds.
When the script is gone the kernel closes the pipe, and the guard sends robotd SIGTERM, so robotd
ends cleanly (and, in a sanitizer build, runs its leak check) rather than being killed."""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from test_domain import claim_domain_id  # noqa: E402  (tests/support)

# Runs "$@" (robotd) until its stdin, the pipe from this script, closes; then stops it with SIGTERM
# and exits with its status. An asynchronous command of a non-interactive sh reads /dev/null.
GUARD = '"$@" & robotd=$!; cat > /dev/null; kill -TERM "$robotd" 2>/dev/null; wait "$robotd"'


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
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(128 + signal.SIGTERM))  # run the finally below

    domain, lock = claim_domain_id()
    config = {
        "daemon": {"log_level": "info", "status_rate_hz": 20, "session_status_period_ms": 200},
        "dds": {"domain_id": domain, "interface": "127.0.0.1", "multicast": False, "peers": ["127.0.0.1"]},
        "devices": [{"name": "arm", "driver": "sim", "rate_hz": 1000, "realtime": "prefer",
                     "params": {"joint_count": 6}}],
    }
    with lock, tempfile.NamedTemporaryFile("w", suffix=".json") as config_file, \
            tempfile.TemporaryFile("w+") as log:
        json.dump(config, config_file)
        config_file.flush()
        # A session of its own: Ctrl-C on the terminal reaches this script, which stops robotd.
        daemon = subprocess.Popen(["/bin/sh", "-c", GUARD, "robotd-guard", args.robotd, "--config", config_file.name],
                                  stdin=subprocess.PIPE, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        status = 0
        try:
            check(args, domain)
        except (AssertionError, subprocess.TimeoutExpired) as failure:
            print(f"FAILED: {failure}")
            status = 1
        finally:
            daemon.stdin.close()  # the guard stops robotd
            try:
                daemon.wait(timeout=25)
            except subprocess.TimeoutExpired:
                os.killpg(daemon.pid, signal.SIGKILL)
                daemon.wait()
        if daemon.returncode != 0:
            print(f"FAILED: robotd exited with status {daemon.returncode} (128 + n: killed by signal n)")
            status = 1
        if status != 0:
            log.seek(0)
            print("robotd's log:\n" + log.read())
    return status


if __name__ == "__main__":
    sys.exit(main())
