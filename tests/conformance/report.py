#!/usr/bin/env python3
"""Runs each vendor's conformance replay program once, whole, and prints the per-vendor table
docs/conformance.md describes: vectors, passed, deliberate differences, not implemented, failed.

usage: report.py VENDOR=PROGRAM ...   (CMake passes them; exits non-zero if a program fails)
"""
import json
import os
import subprocess
import sys
import tempfile


def run(vendor, program):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "report.json")
        env = dict(os.environ, ROBOTD_CONFORMANCE_REPORT=path)
        result = subprocess.run([program, "--gtest_brief=1"], env=env, capture_output=True,
                                text=True, check=False)
        if result.returncode != 0 or not os.path.exists(path):
            sys.stdout.write(result.stdout + result.stderr)
            return None
        with open(path, encoding="utf-8") as f:
            return json.load(f)


def main(args):
    columns = ("vectors", "passed", "deliberate_differences", "not_implemented", "failed")
    print(f"{'vendor':<28}" + "".join(f"{c.replace('_', ' '):>24}" for c in columns))
    ok = True
    for arg in args:
        vendor, _, program = arg.partition("=")
        report = run(vendor, program)
        if report is None:
            print(f"{vendor:<28} replay program failed: {program}")
            ok = False
            continue
        print(f"{vendor:<28}" + "".join(f"{report[c]:>24}" for c in columns))
        for group, counts in sorted(report["groups"].items()):
            print(f"  {group:<26}" + "".join(f"{counts[c]:>24}" for c in columns))
        ok = ok and report["failed"] == 0
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
