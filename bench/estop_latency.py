#!/usr/bin/env python3
"""E-stop latency: how soon robotd's e-stop reaches the device, in every state the device can be
in, through a real robotd, its Python client and the real simulators.

Each sample engages the e-stop with the Python client (Client.estop, the /estop service), reads
robotd's own figure from its reply — from the moment the service latched the e-stop to the
moment the RT loop's driver write() that carried the e-stop frame returned ("reached 'arm' in
0.41 ms"), or "NOT confirmed on 'arm' (why)" when the loop could not hand the frame over — then
resets the e-stop, waits until the loop has seen the reset, and repeats.

Where the device is a vendor simulator (a separate process on loopback) it is also measured from
the outside: from just before the client sent /estop to the moment the simulator took the
vendor's stop command off its wire (each simulator reports that time, CLOCK_MONOTONIC; see
drivers/<vendor>/sim/README.md). The sim driver runs inside robotd: it has no outside view.

States of the simulated arm (driver sim): RUNNING idle; RUNNING while robotd_bench_stream
streams positions at 1 kHz; FAULT (a controller fault, raise_fault); the link lost (disconnect:
robotd must say NOT confirmed); during a recover the driver makes slow (slow_maintenance 5 s);
during a slow reset_zero; with no feedback since a re-initialisation (what the loop has before
any feedback, as in CONNECTING; device "quiet", which waits 60 s before faulting a silent
driver). Each vendor: RUNNING, and during a recover that waits for the device (plus reset_zero
for the PiPER and the HighTorque motors). The figures are in docs/safety.md, "Measured e-stop
latency".

  bench/estop_latency.py --build-dir build            ~3 minutes
  bench/estop_latency.py --build-dir build --quick    a few samples per state (CI)"""
import json
import os
import re
import select
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import benchlib as b
import vendor_sims

SLOW_MS = 5000  # how long a slowed or waiting maintenance would take without the e-stop
REACHED = re.compile(r"reached '([^']+)' in ([0-9.]+) ms")
NOT_CONFIRMED = re.compile(r"NOT confirmed on '([^']+)' \((.*)\): robotd cannot reach it")


def import_client(build_dir):
    """The robotd Python package of this tree, on the build's librobotd_c."""
    os.environ.setdefault("ROBOTD_C_LIBRARY", str(Path(build_dir).resolve() / "lib" / "librobotd_c.so"))
    sys.path.insert(0, str(b.ROOT / "clients" / "python"))
    import robotd
    return robotd


class Sample:
    """One e-stop: robotd's figure (ms, or None with the reason it gave) and the outside one."""

    def __init__(self, message, device):
        reached = [m for m in REACHED.finditer(message) if m.group(1) == device]
        refused = [m for m in NOT_CONFIRMED.finditer(message) if m.group(1) == device]
        self.robotd_ms = float(reached[0].group(2)) if reached else None
        self.why = refused[0].group(2) if refused else ("" if reached else f"unparsed reply: {message}")
        self.wire_ms = None
        self.note = ""


class Target:
    """A robotd device the bench engages, with its client and (for a vendor) its simulator."""

    def __init__(self, robotd_module, client, device, sim=None):
        self.robotd, self.client, self.device, self.sim = robotd_module, client, device, sim

    def state(self):
        return next(d.state for d in self.client.devices() if d.name == self.device)

    def wait_state(self, wanted, timeout_s=10.0, gave_up=lambda: None):
        """Waits until the device is in state `wanted`; raises after `timeout_s`, or as soon as
        gave_up() says why it will not come."""
        deadline = time.monotonic() + timeout_s
        while (state := self.state()) != wanted:
            why = gave_up()
            if why is not None or time.monotonic() > deadline:
                raise RuntimeError(f"'{self.device}' stayed {state.name}, not {wanted.name}" +
                                   (f": {why}" if why else ""))
            time.sleep(0.002)

    def call(self, op, args=None, timeout=10.0):
        return self.client.call(self.device, op, args or {}, timeout=timeout)

    def engage(self, wire=True):
        started_ns = time.monotonic_ns()
        sample = Sample(self.client.estop(self.device, reason="estop_latency bench"), self.device)
        if wire and self.sim is not None and sample.robotd_ms is not None:
            seen_ns = self.sim.wait_estop_seen(started_ns)
            sample.wire_ms = (seen_ns - started_ns) / 1e6 if seen_ns is not None else None
        return sample

    def reset(self):
        """Resets the e-stop and returns once the loop has seen it (a /device_status sample says
        so); the device's state then."""
        self.client.reset_estop(self.device)
        deadline = time.monotonic() + 5
        while (status := self.client.device_status(self.device, timeout=1.0)).estop_engaged:
            if time.monotonic() > deadline:
                raise RuntimeError(f"'{self.device}': the e-stop reset was not seen by the loop within 5 s")
        return status

    def engage_and_reset(self):
        sample = self.engage()
        self.reset()
        return sample

    def reset_to_running(self, sample):
        """Resets the e-stop of a device that was RUNNING before it; a reset that leaves it FAULT
        is noted on the sample and recovered, so that the next sample starts RUNNING again."""
        status = self.reset()
        if status.state == self.robotd.DeviceState.FAULT:
            sample.note = f"the reset left it {status.state_text}; recovered"
            recover_until_running(self)
        if self.sim is not None:
            self.sim.wait_released()

    def cycle(self):
        """Engages and resets the e-stop of a RUNNING device."""
        sample = self.engage()
        self.reset_to_running(sample)
        return sample

    def warm_up(self):
        """One e-stop not measured: the first /estop call also finds robotd's service."""
        self.cycle()


class Maintenance(threading.Thread):
    """A recover (device_call) running on its own thread, as a client's call would; keeps its
    outcome: "ok", or robotd's refusal."""

    def __init__(self, target):
        super().__init__()
        self.target, self.outcome = target, None

    def run(self):
        try:
            self.target.call("recover", timeout=SLOW_MS / 1000 + 5)
            self.outcome = "ok"
        except Exception as error:  # noqa: BLE001 — a refusal is the expected outcome
            self.outcome = str(error)


class ResetZeroTool:
    """robotd_bench_reset_zero on a device: one /reset_zero per go()."""

    def __init__(self, programs, domain, device, motors=(), timeout_ms=SLOW_MS + 2000):
        command = [programs.tool("robotd_bench_reset_zero"), "--domain", str(domain), "--device", device,
                   "--timeout-ms", str(timeout_ms)]
        if motors:
            command += ["--motors", *map(str, motors)]
        self.process = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        if json.loads(self.process.stdout.readline() or "{}").get("ready") is not True:
            raise RuntimeError("robotd_bench_reset_zero did not start")

    def go(self):
        self.process.stdin.write("go\n")
        self.process.stdin.flush()

    def result(self):
        return json.loads(self.process.stdout.readline())

    def answered_early(self):
        """robotd's answer, if it came already (before the bench engaged the e-stop)."""
        ready, _, _ = select.select([self.process.stdout], [], [], 0)
        return f"reset_zero: {self.result()['message']}" if ready else None

    def close(self):
        self.process.stdin.close()
        self.process.wait(timeout=15)


def during_maintenance(target, start, finish, ended, was_running):
    """Starts a maintenance (start()), engages the e-stop once the device is in MAINTENANCE, and
    checks with finish() that the maintenance ended aborted by it; ended() says why it ended
    before that, if it did."""
    start()
    target.wait_state(target.robotd.DeviceState.MAINTENANCE, gave_up=ended)
    sample = target.engage()
    outcome = finish()
    if "aborted" not in outcome:
        sample.note = f"maintenance not aborted: {outcome}"
    if was_running:
        target.reset_to_running(sample)
    else:
        target.reset()
    return sample


def recover_sample(target, prepare):
    prepare()
    recover = Maintenance(target)
    was_running = target.state() == target.robotd.DeviceState.RUNNING
    return during_maintenance(target, recover.start, lambda: (recover.join(), recover.outcome)[1],
                              lambda: None if recover.outcome is None else f"recover: {recover.outcome}",
                              was_running)


def reset_zero_sample(target, tool, prepare):
    prepare()

    def finish():
        result = tool.result()
        return "ok" if result["ok"] else result["message"]

    return during_maintenance(target, tool.go, finish, lambda: tool.answered_early(), was_running=True)


def repeat(count, take):
    samples = []
    for _ in range(count):
        samples.append(take())
        time.sleep(0.001 + 0.003 * (len(samples) % 5) / 5)  # vary the phase against robotd's tick
    return samples


# ---- the simulated arm -----------------------------------------------------------------------

def sim_states(robotd_module, programs, count):
    devices = [b.sim_arm("arm", reconnect_interval_ms=0),
               b.sim_arm("quiet", reconnect_interval_ms=0, feedback_timeout_ms=60000)]
    results = {}
    with b.private_domain() as domain, b.Robotd(programs, domain, status_config(domain, devices)):
        client = robotd_module.Client(domain, node_name="estop_bench")
        arm = Target(robotd_module, client, "arm")
        arm.warm_up()
        running = robotd_module.DeviceState.RUNNING

        results["sim_running"] = repeat(count, arm.cycle)

        stream = b.start_tool(programs, "robotd_bench_stream", "--domain", domain, "--device", "arm", "--rate", 1000,
                              "--seconds", 600)
        try:
            time.sleep(1.0)  # granted, streaming
            results["sim_streaming"] = repeat(count, arm.cycle)
        finally:
            stream.kill()
            stream.wait()
        time.sleep(0.6)  # its session times out (500 ms): recover is refused while it holds the arm

        arm.call("raise_fault", {"code": 7, "text": "injected by the e-stop bench"})
        arm.wait_state(robotd_module.DeviceState.FAULT)
        results["sim_fault"] = repeat(count, arm.engage_and_reset)
        arm.call("recover")

        def link_lost():
            arm.call("disconnect")
            arm.wait_state(robotd_module.DeviceState.FAULT)
            sample = arm.engage()
            arm.reset()
            arm.call("recover")
            arm.wait_state(running)
            return sample

        results["sim_link_lost"] = repeat(count, link_lost)
        results["sim_recover"] = repeat(
            count, lambda: recover_sample(arm, lambda: arm.call("slow_maintenance", {"ms": SLOW_MS})))
        tool = ResetZeroTool(programs, domain, "arm")
        try:
            results["sim_reset_zero"] = repeat(
                count, lambda: reset_zero_sample(arm, tool, lambda: arm.call("slow_maintenance", {"ms": SLOW_MS})))
        finally:
            tool.close()

        # No feedback since a re-initialisation: a reset_zero re-initialises the loop, and the
        # driver then says nothing (its reset_zero fails after 100 ms waiting for feedback).
        quiet = Target(robotd_module, client, "quiet")
        quiet.call("stop_feedback", {"enabled": True})
        tool = ResetZeroTool(programs, domain, "quiet", timeout_ms=100)
        try:
            tool.go()
            tool.result()
        finally:
            tool.close()
        results["sim_no_feedback"] = repeat(count, quiet.engage_and_reset)
        quiet.call("stop_feedback", {"enabled": False})
        quiet.wait_state(running)
        client.close()
    return results


def status_config(domain, devices):
    config = b.config(domain, devices)
    config["daemon"]["status_rate_hz"] = 100  # the reset is seen on /device_status within 10 ms
    return config


# ---- the vendor simulators -------------------------------------------------------------------

def vendor_states(robotd_module, programs, vendor, count):
    """RUNNING, and during maintenance that waits for the device, for one vendor simulator."""
    with tempfile.TemporaryDirectory(prefix=f"robotd-estop-{vendor}-") as scratch, \
            vendor_sims.SIMULATORS[vendor](programs.robotd.parent, scratch) as sim, \
            b.private_domain() as domain:
        device = sim.device()
        device["reconnect_interval_ms"] = 0  # only the bench's recover calls reconnect
        with b.Robotd(programs, domain, status_config(domain, [device])):
            client = robotd_module.Client(domain, node_name="estop_bench")
            target = Target(robotd_module, client, vendor, sim)
            target.warm_up()
            results = {f"{vendor}_running": repeat(count, target.cycle)}
            results.update(VENDOR_MAINTENANCE[vendor](robotd_module, programs, domain, target, count))
            client.close()
    return results


def piper_maintenance(robotd_module, programs, domain, target, count):
    sim = target.sim
    results = {}
    # reset_zero of joint 5 waits for its acknowledge, which the arm does not send.
    tool = ResetZeroTool(programs, domain, "piper", motors=[4])
    try:
        def zeroing():
            sample = reset_zero_sample(target, tool, lambda: sim.control({"op": "drop_replies", "enabled": True}))
            sim.control({"op": "drop_replies", "enabled": False})
            return sample

        results["piper_reset_zero"] = repeat(count, zeroing)
    finally:
        tool.close()
    # A joint driver fault that stays: recover clears the errors and waits for a clean status.
    sim.control({"op": "raise_error", "joint": 1, "driver_status_bits": 0x04})
    target.wait_state(robotd_module.DeviceState.FAULT)
    results["piper_recover"] = repeat(count, lambda: recover_sample(target, lambda: None))
    sim.control({"op": "clear_error"})
    recover_until_running(target)
    return results


def parol6_maintenance(robotd_module, programs, domain, target, count):
    # A silent board is a lost link; recover reopens the line and waits for the board's first
    # reply. The silent board drops every frame: nothing reaches it, whatever robotd writes.
    sim = target.sim

    def silent_recover():
        sim.control({"op": "silence", "ms": 60000})
        target.wait_state(robotd_module.DeviceState.FAULT)
        sample = recover_sample(target, lambda: None)
        sim.control({"op": "silence", "ms": 0})
        recover_until_running(target)
        return sample

    return {"parol6_recover": repeat(count, silent_recover)}


def recover_with_a_dropped_reply(robotd_module, target, raise_error, name, count):
    """A controller error; recover's clear-error takes effect but its reply is dropped, so
    recover waits for it."""
    sim = target.sim

    def waiting_recover():
        sim.control(raise_error)
        target.wait_state(robotd_module.DeviceState.FAULT)
        sample = recover_sample(target, lambda: sim.control({"op": "drop_replies", "count": 1}))
        recover_until_running(target)
        return sample

    return {name: repeat(count, waiting_recover)}


def realman_maintenance(robotd_module, programs, domain, target, count):
    return recover_with_a_dropped_reply(robotd_module, target, {"op": "raise_error", "code": 0x5001},
                                        "realman_recover", count)


def xarm_maintenance(robotd_module, programs, domain, target, count):  # C31: a collision
    return recover_with_a_dropped_reply(robotd_module, target, {"op": "error", "code": 31}, "xarm_recover", count)


def hightorque_maintenance(robotd_module, programs, domain, target, count):
    sim = target.sim
    results = {}
    # reset_zero holds the motors at zero torque for zero_settle_ms (5 s) before zeroing.
    tool = ResetZeroTool(programs, domain, "hightorque")
    try:
        results["hightorque_reset_zero"] = repeat(count, lambda: reset_zero_sample(target, tool, lambda: None))
    finally:
        tool.close()
    # A motor fault that stays: recover sends STOP until it clears (reply_timeout_ms, 5 s here).
    # The faulted motor free-wheels and ignores every command; the others brake.
    sim.control({"op": "set_fault", "bus": 0, "motor": 1, "code": 0x20})
    target.wait_state(robotd_module.DeviceState.FAULT)
    results["hightorque_recover"] = repeat(count, lambda: recover_sample(target, lambda: None))
    sim.control({"op": "clear_fault", "bus": 0, "motor": 1})
    recover_until_running(target)
    return results


VENDOR_MAINTENANCE = {"piper": piper_maintenance, "parol6": parol6_maintenance, "realman": realman_maintenance,
                      "xarm": xarm_maintenance, "hightorque": hightorque_maintenance}


def recover_until_running(target, timeout_s=10.0):
    deadline = time.monotonic() + timeout_s
    while True:
        try:
            target.call("recover")
            return
        except Exception:  # noqa: BLE001 — the device may need a moment to answer again
            if time.monotonic() > deadline:
                raise
            time.sleep(0.1)


# ---- report ----------------------------------------------------------------------------------

def general(text):
    """A note without what changes from one sample to the next (a silence's length, a scratch path)."""
    return re.sub(r"/tmp/\S+", "<scratch>", re.sub(r"\b\d+ ms\b", "N ms", text))


def summarize(key, samples):
    """Figures and a table row for one state."""
    reached = [s.robotd_ms for s in samples if s.robotd_ms is not None]
    wire = [s.wire_ms for s in samples if s.wire_ms is not None]
    figures = {f"estop_{key}_samples": len(samples),
               f"estop_{key}_reached_fraction": round(len(reached) / len(samples), 3) if samples else 0.0}
    row = [key, len(samples), len(reached)]
    for name, values in (("", reached), ("wire_", wire)):
        if values:
            stats = b.percentiles(values)
            figures.update({f"estop_{key}_{name}p50_ms": stats["p50"], f"estop_{key}_{name}p99_ms": stats["p99"],
                            f"estop_{key}_{name}max_ms": stats["max"]})
            row.append(f"{stats['p50']:.2f} / {stats['p99']:.2f} / {stats['max']:.2f}")
        else:
            row.append("—")
    notes = sorted({general(s.why) for s in samples if s.why} | {general(s.note) for s in samples if s.note})
    if samples and samples[0].robotd_ms is not None and not wire and key.split("_")[0] in vendor_sims.SIMULATORS:
        notes.append("the simulator never saw the stop command")
    row.append("; ".join(notes))
    return figures, row


def main():
    parser = b.common_arguments(__doc__)
    parser.add_argument("--vendors", default=",".join(vendor_sims.SIMULATORS),
                        help="vendor simulators to measure (comma-separated; '' for none)")
    args = parser.parse_args()
    programs = b.Programs(args.build_dir)
    robotd_module = import_client(args.build_dir)
    count = 5 if args.quick else 200
    vendor_count = 3 if args.quick else 50
    started = time.monotonic()

    results = sim_states(robotd_module, programs, count)
    for vendor in filter(None, args.vendors.split(",")):
        results.update(vendor_states(robotd_module, programs, vendor, vendor_count))

    figures, rows = {}, []
    for key, samples in results.items():
        state_figures, row = summarize(key, samples)
        figures.update(state_figures)
        rows.append(row)
    print(f"e-stop latency: /estop engaged → the driver write() that carried the e-stop frame returned (robotd's "
          f"reply), and /estop sent → the simulator took the stop command off its wire (outside), in ms; "
          f"{time.monotonic() - started:.0f} s")
    print(b.table(["state", "samples", "reached", "robotd p50 / p99 / max", "outside p50 / p99 / max", "notes"], rows))
    b.emit(figures)


if __name__ == "__main__":
    main()
