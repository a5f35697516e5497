/* A real robotd for the C API tests: on a DDS domain id no other test is using (the flock
 * scheme of tests/support/test_domain.cpp), with the simulated test arm on loopback, and
 * killed by the kernel if the test process dies first. */
#ifndef ROBOTD_TEST_ROBOTD_H
#define ROBOTD_TEST_ROBOTD_H

#include <robotd/robotd.h>
#include <stdbool.h>
#include <sys/types.h>

typedef struct test_robotd {
  int domain_id;
  int domain_lock_fd;
  pid_t pid;
  char config_path[64];
  char log_path[64];
} test_robotd;

/* Locks a free domain id in 100..229 and starts robotd on it with "arm" (6 joints joint1..joint6,
 * ±2.5 rad, 2 rad/s, 40 N·m, default kp 300 / kd 10) and, with_gripper, a 2-joint "gripper". */
bool test_robotd_start(test_robotd* robotd, bool with_gripper);
/* Waits until robotd lists its devices and every one is RUNNING. */
bool test_robotd_wait_ready(robotd_client* client, int timeout_ms);
/* Prints robotd's output so far to stderr. */
void test_robotd_print_log(const test_robotd* robotd);
/* SIGTERM (SIGKILL after 10 s), then removes its files and releases the domain id. */
void test_robotd_stop(test_robotd* robotd);

#endif /* ROBOTD_TEST_ROBOTD_H */
