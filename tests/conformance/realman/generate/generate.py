#!/usr/bin/python3
"""Records the RealMan conformance data: runs the vendor's SDK (RealManRobot/RM_API2, its Python
package over the prebuilt libapi_c.so) against robotd-realman-sim behind a recording proxy and
writes what crossed the wire.

usage: generate.py --rm-api2 CHECKOUT --sim build/bin/robotd-realman-sim [--out DIR]

CHECKOUT is a checkout (or `git archive`) of RM_API2 with Python/Robotic_Arm and its
libs/linux_x86/libapi_c.so; it is only read. Needs Debian's /usr/bin/python3 and x86_64 Linux.

Writes into DIR (default: this script's parent directory):
  transcript.jsonl  one line per message: session, connection, direction (request / reply /
                    push), text (the line as sent, without its CR LF). Every TCP request and
                    reply of every connection in the order the proxy read them; the first push
                    datagrams of each session.
  sdk_results.jsonl what each SDK call returned (session, call, args, returned).
  provenance.json   the repository, commit, library version, files run, command and date.
Exits 1 if an SDK call failed (the data is still written, to show what failed).
"""

import argparse
import datetime
import json
import os
import pathlib
import socket
import subprocess
import sys
import tempfile
import time

from recording_proxy import RecordingProxy, Transcript

HERE = pathlib.Path(__file__).resolve().parent
PUSH_SAMPLES = 5  # push datagrams kept per session: they repeat, the codec checks their shape

# (name, simulator options, what sdk_session.py runs)
SESSIONS = [
    ("gen3", ["--generation", "3"], "full"),
    ("gen4", ["--generation", "4"], "connect"),
]



def return_code(call):
    """The status an SDK call returned: an int, the first of a tuple, "return_code" of a dict; the
    handle's id for rm_create_robot_arm (-1: refused); for the push callback, whether it got a
    datagram."""
    returned = call["returned"]
    if call["call"] == "rm_create_robot_arm":
        return 0 if returned["id"] != -1 else -1
    if call["call"] == "rm_realtime_arm_state_call_back":
        return 0 if returned else -1
    if isinstance(returned, list) and returned and isinstance(returned[0], int):
        return returned[0]
    if isinstance(returned, dict):
        return returned.get("return_code", 0)
    return returned if isinstance(returned, int) else 0


def free_port(kind=socket.SOCK_STREAM):
    with socket.socket(socket.AF_INET, kind) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def control(path, request):
    with socket.socket(socket.AF_UNIX) as s:
        s.connect(path)
        s.sendall(json.dumps(request).encode() + b"\n")
        data = b""
        while not data.endswith(b"\n"):
            data += s.recv(65536)
        return json.loads(data)


def run_session(name, sim_options, session, args, tmp):
    port = free_port()
    control_path = os.path.join(tmp, f"{name}.ctl")
    sim_command = [args.sim, "--port", str(port), "--control", control_path, "--quiet"] + sim_options
    sim = subprocess.Popen(sim_command, stdout=subprocess.PIPE, text=True)
    try:
        if sim.stdout.readline().strip() != "ready":
            raise SystemExit(f"{args.sim} did not start")
        transcript = Transcript()
        proxy = RecordingProxy(port, transcript)
        env = dict(os.environ, PYTHONPATH=str(pathlib.Path(args.rm_api2) / "Python"))
        result = subprocess.run(
            ["/usr/bin/python3", str(HERE / "sdk_session.py"), str(proxy.port), str(free_port(socket.SOCK_DGRAM)),
             session], env=env, capture_output=True, text=True, timeout=180, check=False)
        time.sleep(0.2)
        proxy.close()
        sim_state = control(control_path, {"op": "state"})
    finally:
        sim.terminate()
        sim.wait()
    calls = [json.loads(line) for line in result.stdout.splitlines() if line.startswith("{")]
    version = next((line.split(":", 1)[1].strip() for line in result.stdout.splitlines()
                    if line.startswith("current c api version")), None)
    if result.returncode != 0:
        sys.stderr.write(f"[{name}] sdk_session.py exited {result.returncode}:\n{result.stderr[-2000:]}\n")
    return transcript, calls, version, sim_state, result.returncode


def transcript_lines(name, transcript):
    pushes = 0
    for entry in transcript.entries:
        if entry.get("direction") == "push":
            pushes += 1
            if pushes > PUSH_SAMPLES:
                continue
        if "text" not in entry:
            continue
        line = {"session": name, "direction": entry["direction"], "text": entry["text"]}
        if "connection" in entry:
            line = {"session": name, "connection": entry["connection"], **line}
        yield line


def segments_with_several(transcript):
    """How often the proxy read several requests in one TCP read (the client's batching)."""
    return sum(1 for e in transcript.entries if e.get("event") == "segment")


def git(checkout, *command):
    try:
        return subprocess.run(["git", "-C", checkout, *command], capture_output=True, text=True,
                              check=True).stdout.strip()
    except (subprocess.CalledProcessError, FileNotFoundError):
        return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rm-api2", required=True, help="checkout of RealManRobot/RM_API2")
    parser.add_argument("--sim", required=True, help="the robotd-realman-sim executable")
    parser.add_argument("--commit", help="RM_API2 commit, when CHECKOUT is not a git work tree")
    parser.add_argument("--out", default=str(HERE.parent))
    args = parser.parse_args()
    library = pathlib.Path(args.rm_api2) / "Python/Robotic_Arm/libs/linux_x86/libapi_c.so"
    if not library.is_file():
        raise SystemExit(f"{library} is missing: --rm-api2 must name an RM_API2 checkout")

    out = pathlib.Path(args.out)
    failed = []
    sessions = []
    versions = set()
    with tempfile.TemporaryDirectory() as tmp, \
            open(out / "transcript.jsonl", "w", encoding="utf-8") as transcript_file, \
            open(out / "sdk_results.jsonl", "w", encoding="utf-8") as results_file:
        for name, sim_options, session in SESSIONS:
            transcript, calls, version, sim_state, code = run_session(name, sim_options, session, args, tmp)
            versions.add(version)
            for line in transcript_lines(name, transcript):
                transcript_file.write(json.dumps(line, ensure_ascii=False) + "\n")
            for item in calls:
                results_file.write(json.dumps({"session": name, **item}, ensure_ascii=False) + "\n")
                if return_code(item) != 0:
                    failed.append(f"{name}: {item['call']}{tuple(item['args'])} returned {item['returned']}")
            if code != 0:
                failed.append(f"{name}: the session ended early (exit {code})")
            pass_through = sim_state.get("pass_through", {})
            sessions.append({"name": name, "simulator_options": sim_options, "sdk_session": session,
                             "simulator_errors_at_end": sim_state.get("errors"),
                             "movej_canfd": {k: pass_through.get(k) for k in
                                             ("frames", "accepted", "ignored", "last_rejection")},
                             "tcp_reads_with_several_requests": segments_with_several(transcript)})

    provenance = {
        "repository": "https://github.com/RealManRobot/RM_API2",
        "commit": args.commit or git(args.rm_api2, "rev-parse", "HEAD"),
        "library": "Python/Robotic_Arm/libs/linux_x86/libapi_c.so",
        "library_version": sorted(v for v in versions if v),
        "files_run": ["Python/Robotic_Arm/rm_robot_interface.py", "Python/Robotic_Arm/rm_ctypes_wrap.py",
                      "Python/Robotic_Arm/libs/linux_x86/libapi_c.so"],
        "generator": "tests/conformance/realman/generate/generate.py (sdk_session.py, recording_proxy.py)",
        "command": "/usr/bin/python3 tests/conformance/realman/generate/generate.py --rm-api2 <RM_API2 checkout> "
                   "--sim build/bin/robotd-realman-sim",
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
        "python": sys.version.split()[0],
        "sessions": sessions,
        "push_datagrams_kept_per_session": PUSH_SAMPLES,
    }
    with open(out / "provenance.json", "w", encoding="utf-8") as f:
        json.dump(provenance, f, indent=2, ensure_ascii=False)
        f.write("\n")
    for line in failed:
        print("FAILED", line)
    print(json.dumps(sessions, indent=1))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
