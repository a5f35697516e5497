#!/usr/bin/env python3
"""Closed loop: a client process answers each tick's state with a PD law's torques, through robotd,
and robotd applies the answer on the next tick. One robotd runs the 6-joint sim arm and the 23-motor
sim humanoid (with its IMU), each at 1 kHz; the clients take turns:

  - the C++ client (Session::run_control_loop, robotd_bench_closed_loop) at SCHED_FIFO 70, as a
    controller runs, on the arm, then on the humanoid; then at SCHED_OTHER on the arm; 10 s each;
  - the Python client (session.ticks() / answer, bench/tools/closed_loop_client.py, SCHED_OTHER)
    on the arm at 1 kHz, then, in a robotd of its own, on a sim arm that offers every second
    tick's state (joint_state_rate_hz 500: its loop keeps 1 kHz, the client gets 500 states a
    second and two periods to answer each);
  - the aligned streaming client (robotd_bench_stream --aligned: Session::send_aligned) on the arm,
    5 s with the library's default lead (120 µs before each tick), 5 s each with 200 and 80 µs:
    command latency, client publish → the sim driver's write().

Per closed-loop run: the fraction of ticks answered in time as robotd counts it (SessionInfo in
/session_status) and as the client sees it (its answer sent before the next offered tick's
deadline, skipped ticks unanswered); the round trip tick deadline → robotd accepted the answer
(robotd's loop_timing answer_round_trip samples) p50/p99/p99.9/max; the hops of that round trip
(deadline → state ready → published → client received → client sent → robotd accepted) p50/p99
(the last hop per answer only when robotd took every answer, see analyse(); else its p50 as the
round trip's p50 minus deadline → client sent's);
loop overruns during the run, next to the overruns of the same loop in as many seconds before the
first client. Baselines from the same run: cyclictest (-m -p 80 -i 1000, alone) with its late
wake-up fractions, and a DDS ping-pong of the same sizes (robotd_bench_pingpong: a TickState of 6
or 23 joints, answered by a ControlCommand of as many torques; and the command latency's
ControlCommand both ways for the aligned client). About 2 minutes; --quick about 40 s."""
import os
import subprocess
import time

import benchlib as b

PRIORITY = 80
CLIENT_PRIORITY = 70  # a controller's: below robotd's loops (80), above everything else
ALIGNED_LEADS_US = (120, 200, 80)  # the client library's default lead (kDefaultSendLead), a longer and a shorter one
HUMANOID_JOINTS = 23
PYTHON_CLIENT = b.ROOT / "bench" / "tools" / "closed_loop_client.py"


def devices():
    arm = b.sim_arm("arm")
    humanoid = b.sim_arm("humanoid", HUMANOID_JOINTS)
    humanoid["params"]["imu"] = True
    return [arm, humanoid]


def python_environment(programs):
    """The environment the Python client runs in: the robotd package from this tree and the C
    library from the build. None (with the reason) when this tree's client has no closed loop."""
    environment = dict(os.environ, PYTHONPATH=str(b.ROOT / "clients" / "python"),
                       ROBOTD_C_LIBRARY=str(programs.tools.parent / "lib" / "librobotd_c.so"))
    probe = subprocess.run(["python3", "-c", "import robotd; robotd.Session.ticks"], env=environment,
                           capture_output=True, text=True)
    if probe.returncode != 0:
        return None, probe.stderr.strip().splitlines()[-1] if probe.stderr.strip() else "import failed"
    return environment, None


def run_client(robotd, device, command, environment=None, every=1):
    """Runs one closed-loop client on `device` and joins what it saw with robotd's loop_timing."""
    before = robotd.call(device, "loop_timing", {"reset": True})
    process = subprocess.Popen(command, stdout=subprocess.PIPE, text=True, env=environment)
    client = b.finish_tool(process, timeout_s=120)
    timing = robotd.call(device, "loop_timing", {"samples": True})
    client["round_trip_ns"] = timing["answer_round_trip_ns"]
    client["overruns"] = timing["overruns"] - before["overruns"]
    # States robotd's publisher never wrote: it publishes the newest state when it wakes, so a
    # wake-up later than a period skips the states in between (every state is due: 1 per tick, or
    # 1 per `every` ticks).
    client["states_not_published"] = ((timing["ticks"] - before["ticks"]) // every -
                                      (timing["joint_states_published"] - before["joint_states_published"]))
    return client


def cyclictest_figures(seconds):
    histograms, overflows = b.cyclictest(seconds, PRIORITY, 1000, histogram_us=2000)
    samples = b.histogram_samples_us(histograms[0], overflows[0], 2000)
    stats = b.percentiles(samples)
    count = len(samples) or 1
    return {"cyclictest_p50_us": stats["p50"], "cyclictest_p99_us": stats["p99"], "cyclictest_max_us": stats["max"],
            "cyclictest_late_500us_fraction": round(sum(1 for s in samples if s > 500) / count, 6),
            "cyclictest_late_1ms_fraction": round(sum(1 for s in samples if s > 1000) / count, 6),
            "cyclictest_samples": len(samples)}


def pingpong(programs, shape, joints, seconds):
    """Round trips (µs) of robotd_bench_pingpong at 1 kHz."""
    with b.private_domain() as domain:
        pong = b.start_tool(programs, "robotd_bench_pingpong", "--domain", domain, "--role", "pong", "--shape", shape,
                            "--joints", joints)
        try:
            ping = b.finish_tool(b.start_tool(programs, "robotd_bench_pingpong", "--domain", domain, "--role", "ping",
                                              "--shape", shape, "--joints", joints, "--rate", 1000,
                                              "--seconds", seconds))
        finally:
            pong.kill()
            pong.wait()
    return [ns / 1000 for ns in ping["round_trip_ns"]]


def tick_step(ticks):
    """Ticks between two offered states: the most common difference of consecutive tick numbers."""
    steps = [later - earlier for earlier, later in zip(ticks, ticks[1:])]
    return max(set(steps), key=steps.count) if steps else 1


def analyse(client):
    """In-time fractions, the round trip and its hops (µs) of one closed-loop run."""
    ticks = client["tick"]
    step = tick_step(ticks)
    offered = (ticks[-1] - ticks[0]) // step + 1 if ticks else 0
    period = [(d2 - d1) / (t2 - t1) for d1, d2, t1, t2 in zip(client["deadline_ns"], client["deadline_ns"][1:],
                                                                ticks, ticks[1:]) if t2 > t1]
    period_ns = sorted(period)[len(period) // 2] if period else 1e6
    answer_window_ns = step * period_ns  # robotd takes an answer in time until the next state is measured
    client_in_time = sum(1 for d, s in zip(client["deadline_ns"], client["sent_ns"]) if s - d < answer_window_ns)
    info = client["info"]

    def hop(later, earlier):
        return [(a - e) / 1000 for a, e in zip(client[later], client[earlier])]

    hops = {"deadline → state ready": hop("ready_ns", "deadline_ns"),
            "state ready → published": hop("published_ns", "ready_ns"),
            "published → client received": hop("received_ns", "published_ns"),
            "client received → client sent": hop("sent_ns", "received_ns")}
    round_trip = [ns / 1000 for ns in client["round_trip_ns"]]
    # robotd keeps one round trip (deadline → accepted) per answer it took, in tick order but without
    # the tick's number, and takes no answer that the next one overtook in its mailbox: the two pair
    # one to one only when robotd took every answer. Otherwise the hop is the difference of medians.
    sent = hop("sent_ns", "deadline_ns")
    not_taken = len(ticks) - len(round_trip)
    if not_taken == 0:
        hops["client sent → robotd accepted"] = [r - s for r, s in zip(round_trip, sent)]
    hops["deadline → robotd accepted (round trip)"] = round_trip
    accept_p50 = b.percentiles(round_trip)["p50"] - b.percentiles(sent)["p50"]
    return {"robotd_in_time": info["ticks_answered_in_time"] / info["ticks_to_answer"] if info["ticks_to_answer"]
            else 0.0,
            "client_in_time": client_in_time / offered if offered else 0.0,
            "ticks_offered": offered, "ticks_seen": len(ticks), "step": step, "not_taken": not_taken,
            "accept_p50": accept_p50, "round_trip": b.percentiles(round_trip), "hops": {name: b.percentiles(v) for name, v in hops.items()}}


def show_run(label, client, result, dds_round_trip):
    info = client["info"]
    print(f"\n{label}: robotd counted {info['ticks_answered_in_time']} of {info['ticks_to_answer']} ticks in time "
          f"({100 * result['robotd_in_time']:.2f} %; late {info['ticks_answered_late']}, never "
          f"{info['ticks_unanswered']}); the client answered {result['ticks_seen']} of {result['ticks_offered']} "
          f"offered states, {100 * result['client_in_time']:.2f} % before the next one was due; states robotd "
          f"never published (its publisher woke too late): {client['states_not_published']}; loop overruns during the "
          f"run: {client['overruns']}")
    rows = [[name, f"{s['p50']:.1f}", f"{s['p99']:.1f}", f"{s['p999']:.1f}", f"{s['max']:.1f}", s["count"]]
            for name, s in result["hops"].items()]
    if dds_round_trip is not None:
        rows.append(["DDS ping-pong, same sizes (round trip)", f"{dds_round_trip['p50']:.1f}",
                     f"{dds_round_trip['p99']:.1f}", f"{dds_round_trip['p999']:.1f}", f"{dds_round_trip['max']:.1f}",
                     dds_round_trip["count"]])
    print(b.table(["hop (µs)", "p50", "p99", "p99.9", "max", "samples"], rows))
    if result["not_taken"]:
        print(f"robotd took {len(client['round_trip_ns'])} of the client's {result['ticks_seen']} answers (the others "
              f"were overtaken in its mailbox by the next one): client sent → robotd accepted is not paired per "
              f"answer; round trip p50 − (deadline → client sent) p50 = {result['accept_p50']:.1f} µs")


def figures_of(prefix, client, result):
    out = {f"{prefix}_in_time_fraction": round(result["robotd_in_time"], 5),
           f"{prefix}_client_in_time_fraction": round(result["client_in_time"], 5),
           f"{prefix}_ticks_to_answer": client["info"]["ticks_to_answer"], f"{prefix}_overruns": client["overruns"]}
    for key, stats in (("round_trip", result["round_trip"]),):
        for q in ("p50", "p99", "p999", "max"):
            out[f"{prefix}_{key}_{q}_us"] = stats[q]
    short = {"deadline → state ready": "ready", "state ready → published": "publish",
             "published → client received": "receive", "client received → client sent": "law"}
    for name, key in short.items():
        out[f"{prefix}_hop_{key}_p50_us"] = result["hops"][name]["p50"]
        out[f"{prefix}_hop_{key}_p99_us"] = result["hops"][name]["p99"]
    out[f"{prefix}_hop_accept_p50_us"] = round(result["accept_p50"], 1)  # difference of medians
    out[f"{prefix}_answers_not_taken"] = result["not_taken"]
    out[f"{prefix}_states_not_published"] = client["states_not_published"]
    return out


def closed_loop_runs(programs, seconds, python_env):
    """The C++ client on the arm and the humanoid, the Python client on the arm, the aligned streamer."""
    figures, runs = {}, []
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, devices())) as robotd:
        start = {d: robotd.call(d, "loop_timing")["overruns"] for d in ("arm", "humanoid")}
        time.sleep(seconds)  # the loops alone, as long as a client's run: their overruns without one
        before = {d: robotd.call(d, "loop_timing")["overruns"] - start[d] for d in ("arm", "humanoid")}
        for device, count in before.items():
            figures[f"closed_loop_{device}_overruns_no_client"] = count
        print(f"loop overruns with no client, {seconds} s: arm {before['arm']}, humanoid {before['humanoid']}")

        tool = [programs.tool("robotd_bench_closed_loop"), "--domain", str(domain), "--seconds", str(seconds)]
        for device, priority, prefix in (("arm", CLIENT_PRIORITY, "closed_loop_cpp_arm"),
                                         ("humanoid", CLIENT_PRIORITY, "closed_loop_cpp_humanoid"),
                                         ("arm", 0, "closed_loop_cpp_arm_sched_other")):
            policy = f"SCHED_FIFO {priority}" if priority else "SCHED_OTHER"
            runs.append((prefix, f"C++ client ({policy}), {device}, 1 kHz",
                         run_client(robotd, device, [*tool, "--device", device, "--rt-priority", str(priority)])))
        if python_env is not None:
            command = ["python3", str(PYTHON_CLIENT), "--domain", str(domain), "--device", "arm",
                       "--seconds", str(seconds)]
            runs.append(("closed_loop_py_arm_1khz", "Python client, arm, 1 kHz",
                         run_client(robotd, "arm", command, python_env)))

        for lead_us in ALIGNED_LEADS_US:
            streamer = b.start_tool(programs, "robotd_bench_stream", "--domain", domain, "--device", "arm", "--aligned",
                                    "--lead-us", lead_us, "--seconds", seconds / 2 + 1.5)
            time.sleep(1.0)
            robotd.call("arm", "command_latency", {"reset": True})
            time.sleep(seconds / 2)
            aligned = robotd.call("arm", "command_latency", {"samples": True})
            b.finish_tool(streamer)
            figures[f"aligned_samples_us_{lead_us}"] = [ns / 1000 for ns in aligned["samples_ns"]]
    return figures, runs


def python_500hz_run(programs, seconds, python_env):
    arm = b.sim_arm("arm", joint_state_rate_hz=500)
    with b.private_domain() as domain, b.Robotd(programs, domain, b.config(domain, [arm])) as robotd:
        command = ["python3", str(PYTHON_CLIENT), "--domain", str(domain), "--device", "arm", "--seconds", str(seconds)]
        return run_client(robotd, "arm", command, python_env, every=2)


def main():
    args = b.common_arguments(__doc__).parse_args()
    programs = b.Programs(args.build_dir)
    seconds, baseline_seconds = (2, 2) if args.quick else (10, 10)
    load = os.getloadavg()
    python_env, python_missing = python_environment(programs)

    figures = cyclictest_figures(baseline_seconds)
    dds = {joints: b.percentiles(pingpong(programs, "closed_loop", joints, baseline_seconds / 2))
           for joints in (6, HUMANOID_JOINTS)}
    dds_oneway = b.percentiles([rt / 2 for rt in pingpong(programs, "command", 6, baseline_seconds / 2)])
    loop_figures, runs = closed_loop_runs(programs, seconds, python_env)
    if python_env is not None:
        runs.append(("closed_loop_py_arm_500hz", "Python client, arm offering 500 states/s (joint_state_rate_hz 500)",
                     python_500hz_run(programs, seconds, python_env)))
    aligned = {lead: b.percentiles(loop_figures.pop(f"aligned_samples_us_{lead}")) for lead in ALIGNED_LEADS_US}
    figures.update(loop_figures)

    print(f"closed loop: {seconds} s per client; host load average {load[0]:.1f} at the start")
    print(f"cyclictest alone, {baseline_seconds} s (-m -p {PRIORITY} -i 1000): p50 {figures['cyclictest_p50_us']} / "
          f"p99 {figures['cyclictest_p99_us']} / max {figures['cyclictest_max_us']} µs; wake-ups later than 500 µs: "
          f"{100 * figures['cyclictest_late_500us_fraction']:.3f} %, later than 1 ms: "
          f"{100 * figures['cyclictest_late_1ms_fraction']:.3f} %")
    for prefix, label, client in runs:
        result = analyse(client)
        joints = HUMANOID_JOINTS if "humanoid" in prefix else 6
        show_run(label, client, result, dds[joints])
        figures.update(figures_of(prefix, client, result))
    if python_env is None:
        print(f"\nPython client skipped: {python_missing}")
    print(f"\naligned streaming (send_aligned), client publish → driver write(), next to DDS one-way (command "
          f"ping-pong, round trip / 2) p50 {dds_oneway['p50']:.1f} / p99 {dds_oneway['p99']:.1f} µs:")
    for lead, stats in aligned.items():
        print(f"  lead {lead} µs: p50 {stats['p50']:.1f} / p99 {stats['p99']:.1f} / max {stats['max']:.1f} µs "
              f"({stats['count']} commands); p50 − DDS one-way p50 {stats['p50'] - dds_oneway['p50']:.1f} µs "
              f"(target ≤ 100)")
    for joints, stats in dds.items():
        figures[f"closed_loop_dds_round_trip_{joints}_p50_us"] = stats["p50"]
        figures[f"closed_loop_dds_round_trip_{joints}_p99_us"] = stats["p99"]
    default = aligned[ALIGNED_LEADS_US[0]]
    figures.update({"aligned_cmd_latency_p50_us": default["p50"], "aligned_cmd_latency_p99_us": default["p99"],
                    "aligned_cmd_latency_max_us": default["max"], "aligned_dds_oneway_p50_us": dds_oneway["p50"],
                    "aligned_dds_oneway_p99_us": dds_oneway["p99"],
                    "aligned_cmd_latency_minus_dds_p50_us": round(default["p50"] - dds_oneway["p50"], 1),
                    "closed_loop_host_load_1min": round(load[0], 2)})
    for lead, stats in aligned.items():
        figures.update({f"aligned_lead{lead}_cmd_latency_{q}_us": stats[q] for q in ("p50", "p99", "p999", "max")})
    b.emit(figures)


if __name__ == "__main__":
    main()
