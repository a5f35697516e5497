"""What the Python tests of robotd's command-line tools share: their command line (the binaries
under test, then unittest's own arguments) and reading from and stopping child processes."""
import argparse
import select
import sys
import unittest


def run_tests(description, take_binaries):
    """Parses --robotd and --robotctl, hands them to `take_binaries(robotd, robotctl)`, and runs
    unittest on the remaining arguments (TestCase names, -k, ...)."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--robotd", required=True, help="path of the robotd binary")
    parser.add_argument("--robotctl", required=True, help="path of the robotctl binary")
    args, unittest_args = parser.parse_known_args()
    take_binaries(args.robotd, args.robotctl)
    unittest.main(argv=[sys.argv[0], *unittest_args], verbosity=2)


def read_line(stream, timeout_s=10.0):
    """The next line of `stream`, or "" if none arrives within the timeout."""
    ready, _, _ = select.select([stream], [], [], timeout_s)
    return stream.readline() if ready else ""


def stop_process(process):
    """Kills `process` if it still runs, reaps it and closes its pipes."""
    if process.poll() is None:
        process.kill()
    process.wait()
    for stream in (process.stdout, process.stderr):
        if stream:
            stream.close()
