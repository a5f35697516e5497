/* Closed-loop PD control of the simulated arm through robotd: each tick's state (position q,
 * velocity dq) comes to the law, whose torques tau = kp (q_ref - q) - kd dq answer it and are
 * applied on the next tick. The C API version of clients/cpp/examples/pd_control.cpp.
 *
 *   build/bin/robotd --config config/robotd.json &      # robotd with the simulated robots
 *   build/bin/robotd_example_pd_control_c                 # this program
 *
 * Built against an installed robotd:  cc pd_control.c $(pkg-config --cflags --libs robotd-c) */
#include <robotd/robotd.h>
#include <stdio.h>

enum { kJoints = 6 };
static const double kStep_rad = 0.3; /* each joint's reference: where it started + 0.3 rad */
static const double kKp = 20.0;      /* N·m/rad: with the sim arm's 0.05 kg·m², about 3 Hz */
static const double kKd = 1.0;       /* N·m·s/rad: damped (ζ ≈ 0.65 with the joint's own damping) */

typedef struct pd_law {
  bool started;
  double reference[kJoints]; /* rad */
  float torques[kJoints];    /* N·m: the answer's array, valid until the next call */
} pd_law;

/* Called with each tick's state; fills the command that answers it. */
static int pd(const robotd_tick_state* state, robotd_command* command, void* user_data) {
  pd_law* law = (pd_law*)user_data;
  if (!law->started) {
    for (size_t j = 0; j < kJoints; ++j) law->reference[j] = state->position[j] + kStep_rad;
    law->started = true;
  }
  for (size_t j = 0; j < kJoints; ++j) {
    law->torques[j] = (float)(kKp * (law->reference[j] - state->position[j]) - kKd * state->velocity[j]);
  }
  command->torques = law->torques;
  return 0; /* go on (1: this is the last answer) */
}

static int fail(const char* what) {
  fprintf(stderr, "%s: %s\n", what, robotd_last_error());
  return 1;
}

int main(void) {
  robotd_client* client = NULL;
  robotd_session* session = NULL;
  robotd_session_request request;
  if (robotd_connect(NULL, &client) != ROBOTD_OK) return fail("connect");
  /* Torques for every motor of "arm"; robotd damps the arm if the answers stop for 500 ms, and
   * warns when fewer than 95 % of the last 100 ticks were answered in time. */
  robotd_session_request_init(&request);
  request.device = "arm";
  request.mode = ROBOTD_MODE_TORQUE;
  request.on_timeout = ROBOTD_BEHAVIOR_DAMPING;
  request.timeout_ms = 500;
  request.on_release = ROBOTD_BEHAVIOR_DAMPING;
  request.closed_loop = true;
  request.min_command_success_rate = 0.95F;
  request.on_low_success_rate = ROBOTD_LOW_RATE_WARN;
  if (robotd_request_control(client, &request, &session) != ROBOTD_OK) {
    robotd_disconnect(client);
    return fail("request_control");
  }

  pd_law law = {0};
  robotd_control_loop_options options;
  robotd_control_loop_report report;
  robotd_control_loop_options_init(&options);
  options.duration_ms = 3000;
  int status = 0;
  if (robotd_session_run_control_loop(session, pd, &law, &options, &report) != ROBOTD_OK) {
    status = fail("control loop");
  } else {
    printf("%llu ticks answered (ticks %llu..%llu, %llu skipped)\n", (unsigned long long)report.ticks_answered,
           (unsigned long long)report.first_tick, (unsigned long long)report.last_tick,
           (unsigned long long)report.ticks_skipped);
    robotd_tick_state last;
    if (robotd_session_next_tick(session, 1000, &last) == ROBOTD_OK) {
      for (size_t j = 0; j < kJoints; ++j) {
        printf("joint %zu: %+.3f rad (reference %+.3f)\n", j + 1, last.position[j], law.reference[j]);
      }
    }
    robotd_session_info info;
    if (robotd_session_get_info(session, 2000, &info) == ROBOTD_OK) {
      printf("robotd: %llu of %llu ticks answered in time (command success rate %.1f %%)\n",
             (unsigned long long)info.ticks_answered_in_time, (unsigned long long)info.ticks_to_answer,
             100.0 * info.command_success_rate);
    }
  }
  robotd_session_free(session); /* releases the arm: on_release DAMPING */
  robotd_disconnect(client);
  return status;
}
