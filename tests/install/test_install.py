#!/usr/bin/env python3
"""The install rules, checked the way a user meets them: install into a staging directory,
build a separate project against find_package(robotd_client), then run the installed robotd
(finding its installed sim plugin) and talk to it with the installed robotctl and the consumer."""
import argparse
import os
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from test_domain import claim_domain_id  # noqa: E402  (tests/support)

ARGS = None


class InstallTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.stage = tempfile.TemporaryDirectory(prefix="robotd-install-")
        env = dict(os.environ, DESTDIR=cls.stage.name)
        subprocess.run(["cmake", "--install", ARGS.build_dir], env=env, check=True, capture_output=True)
        cls.prefix = Path(cls.stage.name + ARGS.prefix)
        cls.env = dict(os.environ, LD_LIBRARY_PATH=str(cls.prefix / ARGS.libdir))

    @classmethod
    def tearDownClass(cls):
        cls.stage.cleanup()

    def test_installs_daemon_cli_plugin_headers_package_config_and_unit(self):
        expected = [
            "bin/robotd",
            "bin/robotctl",
            f"{ARGS.libdir}/robotd/drivers/librobotd_driver_sim.so",
            f"{ARGS.libdir}/robotd/drivers/librobotd_driver_piper.so",
            "bin/robotd-piper-sim",
            "bin/robotd-parol6-sim",
            f"{ARGS.libdir}/librobotd_client.so",
            f"{ARGS.libdir}/cmake/robotd_client/robotd_clientConfig.cmake",
            f"{ARGS.libdir}/librobotd_c.so",
            f"{ARGS.libdir}/pkgconfig/robotd-c.pc",
            "include/robotd/client.hpp",
            "include/robotd/robotd.h",
            "share/robotd/examples/move_arm.c",
            "share/robotd/examples/move_arm.py",
            "share/robotd/examples/pd_control.c",
            "share/robotd/examples/pd_control.cpp",
            "share/robotd/examples/pd_control.py",
            "include/robotd/messages.hpp",
            "include/robotd/driver/driver.hpp",
            "etc/robotd/robotd.json",
            "lib/systemd/system/robotd.service",
            "share/robotd/idl/robotd_msgs.idl",
        ]
        missing = [path for path in expected if not (self.prefix / path).exists()]
        self.assertEqual(missing, [], f"not installed under {self.prefix}")

    def test_the_installed_python_package_imports_and_finds_its_library(self):
        if ARGS.sanitize:
            self.skipTest("python3 is not instrumented: it cannot load a sanitized librobotd_c")
        package = self.prefix / ARGS.python_dir
        self.assertTrue((package / "robotd" / "session.py").exists(), f"no robotd package in {package}")
        environment = dict(self.env, PYTHONPATH=str(package), PYTHONDONTWRITEBYTECODE="1")
        environment.pop("ROBOTD_C_LIBRARY", None)
        result = subprocess.run([sys.executable, "-c", "import robotd; print(robotd.__version__)"],
                                capture_output=True, text=True, env=environment)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(result.stdout, r"^\d+\.\d+\.\d+$")

    def test_installed_config_is_valid(self):
        result = subprocess.run([str(self.prefix / "bin/robotd"), "--check-config", "--config",
                                 str(self.prefix / "etc/robotd/robotd.json")], capture_output=True, text=True,
                                env=self.env)
        self.assertEqual(result.returncode, 0, result.stderr)

    def test_a_separate_project_builds_against_the_package_and_talks_to_the_installed_daemon(self):
        with tempfile.TemporaryDirectory(prefix="robotd-consumer-") as build:
            # A sanitized librobotd_client calls into the sanitizer runtime, which the program links.
            flags = f"-fsanitize={ARGS.sanitize}" if ARGS.sanitize else ""
            configure = subprocess.run(["cmake", "-S", str(Path(__file__).parent / "consumer"), "-B", build,
                                        f"-DCMAKE_PREFIX_PATH={self.prefix}", f"-DCMAKE_CXX_COMPILER={ARGS.cxx_compiler}",
                                        f"-DCMAKE_CXX_FLAGS={flags}"], capture_output=True, text=True)
            self.assertEqual(configure.returncode, 0, configure.stdout + configure.stderr)
            compile_ = subprocess.run(["cmake", "--build", build], capture_output=True, text=True)
            self.assertEqual(compile_.returncode, 0, compile_.stdout + compile_.stderr)

            domain, lock = claim_domain_id()
            with lock, tempfile.NamedTemporaryFile("w", suffix=".json") as config:
                config.write('{"dds": {"domain_id": %d, "interface": "127.0.0.1", "multicast": false,'
                             ' "peers": ["127.0.0.1"]},'
                             ' "devices": [{"name": "arm", "driver": "sim", "params": {"joint_count": 6}}]}' % domain)
                config.flush()
                # No plugin_dirs: the installed robotd must find its installed plugin by itself.
                daemon = subprocess.Popen([str(self.prefix / "bin/robotd"), "--config", config.name], env=self.env,
                                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
                try:
                    listing = self.wait_for_devices(domain)
                    self.assertIn("arm", listing)
                    consumer = subprocess.run([str(Path(build) / "consumer"), str(domain)], capture_output=True,
                                              text=True, env=self.env, timeout=20)
                    self.assertEqual(consumer.returncode, 0, consumer.stdout + consumer.stderr)
                    self.assertEqual(consumer.stdout.strip(), "arm sim 6")
                finally:
                    daemon.terminate()
                    output, _ = daemon.communicate(timeout=20)
                self.assertEqual(daemon.returncode, 0, output)

    def wait_for_devices(self, domain):
        deadline = time.monotonic() + 20
        while True:
            result = subprocess.run([str(self.prefix / "bin/robotctl"), "--domain", str(domain), "devices"],
                                    capture_output=True, text=True, env=self.env, timeout=20)
            if result.returncode == 0 or time.monotonic() > deadline:
                self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
                return result.stdout
            time.sleep(0.2)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", required=True)
    parser.add_argument("--prefix", required=True)
    parser.add_argument("--libdir", required=True)
    parser.add_argument("--python-dir", required=True, help="where the Python package is installed, in the prefix")
    parser.add_argument("--cxx-compiler", required=True, help="the compiler robotd was built with")
    parser.add_argument("--sanitize", default="",
                        help="the sanitizers robotd was built with (ROBOTD_SANITIZE): the consumer needs them too")
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
