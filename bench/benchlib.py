"""What every robotd bench shares: paths to the built programs, a private DDS domain, a robotd
process with a generated config, robotctl calls, the cyclictest baseline, percentiles, tables
and the JSON result line. Python 3 standard library only."""
import argparse
import contextlib
import fcntl
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def common_arguments(description):
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--build-dir", default=os.environ.get("ROBOTD_BUILD_DIR", str(ROOT / "build")),
                        help="robotd build tree (default: build)")
    parser.add_argument("--quick", action="store_true", help="a few seconds per block: checks the bench runs, "
                        "not the machine")
    return parser


class Programs:
    """The built programs a bench runs."""

    def __init__(self, build_dir):
        build = Path(build_dir).resolve()
        self.robotd = build / "bin" / "robotd"
        self.robotctl = build / "bin" / "robotctl"
        self.tools = build / "bench"
        missing = [p for p in (self.robotd, self.robotctl, self.tools) if not p.exists()]
        if missing:
            sys.exit(f"bench: {', '.join(map(str, missing))} not found: build first (cmake --build {build})")

    def tool(self, name):
        return str(self.tools / name)


@contextlib.contextmanager
def private_domain():
    """A DDS domain id no test or bench is using (flock on /tmp/robotd-test-domain-<id>.lock)."""
    for domain in range(100 + os.getpid() % 37, 230):
        handle = open(f"/tmp/robotd-test-domain-{domain}.lock", "w")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.close()
            continue
        try:
            yield domain
        finally:
            handle.close()
        return
    raise RuntimeError("no free DDS domain id in 100..229")


def sim_arm(name="arm", joints=6, **overrides):
    device = {"name": name, "driver": "sim", "rate_hz": 1000, "rt_priority": 80, "realtime": "prefer",
              "params": {"model": f"bench {joints}-joint sim", "joint_count": joints,
                         "joint_defaults": {"position_min_rad": -2.5, "position_max_rad": 2.5,
                                            "velocity_max_rad_s": 2.0, "acceleration_max_rad_s2": 10.0,
                                            "default_kp": 200, "default_kd": 8}}}
    device.update(overrides)
    return device


def config(domain, devices, window_ticks=20000):
    return {"daemon": {"log_level": "warn", "stats_window_ticks": window_ticks},
            "dds": {"domain_id": domain, "interface": "127.0.0.1", "multicast": False, "peers": ["127.0.0.1"]},
            "devices": devices}


class Robotd:
    """robotd running a generated config; stopped (SIGTERM) when the block ends."""

    def __init__(self, programs, domain, config_dict):
        self.programs = programs
        self.domain = domain
        self.config_file = tempfile.NamedTemporaryFile("w", suffix=".json", prefix="robotd-bench-")
        json.dump(config_dict, self.config_file)
        self.config_file.flush()
        self.log = tempfile.TemporaryFile("w+")
        self.process = subprocess.Popen([str(programs.robotd), "--config", self.config_file.name],
                                        stdout=self.log, stderr=subprocess.STDOUT)
        self.wait_ready()

    def wait_ready(self, timeout_s=20):
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"robotd exited with {self.process.returncode}:\n{self.output()}")
            result = subprocess.run(self.robotctl_command("devices", "--json"), capture_output=True, text=True)
            if result.returncode == 0 and all(d["state"] == "RUNNING" for d in json.loads(result.stdout)):
                return
            time.sleep(0.1)
        raise RuntimeError(f"robotd did not become ready:\n{self.output()}")

    def robotctl_command(self, *args):
        return [str(self.programs.robotctl), "--domain", str(self.domain), *args]

    def call(self, device, op, args=None):
        """robotctl call DEVICE OP ARGS, parsed."""
        result = subprocess.run(self.robotctl_command("call", device, op, json.dumps(args or {})),
                                capture_output=True, text=True)
        if result.returncode != 0:
            raise RuntimeError(f"robotctl call {device} {op} failed: {result.stdout}{result.stderr}")
        return json.loads(result.stdout)

    def cpu_seconds(self):
        """user + system CPU seconds robotd has used so far."""
        fields = Path(f"/proc/{self.process.pid}/stat").read_text().rsplit(")", 1)[1].split()
        ticks = int(fields[11]) + int(fields[12])  # utime, stime
        return ticks / os.sysconf("SC_CLK_TCK")

    def output(self):
        self.log.seek(0)
        return self.log.read()

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.config_file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


def start_tool(programs, name, *args):
    return subprocess.Popen([programs.tool(name), *map(str, args)], stdout=subprocess.PIPE, text=True)


def finish_tool(process, timeout_s=60):
    """Waits for a bench tool and returns the JSON object it printed last."""
    output, _ = process.communicate(timeout=timeout_s)
    if process.returncode != 0:
        raise RuntimeError(f"{process.args[0]} exited with {process.returncode}: {output}")
    return json.loads(output.strip().splitlines()[-1])


def cyclictest(duration_s, priority=80, interval_us=1000, threads=1, histogram_us=10000):
    """Runs cyclictest (Debian rt-tests) and returns its per-thread latency histograms
    ({µs: count} per thread) and per-thread overflow counts."""
    with tempfile.NamedTemporaryFile("r", suffix=".hist") as histfile:
        # -d 0: every thread at the same interval (cyclictest spaces them 500 µs apart by default).
        command = ["cyclictest", "-m", "-q", "-p", str(priority), "-i", str(interval_us), "-t", str(threads), "-d", "0",
                   "-D", f"{duration_s}s", "-h", str(histogram_us), f"--histfile={histfile.name}"]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            raise RuntimeError(f"cyclictest failed ({result.returncode}): {result.stderr}")
        histograms = [dict() for _ in range(threads)]
        overflows = [0] * threads
        for line in histfile.read().splitlines():
            if line.startswith("# Histogram Overflows:"):
                overflows = [int(v) for v in line.split(":", 1)[1].split()[:threads]]
            if not line or line.startswith("#"):
                continue
            values = [int(v) for v in line.split()]
            for thread in range(threads):
                if values[1 + thread]:
                    histograms[thread][values[0]] = values[1 + thread]
        return histograms, overflows


def histogram_samples_us(histogram, overflow, overflow_us):
    """Expands a {µs: count} histogram into a list of samples (overflows counted at overflow_us)."""
    samples = []
    for value, count in sorted(histogram.items()):
        samples.extend([float(value)] * count)
    samples.extend([float(overflow_us)] * overflow)
    return samples


def percentiles(samples):
    """p50, p99, p99.9 and max (nearest rank) of a list of numbers."""
    if not samples:
        return {"p50": 0.0, "p99": 0.0, "p999": 0.0, "max": 0.0, "count": 0}
    ordered = sorted(samples)

    def rank(q):
        index = max(0, min(len(ordered) - 1, int(-(-q * len(ordered) // 1)) - 1))
        return ordered[index]

    return {"p50": rank(0.50), "p99": rank(0.99), "p999": rank(0.999), "max": ordered[-1], "count": len(ordered)}


def ratio(a, b):
    return round(a / b, 3) if b else None


def table(headers, rows):
    widths = [max(len(str(h)), *(len(str(r[i])) for r in rows)) if rows else len(str(h))
              for i, h in enumerate(headers)]
    lines = ["  ".join(str(h).ljust(w) for h, w in zip(headers, widths))]
    for row in rows:
        lines.append("  ".join(str(c).ljust(w) for c, w in zip(row, widths)))
    return "\n".join(lines)


def distribution_row(label, stats, unit="µs"):
    return [label, f"{stats['p50']:.1f}", f"{stats['p99']:.1f}", f"{stats['p999']:.1f}", f"{stats['max']:.1f}",
            stats["count"], unit]


DISTRIBUTION_HEADERS = ["", "p50", "p99", "p99.9", "max", "samples", "unit"]


def emit(figures):
    """The bench's result: one JSON object as the last line of output."""
    print(json.dumps(figures, sort_keys=True), flush=True)
