"""The vendor simulators for the e-stop bench: each one started as a process on loopback, the
robotd device that drives it, its control channel, and when the simulator took robotd's e-stop
off its wire (the vendor's own stop command), read from what the simulator reports. Python 3
standard library only; the simulators and their control channels are described in
drivers/<vendor>/sim/README.md."""
import json
import select
import socket
import subprocess
import time
from pathlib import Path

READY_TIMEOUT_S = 5.0


def free_tcp_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


# The simulators stand in for hardware with a CPU of its own: SCHED_FIFO, below robotd's loops.
SIM_RT_PRIORITY = "10"


class Simulator:
    """One simulator process, ready once it printed "ready"; stopped (SIGTERM) when the block ends."""

    vendor = ""

    def __init__(self, bin_dir, scratch):
        self.scratch = Path(scratch)
        self.control_path = str(self.scratch / f"{self.vendor}.ctl")
        program = Path(bin_dir) / f"robotd-{self.vendor}-sim"
        if not program.exists():
            raise RuntimeError(f"{program} not found: build it first")
        arguments = [str(program), *self.link_arguments(), "--control", self.control_path,
                     "--rt-priority", SIM_RT_PRIORITY, "--quiet"]
        self.process = subprocess.Popen(arguments, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        ready, _, _ = select.select([self.process.stdout], [], [], READY_TIMEOUT_S)
        line = self.process.stdout.readline().strip() if ready else ""
        if line != "ready":
            self.stop()
            raise RuntimeError(f"robotd-{self.vendor}-sim did not print \"ready\" (printed {line!r})")

    def link_arguments(self):
        raise NotImplementedError

    def device(self):
        """The robotd device for this simulator (a config "devices" entry)."""
        return {"name": self.vendor, "driver": self.vendor, "rate_hz": 1000, "realtime": "prefer",
                "reconnect_interval_ms": 200, "feedback_timeout_ms": 100, "params": self.params()}

    def params(self):
        raise NotImplementedError

    def control(self, request):
        """One request on the control channel; its reply. Raises on {"ok": false}."""
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as channel:
            channel.settimeout(5.0)
            channel.connect(self.control_path)
            channel.sendall((json.dumps(request) + "\n").encode())
            reply = b""
            while not reply.endswith(b"\n"):
                chunk = channel.recv(1 << 16)
                if not chunk:
                    break
                reply += chunk
        answer = json.loads(reply)
        if not answer.get("ok", False):
            raise RuntimeError(f"robotd-{self.vendor}-sim refused {request}: {answer.get('error')}")
        return answer

    def estop_seen_ns(self, since_ns):
        """CLOCK_MONOTONIC ns at which the simulator took robotd's e-stop (sent after `since_ns`)
        off its wire, or None while it has not."""
        raise NotImplementedError

    def released(self):
        """Whether the simulator has left the stop robotd's last e-stop put it in (what the next
        sample's estop_seen_ns needs to see a new stop); most mark every stop command anew."""
        return True

    def wait_released(self, timeout_s=2.0):
        deadline = time.monotonic() + timeout_s
        while not self.released():
            if time.monotonic() > deadline:
                raise RuntimeError(f"robotd-{self.vendor}-sim stayed stopped {timeout_s} s after the e-stop reset")
            time.sleep(0.002)

    def wait_estop_seen(self, since_ns, timeout_s=0.5):
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            seen = self.estop_seen_ns(since_ns)
            if seen is not None:
                return seen
            time.sleep(0.002)
        return None

    def stop(self):
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process.stdout.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


class PiperSim(Simulator):
    """AgileX PiPER on the CAN stand-in; robotd's e-stop is EmergencyStop 0x150 01."""

    vendor = "piper"

    def link_arguments(self):
        self.bus = str(self.scratch / "piper.sock")
        return ["--standin", self.bus]

    def params(self):
        # No gripper: robotd refuses the gripper's default gains (0) on a driver that can damp.
        return {"can": {"transport": "standin", "path": self.bus}, "gripper": False, "connect_timeout_ms": 5000,
                "reply_timeout_ms": 3000}

    def estop_seen_ns(self, since_ns):
        seen = self.control({"op": "state"})["estop_since_ns"]
        return seen if seen >= since_ns else None


class Parol6Sim(Simulator):
    """PAROL6 board on a pty; robotd's e-stop is DISABLE (102) in every frame."""

    vendor = "parol6"
    DISABLE = 102

    def link_arguments(self):
        self.pty = str(self.scratch / "parol6.tty")
        return ["--pty", self.pty, "--homed"]

    def params(self):
        return {"serial": {"device": self.pty, "baud": 3000000}, "connect_timeout_ms": 5000}

    def estop_seen_ns(self, since_ns):
        state = self.control({"op": "state"})
        seen = state["command_since_ns"]
        return seen if state["command"] == self.DISABLE and seen >= since_ns else None

    def released(self):
        # The ENABLE after a reset goes out at the next exchange (100 Hz); until then a new
        # DISABLE would change nothing the simulator marks.
        return self.control({"op": "state"})["command"] != self.DISABLE


class RealmanSim(Simulator):
    """RealMan RM65 controller on TCP; robotd's e-stop is set_arm_stop."""

    vendor = "realman"

    def link_arguments(self):
        self.port = free_tcp_port()
        return ["--port", str(self.port)]

    def params(self):
        return {"model": "RM65", "host": "127.0.0.1", "port": self.port, "push": {"ip": "127.0.0.1", "port": 0}}

    def estop_seen_ns(self, since_ns):
        seen = self.control({"op": "state"})["commands_last_ns"].get("set_arm_stop", 0)
        return seen if seen >= since_ns else None


class XarmSim(Simulator):
    """UFACTORY xArm 6 control box on TCP; robotd's e-stop is set_state 4 (STOPPED)."""

    vendor = "xarm"
    STOPPED = 4

    def link_arguments(self):
        self.port, self.report_port = free_tcp_port(), free_tcp_port()
        while self.report_port == self.port:
            self.report_port = free_tcp_port()
        return ["--port", str(self.port), "--report-port", str(self.report_port)]

    def params(self):
        return {"model": "xarm6", "host": "127.0.0.1", "port": self.port,
                "report": {"kind": "real", "port": self.report_port}}

    def estop_seen_ns(self, since_ns):
        state = self.control({"op": "state"})
        seen = state["commands_last_ns"].get("set_state", 0)
        return seen if state["state"] == self.STOPPED and seen >= since_ns else None


class HighTorqueSim(Simulator):
    """Six HighTorque motors on one CAN-FD stand-in bus; robotd's e-stop is BRAKE (block 0x86)
    to every motor. A motor with a fault free-wheels and ignores commands, BRAKE too."""

    vendor = "hightorque"
    MOTORS = 6

    def link_arguments(self):
        self.bus = str(self.scratch / "hightorque.sock")
        return ["--bus", f"{self.bus}:1-{self.MOTORS}"]

    def params(self):
        return {"model": "six HighTorque motors (simulated)",
                "buses": [{"name": "bus0", "can": {"transport": "standin", "path": self.bus}}],
                "motor_defaults": {"position_min_rad": -1.5, "position_max_rad": 1.5, "velocity_max_rad_s": 10.0,
                                   "kp_max": 300, "kd_max": 20, "default_kp": 40, "default_kd": 2.0,
                                   "effort_max_nm": 30},
                "motors": [{"name": f"m{i}", "bus": "bus0", "id": i} for i in range(1, self.MOTORS + 1)],
                "zero_settle_ms": 5000}

    def estop_seen_ns(self, since_ns):
        motors = [m for m in self.control({"op": "state"})["buses"][0]["motors"] if m["fault"] == 0]
        if not motors or any(m["mode"] != "brake" or m["mode_commanded_ns"] < since_ns for m in motors):
            return None
        return max(m["mode_commanded_ns"] for m in motors)  # the last of them to brake


SIMULATORS = {sim.vendor: sim for sim in (PiperSim, Parol6Sim, RealmanSim, XarmSim, HighTorqueSim)}
