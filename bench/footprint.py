#!/usr/bin/env python3
"""Footprint: robotd's resident memory, locked memory and thread count once every
device is RUNNING, for the 7-device demo (config/robotd.json with its six simulators, started
as scripts/demo starts them, on private paths, ports and DDS domain) and for four simulated
6-joint arms. Read from /proc/<pid>/status a few times over some seconds of running; the
figure is the largest reading (resident memory only grows while the loops warm up)."""
import json
import re
import select
import socket
import subprocess
import tempfile
import time
from pathlib import Path

import benchlib as b

READY_TIMEOUT_S = 10.0
SIM_RT_PRIORITY = "10"  # as scripts/demo: below robotd's loops


def free_tcp_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def strip_comments(text):
    """config/robotd.json without its // comments (robotd allows them, json does not)."""
    out, in_string, i = [], False, 0
    while i < len(text):
        if in_string:
            if text[i] == "\\":
                out.append(text[i:i + 2])
                i += 2
                continue
            in_string = text[i] != '"'
        elif text[i] == '"':
            in_string = True
        elif text.startswith("//", i):
            i = text.find("\n", i)
            continue
        out.append(text[i])
        i += 1
    return "".join(out)


class DemoSimulators:
    """The six simulators of scripts/demo on private socket paths and ports, and the demo's
    devices pointed at them."""

    def __init__(self, bin_dir, scratch):
        self.bin_dir, self.scratch, self.processes = Path(bin_dir), Path(scratch), []

    def devices(self):
        text = (b.ROOT / "config" / "robotd.json").read_text()
        devices = {d["name"]: d for d in json.loads(strip_comments(text))["devices"]}
        piper = devices["piper"]["params"]["can"]
        piper["path"] = self.start("piper", "--standin", self.path("piper.sock"))
        parol6 = devices["parol6"]["params"]["serial"]
        parol6["device"] = self.start("parol6", "--pty", self.path("parol6.tty"))
        realman = devices["realman"]["params"]
        realman["port"] = int(self.start("realman", "--port", str(free_tcp_port())))
        xarm = devices["xarm"]["params"]
        xarm["port"], xarm["report"]["port"] = free_tcp_port(), free_tcp_port()
        self.start("xarm", "--port", str(xarm["port"]), "--report-port", str(xarm["report"]["port"]))
        pi_plus = devices["pi_plus"]["params"]
        buses = []
        for bus in pi_plus["buses"]:
            bus["can"]["path"] = self.path(f"pi-plus-{bus['name']}.sock")
            ids = sorted(m["id"] for m in pi_plus["motors"] if m["bus"] == bus["name"])
            buses += ["--bus", f"{bus['can']['path']}:{ids[0]}-{ids[-1]}"]
        self.start("hightorque", *buses)
        imu = pi_plus["imu"]["serial"]
        imu["device"] = self.start("imu", "--pty", self.path("imu.tty"))
        return list(devices.values())

    def path(self, name):
        return str(self.scratch / name)

    def start(self, vendor, *link):
        """Starts robotd-<vendor>-sim; returns the last link argument (its path or port)."""
        process = subprocess.Popen([str(self.bin_dir / f"robotd-{vendor}-sim"), *link, "--rt-priority",
                                    SIM_RT_PRIORITY, "--quiet"], stdout=subprocess.PIPE,
                                   stderr=subprocess.DEVNULL, text=True)
        self.processes.append(process)
        ready, _, _ = select.select([process.stdout], [], [], READY_TIMEOUT_S)
        if not ready or process.stdout.readline().strip() != "ready":
            raise RuntimeError(f"robotd-{vendor}-sim did not print \"ready\"")
        return link[-1]

    def stop(self):
        for process in self.processes:
            process.terminate()
        for process in self.processes:
            process.wait(timeout=10)
            process.stdout.close()


def memory_status(pid):
    """From /proc/<pid>: resident memory (VmRSS), locked and resident memory (smaps_rollup's Locked),
    locked address space (VmLck, what RLIMIT_MEMLOCK counts: with mlockall it includes untouched
    reservations, such as glibc's 64 MiB per malloc arena) in MiB, and the thread count."""
    status = Path(f"/proc/{pid}/status").read_text()
    rollup = Path(f"/proc/{pid}/smaps_rollup").read_text()

    def field(text, name):
        return int(re.search(rf"^{name}:\s+(\d+)", text, re.MULTILINE).group(1))

    return {"rss_mib": round(field(status, "VmRSS") / 1024, 1),
            "locked_resident_mib": round(field(rollup, "Locked") / 1024, 1),
            "locked_space_mib": round(field(status, "VmLck") / 1024, 1), "threads": field(status, "Threads")}


def measure(programs, devices, seconds):
    """The largest of a reading per second over `seconds`, once every device is RUNNING."""
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, devices)) as robotd:
        readings = []
        for _ in range(seconds):
            time.sleep(1.0)
            readings.append(memory_status(robotd.process.pid))
    return {key: max(r[key] for r in readings) for key in readings[0]}


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    seconds = 2 if args.quick else 10
    figures, rows = {}, []
    with tempfile.TemporaryDirectory(prefix="robotd-footprint-") as scratch:
        sims = DemoSimulators(programs.robotd.parent, scratch)
        try:
            cases = [("demo7", sims.devices()), ("sim4", [b.sim_arm(f"arm{i}") for i in range(4)])]
            for key, devices in cases:
                reading = measure(programs, devices, seconds)
                rows.append([key, len(devices), reading["rss_mib"], reading["locked_resident_mib"],
                             reading["locked_space_mib"], reading["threads"]])
                figures.update({f"footprint_{key}_{name}": value for name, value in reading.items()})
        finally:
            sims.stop()
    print(f"footprint: robotd once every device is RUNNING, the largest of {seconds} readings a second apart")
    print(b.table(["case", "devices", "VmRSS MiB", "locked resident MiB", "VmLck MiB", "threads"], rows))
    print("target: the 7-device demo under 48 MiB resident")
    b.emit(figures)


if __name__ == "__main__":
    main()
