/* Acquire the simulated arm, move it, print its joint states, release it: the C API version of
 * clients/cpp/examples/move_arm.cpp.
 *
 *   build/bin/robotd --config config/robotd.json &      # robotd with the simulated robots
 *   build/bin/robotd_example_move_arm_c                   # this program
 *
 * Built against an installed robotd:  cc move_arm.c $(pkg-config --cflags --libs robotd-c) -lm */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <robotd/robotd.h>
#include <stdio.h>
#include <time.h>

static const double kPi = 3.14159265358979323846;

static double seconds_since(const struct timespec* start) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (double)(now.tv_sec - start->tv_sec) + (double)(now.tv_nsec - start->tv_nsec) * 1e-9;
}

static void sleep_ms(long ms) {
  const struct timespec duration = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&duration, NULL);
}

static int fail(const char* what) {
  fprintf(stderr, "%s: %s\n", what, robotd_last_error());
  return 1;
}

/* Streams a smooth 2-second move (cosine blend) of every joint by +0.5 rad, at 100 Hz, then
 * holds the target a moment. robotd rate-limits and interpolates it into its 1 kHz loop. */
static int move(robotd_session* session, const robotd_joint_state* start, size_t joints) {
  const double move_rad = 0.5;
  const double duration_s = 2.0;
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (double elapsed = 0; elapsed <= duration_s; elapsed = seconds_since(&t0)) {
    const double blend = 0.5 - 0.5 * cos(kPi * elapsed / duration_s);
    float positions[ROBOTD_MAX_JOINTS];
    for (size_t j = 0; j < joints; ++j) positions[j] = (float)(start->position[j] + move_rad * blend);
    if (robotd_send_positions(session, positions, joints) != ROBOTD_OK) return fail("send");
    sleep_ms(10);
  }
  for (int i = 0; i < 30; ++i) {
    robotd_keepalive(session);
    sleep_ms(10);
  }
  return 0;
}

/* Everything between acquiring the arm and releasing it. */
static int move_and_report(robotd_client* client, robotd_session* session) {
  static robotd_joint_state start, end; /* about 6 KB each: not on the stack */
  const char* session_id = NULL;
  int32_t motor_ids[ROBOTD_MAX_JOINTS];
  size_t joints = 0;
  robotd_session_id(session, &session_id);
  robotd_session_motor_ids(session, motor_ids, ROBOTD_MAX_JOINTS, &joints);
  printf("session %s on %zu motors\n", session_id, joints);

  if (robotd_next_joint_state(client, "arm", 2000, &start) != ROBOTD_OK) return fail("no joint state");
  if (move(session, &start, joints) != 0) return 1;
  if (robotd_next_joint_state(client, "arm", 2000, &end) != ROBOTD_OK) return fail("no joint state");
  for (size_t j = 0; j < joints; ++j) {
    printf("%-8s %+.3f rad -> %+.3f rad  (%.3f N·m)\n", end.names[j], start.position[j], end.position[j],
           end.effort[j]);
  }
  if (robotd_release(session, ROBOTD_BEHAVIOR_KEEP) != ROBOTD_OK) return fail("release");
  printf("released\n");
  return 0;
}

int main(void) {
  robotd_client* client = NULL;
  if (robotd_connect(NULL, &client) != ROBOTD_OK) return fail("cannot join DDS");
  /* Every motor of "arm"; if this program stops sending for 500 ms, robotd damps the arm. */
  robotd_session_request request;
  robotd_session_request_init(&request);
  request.device = "arm";
  request.mode = ROBOTD_MODE_POSITION;
  request.on_timeout = ROBOTD_BEHAVIOR_DAMPING;
  request.timeout_ms = 500;
  robotd_session* session = NULL;
  int status = 1;
  if (robotd_request_control(client, &request, &session) == ROBOTD_OK) {
    status = move_and_report(client, session);
  } else {
    fail("no control");
  }
  robotd_session_free(session); /* releases the motors if move_and_report did not */
  robotd_disconnect(client);
  return status;
}
