#!/usr/bin/env python3
"""CI's check of the benches: bench/run --quick must run every bench and write every figure.
It checks that the figures exist and are numbers, not that this machine was fast."""
import json
import numbers
import subprocess
import sys
import tempfile
from pathlib import Path

REQUIRED = [
    "loop_wake_p50_us", "loop_wake_p99_us", "loop_wake_p999_us", "loop_wake_max_us", "loop_exec_p99_us",
    "baseline_wake_p50_us", "baseline_wake_p99_us", "baseline_wake_p999_us", "baseline_wake_max_us",
    "wake_p99_ratio", "wake_p99_ratio_median_of_blocks",
    "cmd_latency_p50_us", "cmd_latency_p99_us", "cmd_latency_p999_us", "cmd_latency_max_us",
    "dds_oneway_p50_us", "dds_oneway_p99_us", "dds_oneway_p999_us", "dds_oneway_max_us",
    "fanout1_min_fraction", "fanout4_min_fraction", "fanout16_min_fraction", "fanout16_overruns",
    "fanout16_robotd_cpu_cores",
    "scale1_worst_wake_p99_us", "scale4_worst_wake_p99_us", "scale8_worst_wake_p99_us", "humanoid_worst_wake_p99_us",
    "scale8_overruns_per_min", "scale8_late_per_min", "scale8_baseline_late_per_min", "scale8_robotd_cpu_cores",
    "tick_ns_6", "tick_ns_23", "tick_instructions_6", "tick_instructions_23",
    *(f"flood{n}_{figure}" for n in (0, 1, 8, 32)
      for figure in ("owner_fraction", "forged_counted_fraction", "intake_cpu_us_per_command",
                     "receive_cpu_us_per_command", "robotd_cpu_us_per_command")),
    *(f"estop_sim_{state}_{figure}" for state in ("running", "streaming", "fault", "recover", "reset_zero",
                                                  "no_feedback") for figure in ("p50_ms", "p99_ms", "max_ms")),
    "estop_sim_link_lost_reached_fraction",
    *(f"estop_{vendor}_running_{figure}" for vendor in ("piper", "parol6", "realman", "xarm", "hightorque")
      for figure in ("p50_ms", "p99_ms", "max_ms", "wire_p50_ms", "wire_p99_ms", "wire_max_ms")),
    *(f"estop_{vendor}_recover_reached_fraction" for vendor in ("piper", "parol6", "realman", "xarm", "hightorque")),
    *(f"estop_{vendor}_reset_zero_p99_ms" for vendor in ("piper", "hightorque")),
    *(f"footprint_{case}_{figure}" for case in ("demo7", "sim4")
      for figure in ("rss_mib", "locked_resident_mib", "locked_space_mib", "threads")),
    *(f"closed_loop_{run}_{figure}" for run in ("cpp_arm", "cpp_humanoid", "cpp_arm_sched_other", "py_arm_1khz",
                                                "py_arm_500hz")
      for figure in ("in_time_fraction", "client_in_time_fraction", "overruns", "round_trip_p50_us",
                     "round_trip_p99_us", "round_trip_p999_us", "round_trip_max_us",
                     "hop_accept_p50_us", "answers_not_taken", "states_not_published",
                     *(f"hop_{hop}_{q}_us" for hop in ("ready", "publish", "receive", "law") for q in ("p50", "p99")))),
    "closed_loop_arm_overruns_no_client", "closed_loop_humanoid_overruns_no_client",
    "closed_loop_dds_round_trip_6_p50_us", "closed_loop_dds_round_trip_23_p50_us",
    "cyclictest_late_500us_fraction", "cyclictest_late_1ms_fraction", "cyclictest_p99_us",
    "aligned_cmd_latency_p50_us", "aligned_dds_oneway_p50_us", "aligned_cmd_latency_minus_dds_p50_us",
    *(f"aligned_lead{lead}_cmd_latency_{q}_us" for lead in (120, 200, 80) for q in ("p50", "p99", "p999", "max")),
]


def main():
    repo, build_dir = Path(sys.argv[1]), sys.argv[2]
    with tempfile.TemporaryDirectory(prefix="robotd-bench-") as scratch:
        output = Path(scratch) / "results.json"
        run = subprocess.run([sys.executable, str(repo / "bench" / "run"), "--quick", "--build-dir", build_dir,
                              "--output", str(output)], capture_output=True, text=True)
        print(run.stdout[-3000:])
        if run.returncode != 0:
            print(run.stderr[-3000:])
            sys.exit(f"bench/run --quick failed with exit code {run.returncode}")
        figures = json.loads(output.read_text())["figures"]
    missing = [key for key in REQUIRED if key not in figures]
    not_numbers = [key for key in REQUIRED if key in figures and not isinstance(figures[key], numbers.Number)]
    if missing or not_numbers:
        sys.exit(f"missing figures: {missing}; not numbers: {not_numbers}")
    print(f"all {len(REQUIRED)} required figures present")


if __name__ == "__main__":
    main()
