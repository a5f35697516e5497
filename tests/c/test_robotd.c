#define _DEFAULT_SOURCE /* flock, mkstemp, nanosleep */

#include "test_robotd.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#ifndef ROBOTD_BINARY
#error "ROBOTD_BINARY must point at the robotd executable under test"
#endif

enum { kFirstDomain = 100, kLastDomain = 229 };

static const char kArm[] =
    "{\"name\": \"arm\", \"driver\": \"sim\", \"rate_hz\": 1000, \"realtime\": \"prefer\", \"params\": {"
    "\"model\": \"test arm\", \"kinematic_model\": \"parol6\", \"joint_defaults\": {\"position_min_rad\": -2.5, "
    "\"position_max_rad\": 2.5, \"velocity_max_rad_s\": 2.0, \"acceleration_max_rad_s2\": 10.0, "
    "\"effort_max_nm\": 40.0, \"kp_max\": 500.0, \"kd_max\": 50.0, \"default_kp\": 300.0, \"default_kd\": 10.0, "
    "\"inertia_kg_m2\": 0.05, "
    "\"damping_nm_s_rad\": 0.3}, \"joints\": [{\"name\": \"joint1\"}, {\"name\": \"joint2\"}, "
    "{\"name\": \"joint3\"}, {\"name\": \"joint4\"}, {\"name\": \"joint5\"}, {\"name\": \"joint6\"}]}}";
static const char kGripper[] =
    "{\"name\": \"gripper\", \"driver\": \"sim\", \"rate_hz\": 500, \"realtime\": \"prefer\", "
    "\"params\": {\"joint_count\": 2}}";

static void sleep_ms(long ms) {
  const struct timespec duration = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&duration, NULL);
}

static bool lock_domain(test_robotd* robotd) {
  for (int id = kFirstDomain + (int)(getpid() % 37); id <= kLastDomain; ++id) {
    char path[64];
    snprintf(path, sizeof path, "/tmp/robotd-test-domain-%d.lock", id);
    const int fd = open(path, O_CREAT | O_RDWR | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
      robotd->domain_id = id;
      robotd->domain_lock_fd = fd;
      return true;
    }
    close(fd);
  }
  fprintf(stderr, "no free test DDS domain id in %d..%d\n", kFirstDomain, kLastDomain);
  return false;
}

static bool temp_file(char* path, size_t capacity, const char* stem) {
  snprintf(path, capacity, "/tmp/robotd-c-test-%s-XXXXXX", stem);
  const int fd = mkstemp(path);
  if (fd < 0) return false;
  close(fd);
  return true;
}

static bool write_config(const test_robotd* robotd, bool with_gripper) {
  FILE* file = fopen(robotd->config_path, "w");
  if (file == NULL) return false;
  fprintf(file,
          "{\"daemon\": {\"log_level\": \"info\", \"status_rate_hz\": 20, \"session_status_period_ms\": 200},\n"
          " \"dds\": {\"domain_id\": %d, \"interface\": \"127.0.0.1\", \"multicast\": false, "
          "\"peers\": [\"127.0.0.1\"]},\n"
          " \"devices\": [%s%s%s]}\n",
          robotd->domain_id, kArm, with_gripper ? ", " : "", with_gripper ? kGripper : "");
  return fclose(file) == 0;
}

/* In the child: robotd, with its output in the log file. The kernel SIGKILLs it when the test
 * process ends, however that ends (an abort, or CTest's timeout). */
static void exec_robotd(const test_robotd* robotd, pid_t parent) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(127); /* the test was already gone */
  const int log_fd = open(robotd->log_path, O_WRONLY | O_TRUNC);
  dup2(log_fd, STDOUT_FILENO);
  dup2(log_fd, STDERR_FILENO);
  execl(ROBOTD_BINARY, ROBOTD_BINARY, "--config", robotd->config_path, (char*)NULL);
  _exit(127);
}

bool test_robotd_start(test_robotd* robotd, bool with_gripper) {
  memset(robotd, 0, sizeof *robotd);
  robotd->domain_lock_fd = -1;
  robotd->pid = -1;
  if (!lock_domain(robotd)) return false;
  if (!temp_file(robotd->config_path, sizeof robotd->config_path, "config") ||
      !temp_file(robotd->log_path, sizeof robotd->log_path, "log") || !write_config(robotd, with_gripper)) {
    fprintf(stderr, "cannot write robotd's config and log files in /tmp\n");
    return false;
  }
  const pid_t parent = getpid();
  robotd->pid = fork();
  if (robotd->pid == 0) exec_robotd(robotd, parent);
  return robotd->pid > 0;
}

bool test_robotd_wait_ready(robotd_client* client, int timeout_ms) {
  static robotd_device_info devices[4];
  for (int waited = 0; waited < timeout_ms; waited += 20) {
    size_t count = 0;
    if (robotd_list_devices(client, devices, 4, &count) == ROBOTD_OK && count > 0) {
      bool running = true;
      for (size_t i = 0; i < count; ++i) running = running && devices[i].state == ROBOTD_DEVICE_RUNNING;
      if (running) return true;
    }
    sleep_ms(20);
  }
  return false;
}

void test_robotd_print_log(const test_robotd* robotd) {
  FILE* file = fopen(robotd->log_path, "r");
  if (file == NULL) return;
  fprintf(stderr, "---- robotd's log ----\n");
  char line[512];
  while (fgets(line, sizeof line, file) != NULL) fputs(line, stderr);
  fclose(file);
}

void test_robotd_stop(test_robotd* robotd) {
  if (robotd->pid > 0) {
    kill(robotd->pid, SIGTERM);
    int status = 0;
    int waited = 0;
    while (waitpid(robotd->pid, &status, WNOHANG) == 0) {
      if (waited >= 10000) {
        kill(robotd->pid, SIGKILL);
        waitpid(robotd->pid, &status, 0);
        break;
      }
      sleep_ms(10);
      waited += 10;
    }
    robotd->pid = -1;
  }
  if (robotd->config_path[0] != '\0') remove(robotd->config_path);
  if (robotd->log_path[0] != '\0') remove(robotd->log_path);
  if (robotd->domain_lock_fd >= 0) close(robotd->domain_lock_fd); /* releases the flock */
  robotd->domain_lock_fd = -1;
}
