/* The C API end to end, in C99, against a real robotd: `robotd_c_api_test <case>` runs one case
 * (each is its own CTest test, c_api.<case>). Every case gets a fresh robotd with the simulated
 * arm and a client connected to it as node "c_api_test". */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, nanosleep, setenv, popen */

#include <math.h>
#include <pthread.h>
#include <robotd/robotd.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "test_robotd.h"

#ifndef EXPECTED_VERSION
#error "EXPECTED_VERSION must be the project version"
#endif
#ifndef EXAMPLE_MOVE_ARM_C
#error "EXAMPLE_MOVE_ARM_C must point at the C example program"
#endif
#ifndef EXAMPLE_PD_CONTROL_C
#error "EXAMPLE_PD_CONTROL_C must point at the C closed-loop example program"
#endif

typedef struct fixture {
  test_robotd robotd;
  robotd_client* client;
} fixture;

/* ---- helpers ----------------------------------------------------------------------------- */

static void sleep_ms(long ms) {
  const struct timespec duration = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&duration, NULL);
}

static double now_s(void) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (double)now.tv_sec + (double)now.tv_nsec * 1e-9;
}

static robotd_client* connect_as(const fixture* f, const char* node_name) {
  robotd_client_options options;
  robotd_client* client = NULL;
  robotd_client_options_init(&options);
  options.domain_id = f->robotd.domain_id;
  options.node_name = node_name;
  options.service_timeout_ms = 3000;
  if (robotd_connect(&options, &client) != ROBOTD_OK) fprintf(stderr, "connect: %s\n", robotd_last_error());
  return client;
}

/* A session on "arm": `count` motors from `motor_ids` (0 = all), NULL (with the error printed) if refused. */
static robotd_session* acquire(robotd_client* client, const int32_t* motor_ids, size_t count, robotd_control_mode mode,
                               robotd_behavior on_timeout, int32_t timeout_ms) {
  robotd_session_request request;
  robotd_session* session = NULL;
  robotd_session_request_init(&request);
  request.device = "arm";
  request.motor_ids = motor_ids;
  request.motor_count = count;
  request.mode = mode;
  request.on_timeout = on_timeout;
  request.timeout_ms = timeout_ms;
  if (robotd_request_control(client, &request, &session) != ROBOTD_OK) {
    fprintf(stderr, "request_control: %s\n", robotd_last_error());
  }
  return session;
}

static double max_error(const robotd_joint_state* state, const float* target, size_t count) {
  double worst = 0;
  for (size_t j = 0; j < count; ++j) worst = fmax(worst, fabs(state->position[j] - (double)target[j]));
  return worst;
}

/* Streams `target` to every motor of the session until the arm is within 0.01 rad of it. */
static bool move_to(robotd_client* client, robotd_session* session, const float* target, size_t count,
                    double timeout_s) {
  static robotd_joint_state state;
  const double start = now_s();
  while (now_s() - start < timeout_s) {
    if (robotd_send_positions(session, target, count) != ROBOTD_OK) return false;
    if (robotd_next_joint_state(client, "arm", 1000, &state) == ROBOTD_OK && max_error(&state, target, count) < 0.01) {
      return true;
    }
  }
  return false;
}

/* The next device status of "arm" whose e-stop is `engaged`, within 3 s. */
static bool wait_for_estop(robotd_client* client, bool engaged, robotd_device_status* status) {
  const double start = now_s();
  while (now_s() - start < 3.0) {
    if (robotd_next_device_status(client, "arm", 1000, status) == ROBOTD_OK && status->estop_engaged == engaged) {
      return true;
    }
  }
  return false;
}

/* The sim driver's own view of the arm (device_call "state") contains `text`, within 2 s. */
static bool sim_state_shows(robotd_client* client, const char* text) {
  const double start = now_s();
  while (now_s() - start < 2.0) {
    char* json = NULL;
    if (robotd_device_call(client, "arm", "state", NULL, 2000, &json) == ROBOTD_OK) {
      const bool found = strstr(json, text) != NULL;
      robotd_free_string(json);
      if (found) return true;
    }
    sleep_ms(20);
  }
  fprintf(stderr, "the sim arm's state never showed %s\n", text);
  return false;
}

/* ---- cases ------------------------------------------------------------------------------- */

static bool versions_errors_and_connecting_from_the_environment(fixture* f) {
  CHECK(robotd_c_api_version() == ROBOTD_C_API_VERSION);
  CHECK(strcmp(robotd_version(), EXPECTED_VERSION) == 0);
  CHECK(strcmp(robotd_status_name(ROBOTD_REFUSED), "ROBOTD_REFUSED") == 0);
  CHECK(strcmp(robotd_status_name((robotd_status)99), "ROBOTD_UNKNOWN_STATUS") == 0);

  /* main() put ROBOTD_DOMAIN_ID in the environment: the defaults follow it. */
  robotd_client_options options;
  CHECK_OK(robotd_client_options_init(&options));
  CHECK(options.domain_id == f->robotd.domain_id);
  CHECK(strcmp(options.network_interface, "127.0.0.1") == 0);
  CHECK(strcmp(options.peers, "127.0.0.1") == 0);
  CHECK(!options.multicast);
  CHECK(strcmp(options.node_name, "robotd_client") == 0);
  CHECK(options.service_timeout_ms == 2000);

  robotd_client* client = NULL;
  size_t count = 0;
  CHECK_OK(robotd_connect(NULL, &client));
  CHECK_CALL(ROBOTD_BUFFER_TOO_SMALL, robotd_list_devices(client, NULL, 0, &count), "robotd drives 1 devices");
  CHECK(count == 1);
  /* A success clears the thread's last error. */
  CHECK_OK(robotd_client_options_init(&options));
  CHECK(strcmp(robotd_last_error(), "") == 0);
  robotd_disconnect(client);

  /* Explicit options, peers as a list. */
  options.domain_id = f->robotd.domain_id;
  options.peers = "127.0.0.1, localhost";
  options.node_name = "explicit";
  CHECK_OK(robotd_connect(&options, &client));
  CHECK_CALL(ROBOTD_BUFFER_TOO_SMALL, robotd_list_devices(client, NULL, 0, &count), "");
  robotd_disconnect(client);
  return true;
}

static bool list_devices_fills_what_fits(fixture* f) {
  static robotd_device_info devices[2];
  size_t count = 0;
  CHECK_CALL(ROBOTD_BUFFER_TOO_SMALL, robotd_list_devices(f->client, devices, 1, &count),
             "robotd drives 2 devices; the array holds 1");
  CHECK(count == 2);
  CHECK(strcmp(devices[0].name, "arm") == 0 || strcmp(devices[0].name, "gripper") == 0);

  CHECK_OK(robotd_list_devices(f->client, devices, 2, &count));
  CHECK(count == 2);
  const robotd_device_info* arm = strcmp(devices[0].name, "arm") == 0 ? &devices[0] : &devices[1];
  const robotd_device_info* gripper = arm == &devices[0] ? &devices[1] : &devices[0];
  CHECK(strcmp(arm->name, "arm") == 0);
  CHECK(strcmp(arm->driver, "sim") == 0);
  CHECK(strcmp(arm->model, "test arm") == 0);
  CHECK(strcmp(arm->kinematic_model, "parol6") == 0);
  CHECK(arm->state == ROBOTD_DEVICE_RUNNING);
  CHECK(arm->rate_hz == 1000.0);
  CHECK(arm->joint_count == 6);
  CHECK(strcmp(arm->joint_names[0], "joint1") == 0 && strcmp(arm->joint_names[5], "joint6") == 0);
  CHECK(arm->position_min[3] == -2.5 && arm->position_max[3] == 2.5);
  CHECK(arm->velocity_max[5] == 2.0 && arm->effort_max[5] == 40.0);
  CHECK(strcmp(gripper->name, "gripper") == 0);
  CHECK(gripper->joint_count == 2);
  CHECK(strcmp(gripper->kinematic_model, "") == 0);
  return true;
}

static bool request_accessors_and_release(fixture* f) {
  robotd_session_request request;
  CHECK_OK(robotd_session_request_init(&request));
  CHECK(request.device == NULL && request.motor_ids == NULL && request.motor_count == 0);
  CHECK(request.mode == ROBOTD_MODE_POSITION && request.on_timeout == ROBOTD_BEHAVIOR_DAMPING);
  CHECK(request.timeout_ms == 1000 && request.on_release == ROBOTD_BEHAVIOR_KEEP);
  CHECK(request.default_kp == NULL && request.default_kd == NULL);
  CHECK(request.policy_name == NULL && request.policy_file_name == NULL);

  request.device = NULL; /* robotd's only device */
  request.timeout_ms = 5000;
  robotd_session* session = NULL;
  CHECK_OK(robotd_request_control(f->client, &request, &session));

  const char* uuid = NULL;
  const char* session_id = NULL;
  const char* device = NULL;
  int32_t ids[ROBOTD_MAX_JOINTS];
  size_t count = 0;
  robotd_control_mode mode = ROBOTD_MODE_TORQUE;
  robotd_behavior behavior = ROBOTD_BEHAVIOR_KEEP;
  CHECK_OK(robotd_session_uuid(session, &uuid));
  CHECK(strlen(uuid) == 36 && uuid[8] == '-' && uuid[14] == '4');
  CHECK_OK(robotd_session_id(session, &session_id));
  CHECK(strlen(session_id) == 8 && strspn(session_id, "0123456789abcdef") == 8 && strstr(uuid, session_id) == NULL);
  CHECK_OK(robotd_session_device(session, &device));
  CHECK(strcmp(device, "arm") == 0);
  CHECK_OK(robotd_session_motor_ids(session, ids, ROBOTD_MAX_JOINTS, &count));
  CHECK(count == 6 && ids[0] == 0 && ids[5] == 5);
  ids[2] = -1;
  CHECK_CALL(ROBOTD_BUFFER_TOO_SMALL, robotd_session_motor_ids(session, ids, 2, &count),
             "the session has 6 motors; the array holds 2");
  CHECK(count == 6 && ids[1] == 1 && ids[2] == -1);
  CHECK_OK(robotd_session_mode(session, &mode));
  CHECK(mode == ROBOTD_MODE_POSITION);
  CHECK_OK(robotd_session_timeout_behavior(session, &behavior));
  CHECK(behavior == ROBOTD_BEHAVIOR_DAMPING);

  CHECK_OK(robotd_release(session, ROBOTD_BEHAVIOR_KEEP));
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_release(session, ROBOTD_BEHAVIOR_KEEP),
             "robotd_release: this session has already been released");
  CHECK_OK(robotd_session_uuid(session, &uuid)); /* the handle still answers */
  CHECK(strlen(uuid) == 36);
  robotd_session_free(session);

  /* The motors are free again; robotd_session_free releases an active session. */
  session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 5000);
  CHECK(session != NULL);
  robotd_session_free(session);
  CHECK(strcmp(robotd_last_error(), "") == 0);
  session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 5000);
  CHECK(session != NULL);
  robotd_session_free(session);
  return true;
}

static bool overlapping_request_is_refused_naming_the_holder(fixture* f) {
  const int32_t held_ids[] = {0, 1, 2};
  const int32_t overlap_ids[] = {2, 3};
  const int32_t disjoint_ids[] = {3, 4, 5};
  robotd_session* held = acquire(f->client, held_ids, 3, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_DAMPING, 5000);
  CHECK(held != NULL);
  const char* uuid = NULL;
  const char* session_id = NULL;
  CHECK_OK(robotd_session_uuid(held, &uuid));
  CHECK_OK(robotd_session_id(held, &session_id));

  robotd_client* planner = connect_as(f, "planner");
  CHECK(planner != NULL);
  robotd_session_request request;
  robotd_session_request_init(&request);
  request.device = "arm";
  request.motor_ids = overlap_ids;
  request.motor_count = 2;
  robotd_session* refused = NULL;
  CHECK_CALL(ROBOTD_REFUSED, robotd_request_control(planner, &request, &refused), "held by node 'c_api_test'");
  CHECK(strstr(robotd_last_error(), "robotd_request_control: robotd refused /request_control: ") ==
        robotd_last_error());
  CHECK(strstr(robotd_last_error(), session_id) != NULL); /* others learn the public id, never the uuid */
  CHECK(strstr(robotd_last_error(), uuid) == NULL);
  CHECK(strstr(robotd_last_error(), "motor(s) 2") != NULL);
  CHECK(refused == NULL);

  robotd_session* disjoint = acquire(planner, disjoint_ids, 3, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_DAMPING, 5000);
  CHECK(disjoint != NULL);
  robotd_session_free(disjoint);
  robotd_session_free(held);
  robotd_disconnect(planner);
  return true;
}

static bool send_positions_moves_the_arm(fixture* f) {
  const float target[6] = {0.5F, -0.3F, 0.8F, 0.2F, -0.6F, 1.0F};
  robotd_session* session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_DAMPING, 1000);
  CHECK(session != NULL);
  CHECK(move_to(f->client, session, target, 6, 5.0));

  static robotd_joint_state state;
  CHECK_OK(robotd_next_joint_state(f->client, "arm", 1000, &state));
  CHECK(strcmp(state.device, "arm") == 0);
  CHECK(state.joint_count == 6);
  CHECK(strcmp(state.names[0], "joint1") == 0 && strcmp(state.names[5], "joint6") == 0);
  CHECK(state.stamp_ns > 0);
  CHECK(max_error(&state, target, 6) < 0.01);
  CHECK_OK(robotd_release(session, ROBOTD_BEHAVIOR_KEEP));
  robotd_session_free(session);
  return true;
}

static bool send_command_with_gains_in_mixed_mode(fixture* f) {
  const int32_t ids[] = {0, 1};
  robotd_session* session = acquire(f->client, ids, 2, ROBOTD_MODE_MIXED, ROBOTD_BEHAVIOR_DAMPING, 5000);
  CHECK(session != NULL);
  const float positions[] = {0.0F, 0.0F};
  const float kp[] = {50.0F, 60.0F};
  const float kd[] = {2.0F, 3.0F};
  const float torques[] = {0.0F, 0.0F};
  robotd_command command = {0};
  command.motor_ids = ids;
  command.count = 2;
  command.positions = positions;
  command.kp = kp;
  command.kd = kd;
  command.torques = torques;
  CHECK_OK(robotd_send_command(session, &command));
  CHECK(sim_state_shows(f->client, "\"kd\":2.0,\"kp\":50.0"));
  CHECK(sim_state_shows(f->client, "\"kd\":3.0,\"kp\":60.0"));

  /* MIXED needs kp: robotd rejects the command and counts it. */
  robotd_device_status before;
  robotd_device_status after;
  CHECK_OK(robotd_next_device_status(f->client, "arm", 1000, &before));
  CHECK(before.commands_accepted > 0);
  command.kp = NULL;
  CHECK_OK(robotd_send_command(session, &command));
  const double start = now_s();
  do {
    CHECK_OK(robotd_next_device_status(f->client, "arm", 1000, &after));
  } while (after.commands_rejected == before.commands_rejected && now_s() - start < 2.0);
  CHECK(after.commands_rejected == before.commands_rejected + 1);

  /* No motor ids: the values address the session's motors in order. */
  const float other_kp[] = {70.0F, 80.0F};
  robotd_command in_order = {0};
  in_order.positions = positions;
  in_order.kp = other_kp;
  in_order.kd = kd;
  in_order.torques = torques;
  CHECK_OK(robotd_send_command(session, &in_order));
  CHECK(sim_state_shows(f->client, "\"kd\":2.0,\"kp\":70.0"));
  CHECK(sim_state_shows(f->client, "\"kd\":3.0,\"kp\":80.0"));
  robotd_session_free(session);
  return true;
}

static bool released_session_and_unknown_uuid_fail(fixture* f) {
  const float positions[6] = {0};
  robotd_session* session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 5000);
  CHECK(session != NULL);
  CHECK_OK(robotd_keepalive(session));
  CHECK_OK(robotd_release(session, ROBOTD_BEHAVIOR_KEEP));
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_send_positions(session, positions, 6), "has been released");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_keepalive(session), "has been released");
  robotd_session_free(session);

  CHECK_CALL(ROBOTD_REFUSED,
             robotd_release_by_uuid(f->client, "00000000-0000-4000-8000-000000000000", ROBOTD_BEHAVIOR_KEEP),
             "robotd refused /release_control");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT,
             robotd_release_by_uuid(f->client, "00000000-0000-4000-8000-000000000000-and-more", ROBOTD_BEHAVIOR_KEEP),
             "uuid is 45 bytes long: expected at most 39");

  /* A session is released by its uuid from any client that has it, as robotctl release does;
   * its public id releases nothing. */
  session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 5000);
  CHECK(session != NULL);
  const char* uuid = NULL;
  const char* session_id = NULL;
  CHECK_OK(robotd_session_uuid(session, &uuid));
  CHECK_OK(robotd_session_id(session, &session_id));
  robotd_client* operator_client = connect_as(f, "operator");
  CHECK(operator_client != NULL);
  CHECK_CALL(ROBOTD_REFUSED, robotd_release_by_uuid(operator_client, session_id, ROBOTD_BEHAVIOR_KEEP),
             "is the public id of a session of node 'c_api_test'");
  CHECK_OK(robotd_release_by_uuid(operator_client, uuid, ROBOTD_BEHAVIOR_KEEP));
  CHECK_CALL(ROBOTD_REFUSED, robotd_release(session, ROBOTD_BEHAVIOR_KEEP), "robotd refused /release_control");
  robotd_session_free(session);
  robotd_disconnect(operator_client);
  return true;
}

static void ignore_joint_state(const robotd_joint_state* state, void* user_data) {
  (void)state;
  (void)user_data;
}

static bool invalid_arguments_are_named(fixture* f) {
  robotd_client* client = NULL;
  robotd_client_options options;
  robotd_client_options_init(&options);
  options.service_timeout_ms = 0;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_connect(&options, &client),
             "robotd_connect: options->service_timeout_ms is 0: expected more than 0 milliseconds");
  CHECK(client == NULL);
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_connect(NULL, NULL), "robotd_connect: client is NULL: expected a");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_client_options_init(NULL), "options is NULL");

  size_t count = 0;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_list_devices(NULL, NULL, 0, &count),
             "robotd_list_devices: client is NULL: expected a client from robotd_connect");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_list_devices(f->client, NULL, 3, &count),
             "devices is NULL with capacity 3");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_list_devices(f->client, NULL, 0, NULL), "count is NULL");

  /* Requests: nothing reaches robotd. */
  const int32_t ids[ROBOTD_MAX_JOINTS + 1] = {0};
  const float gains[2] = {1.0F, 1.0F};
  char long_name[ROBOTD_NAME_CAPACITY + 1];
  memset(long_name, 'a', ROBOTD_NAME_CAPACITY);
  long_name[ROBOTD_NAME_CAPACITY] = '\0';
  robotd_session* session = NULL;
  robotd_session_request request;
  robotd_session_request_init(&request);
  request.motor_ids = ids;
  request.motor_count = ROBOTD_MAX_JOINTS + 1;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "request->motor_count is 65: expected at most ROBOTD_MAX_JOINTS (64)");
  request.motor_ids = NULL;
  request.motor_count = 2;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "request->motor_ids is NULL with motor_count 2");
  request.motor_count = 0;
  request.default_kp = gains;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "default_kp/default_kd given with motor_count 0");
  request.default_kp = NULL;
  request.mode = (robotd_control_mode)7;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "request->mode is 7: expected ROBOTD_MODE_POSITION, ROBOTD_MODE_TORQUE or ROBOTD_MODE_MIXED");
  request.mode = ROBOTD_MODE_POSITION;
  request.device = long_name;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "request->device is 64 bytes long: expected at most 63");
  request.device = "arm";
  char long_policy[1025];
  memset(long_policy, 'p', sizeof long_policy - 1);
  long_policy[sizeof long_policy - 1] = '\0';
  request.policy_file_name = long_policy;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "request->policy_file_name is 1024 bytes long: expected at most 1023");
  request.policy_file_name = NULL;
  long_policy[256] = '\0';
  request.policy_name = long_policy;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "request->policy_name is 256 bytes long: expected at most 255");
  request.policy_name = NULL;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, NULL), "session is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, NULL, &session), "request is NULL");
  CHECK(session == NULL);

  /* Commands of a real session. */
  session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 5000);
  CHECK(session != NULL);
  const float positions[ROBOTD_MAX_JOINTS + 1] = {0};
  robotd_command command = {0};
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_send_positions(session, positions, 3),
             "robotd_send_positions: count is 3: expected 6, one position per motor of the session");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_send_positions(session, NULL, 6), "positions_rad is NULL");
  command.count = ROBOTD_MAX_JOINTS + 1;
  command.motor_ids = ids;
  command.positions = positions;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_send_command(session, &command), "command->count is 65");
  command.count = 2;
  command.motor_ids = NULL;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_send_command(session, &command), "command->motor_ids is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_send_command(session, NULL), "command is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_release(session, (robotd_behavior)9),
             "behavior is 9: expected ROBOTD_BEHAVIOR_KEEP, ROBOTD_BEHAVIOR_DAMPING or ROBOTD_BEHAVIOR_ZERO_TORQUE");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_uuid(NULL, NULL),
             "session is NULL: expected a session from robotd_request_control");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_id(session, NULL), "session_id is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_keepalive(NULL), "session is NULL");
  CHECK_OK(robotd_release(session, ROBOTD_BEHAVIOR_KEEP));
  robotd_session_free(session);

  /* State, subscriptions, device calls. */
  static robotd_joint_state state;
  robotd_subscription* subscription = NULL;
  char* json = NULL;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_next_joint_state(f->client, "arm", -1, &state),
             "timeout_ms is -1: expected 0 or more milliseconds");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_next_joint_state(f->client, "arm", 100, NULL), "state is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_subscribe_joint_states(f->client, NULL, NULL, &subscription),
             "callback is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_subscribe_joint_states(f->client, ignore_joint_state, NULL, NULL),
             "subscription is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_device_call(f->client, "arm", NULL, NULL, 1000, &json), "op is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_device_call(f->client, "arm", "state", NULL, 0, &json),
             "timeout_ms is 0: expected more than 0 milliseconds");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_device_call(f->client, "arm", "state", NULL, 1000, NULL),
             "result_json is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_estop(f->client, long_name, NULL), "device is 64 bytes long");
  CHECK(json == NULL && subscription == NULL);

  /* Every free function takes NULL. */
  robotd_disconnect(NULL);
  robotd_session_free(NULL);
  robotd_free_string(NULL);
  CHECK_OK(robotd_unsubscribe(NULL));
  return true;
}

/* What the callbacks saw. */
typedef struct seen_values {
  int joint_states;
  int device_statuses;
  char device[ROBOTD_NAME_CAPACITY];
  size_t joint_count;
  bool tried_self_unsubscribe;
  robotd_status self_unsubscribe;
  char self_unsubscribe_error[256];
} seen_values;

/* The dispatch thread writes it, the test thread reads it. */
typedef struct samples {
  pthread_mutex_t mutex;
  seen_values values;
  robotd_subscription* self; /* the joint state subscription, to unsubscribe from its callback */
} samples;

static void count_joint_state(const robotd_joint_state* state, void* user_data) {
  samples* seen = user_data;
  pthread_mutex_lock(&seen->mutex);
  ++seen->values.joint_states;
  memcpy(seen->values.device, state->device, sizeof seen->values.device);
  seen->values.joint_count = state->joint_count;
  if (seen->self != NULL && !seen->values.tried_self_unsubscribe) {
    seen->values.tried_self_unsubscribe = true;
    seen->values.self_unsubscribe = robotd_unsubscribe(seen->self); /* refused: it would wait for itself */
    snprintf(seen->values.self_unsubscribe_error, sizeof seen->values.self_unsubscribe_error, "%s",
             robotd_last_error());
  }
  pthread_mutex_unlock(&seen->mutex);
}

static void count_device_status(const robotd_device_status* status, void* user_data) {
  samples* seen = user_data;
  pthread_mutex_lock(&seen->mutex);
  if (strcmp(status->device, "arm") == 0) ++seen->values.device_statuses;
  pthread_mutex_unlock(&seen->mutex);
}

static seen_values counts(samples* seen) {
  pthread_mutex_lock(&seen->mutex);
  const seen_values copy = seen->values;
  pthread_mutex_unlock(&seen->mutex);
  return copy;
}

/* Waits up to 3 s until the callbacks have seen at least that many samples. */
static bool wait_for_samples(samples* seen, int joint_states, int device_statuses) {
  const double start = now_s();
  while (now_s() - start < 3.0) {
    const seen_values now = counts(seen);
    if (now.joint_states >= joint_states && now.device_statuses >= device_statuses) return true;
    sleep_ms(10);
  }
  return false;
}

static bool subscriptions_call_back_until_unsubscribed(fixture* f) {
  static samples seen;
  pthread_mutex_init(&seen.mutex, NULL);
  robotd_subscription* joint_states = NULL;
  robotd_subscription* device_status = NULL;
  CHECK_OK(robotd_subscribe_joint_states(f->client, count_joint_state, &seen, &joint_states));
  CHECK_OK(robotd_subscribe_device_status(f->client, count_device_status, &seen, &device_status));
  pthread_mutex_lock(&seen.mutex);
  seen.self = joint_states;
  pthread_mutex_unlock(&seen.mutex);

  CHECK(wait_for_samples(&seen, 50, 3));
  seen_values now = counts(&seen);
  CHECK(strcmp(now.device, "arm") == 0);
  CHECK(now.joint_count == 6);
  CHECK(now.tried_self_unsubscribe && now.self_unsubscribe == ROBOTD_INVALID_ARGUMENT);
  CHECK(strstr(now.self_unsubscribe_error, "robotd_unsubscribe: called from a callback of the same client") != NULL);

  CHECK_OK(robotd_unsubscribe(joint_states));
  CHECK_OK(robotd_unsubscribe(device_status));
  const seen_values stopped = counts(&seen);
  sleep_ms(300);
  now = counts(&seen);
  CHECK(now.joint_states == stopped.joint_states);
  CHECK(now.device_statuses == stopped.device_statuses);
  pthread_mutex_destroy(&seen.mutex);
  return true;
}

static bool sessions_and_subscriptions_outlive_their_client(fixture* f) {
  static samples seen;
  pthread_mutex_init(&seen.mutex, NULL);
  robotd_client* client = connect_as(f, "short_lived");
  CHECK(client != NULL);
  robotd_subscription* subscription = NULL;
  CHECK_OK(robotd_subscribe_joint_states(client, count_joint_state, &seen, &subscription));
  robotd_session* session = acquire(client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 5000);
  CHECK(session != NULL);
  robotd_disconnect(client);

  const int before = counts(&seen).joint_states;
  CHECK(wait_for_samples(&seen, before + 20, 0));
  const float target[6] = {0.2F, 0, 0, 0, 0, 0};
  CHECK(move_to(f->client, session, target, 6, 5.0));
  CHECK_OK(robotd_unsubscribe(subscription));
  CHECK_OK(robotd_release(session, ROBOTD_BEHAVIOR_KEEP));
  robotd_session_free(session);
  pthread_mutex_destroy(&seen.mutex);
  return true;
}

static bool estop_latches_until_reset(fixture* f) {
  robotd_device_status status;
  CHECK_OK(robotd_estop(f->client, "arm", "C API test"));
  CHECK(wait_for_estop(f->client, true, &status));
  CHECK(status.state == ROBOTD_DEVICE_ESTOP);
  robotd_session_request request;
  robotd_session* session = NULL;
  robotd_session_request_init(&request);
  CHECK_CALL(ROBOTD_REFUSED, robotd_request_control(f->client, &request, &session), "robotd refused");

  CHECK_OK(robotd_reset_estop(f->client, "arm"));
  CHECK(wait_for_estop(f->client, false, &status));
  CHECK(status.state == ROBOTD_DEVICE_RUNNING);

  /* NULL = every device; the report says whether the e-stop reached each. */
  char* report = NULL;
  CHECK_OK(robotd_estop_report(f->client, NULL, NULL, &report));
  const bool reached = strstr(report, "reached 'arm' in ") != NULL;
  robotd_free_string(report);
  CHECK(reached);
  CHECK(wait_for_estop(f->client, true, &status));
  CHECK_OK(robotd_reset_estop(f->client, NULL));
  CHECK(wait_for_estop(f->client, false, &status));
  CHECK_CALL(ROBOTD_REFUSED, robotd_estop(f->client, "nope", NULL), "robotd refused /estop");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_estop_report(f->client, "arm", NULL, NULL), "report is NULL");
  return true;
}

static bool device_call_returns_json_or_the_drivers_refusal(fixture* f) {
  char* json = NULL;
  CHECK_OK(robotd_device_call(f->client, "arm", "state", NULL, 2000, &json));
  CHECK(json != NULL && json[0] == '{');
  CHECK(strstr(json, "\"joints\":[") != NULL && strstr(json, "\"name\":\"joint6\"") != NULL);
  robotd_free_string(json);
  json = NULL;

  CHECK_OK(robotd_device_call(f->client, "arm", "set_external_torque", "{\"joint\": \"joint2\", \"torque_nm\": -1.5}",
                              2000, &json));
  robotd_free_string(json);
  json = NULL;
  CHECK(sim_state_shows(f->client, "\"external_torque_nm\":-1.5"));

  CHECK_CALL(ROBOTD_REFUSED, robotd_device_call(f->client, "arm", "fly", NULL, 2000, &json),
             "unknown op \"fly\" (the sim driver has: ");
  CHECK_CALL(ROBOTD_REFUSED, robotd_device_call(f->client, "arm", "set_external_torque", "{\"joint\": 9}", 2000, &json),
             "set_external_torque: args.joint: expected an integer in 0..5, got 9");
  CHECK(json == NULL);
  return true;
}

/* A session that stops sending ends after its timeout, and robotd applies its fallback: damped,
 * the loaded joint2 sinks slowly. */
static bool silent_session_times_out_into_its_fallback(fixture* f) {
  char* json = NULL;
  CHECK_OK(robotd_device_call(f->client, "arm", "set_external_torque", "{\"joint\": \"joint2\", \"torque_nm\": -2.0}",
                              2000, &json));
  robotd_free_string(json);
  robotd_session* session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_DAMPING, 300);
  CHECK(session != NULL);
  const float hold[6] = {0};
  CHECK(move_to(f->client, session, hold, 6, 5.0));

  sleep_ms(800); /* silent for longer than the 300 ms timeout */
  static robotd_joint_state state;
  CHECK_OK(robotd_next_joint_state(f->client, "arm", 1000, &state));
  /* Damped (kd 10, friction 0.3), joint2 sinks under its 2 N·m load at about 0.19 rad/s. */
  CHECK(state.velocity[1] < -0.1 && state.velocity[1] > -0.35);
  CHECK_CALL(ROBOTD_REFUSED, robotd_release(session, ROBOTD_BEHAVIOR_KEEP), "robotd refused /release_control");
  robotd_session_free(session);

  /* Its motors are free again. */
  session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 1000);
  CHECK(session != NULL);
  robotd_session_free(session);
  return true;
}

/* clients/c/examples/move_arm.c runs as documented (main() put the domain in its environment). */
static bool example_program_moves_the_arm(fixture* f) {
  (void)f;
  FILE* output = popen(EXAMPLE_MOVE_ARM_C " 2>&1", "r");
  CHECK(output != NULL);
  char lines[16][256];
  int count = 0;
  while (count < 16 && fgets(lines[count], sizeof lines[count], output) != NULL) fputs(lines[count++], stderr);
  CHECK(pclose(output) == 0);
  CHECK(count == 8);
  CHECK(strncmp(lines[0], "session ", 8) == 0);
  CHECK(strstr(lines[1], "joint1") != NULL && strstr(lines[1], "+0.000 rad -> +0.500 rad") != NULL);
  CHECK(strcmp(lines[7], "released\n") == 0);
  return true;
}

/* ---- closed loop ------------------------------------------------------------------------- */

/* A PD law on every joint of the arm, towards reference[j], in torque mode. */
typedef struct pd_run {
  double reference[6];
  float torques[6];
  uint64_t previous_tick;
  uint64_t calls;
  uint64_t consecutive; /* calls whose tick followed the previous one's */
  double worst_error;   /* rad, at the last call */
} pd_run;

static int pd_law(const robotd_tick_state* state, robotd_command* command, void* user_data) {
  pd_run* run = (pd_run*)user_data;
  if (run->calls > 0 && state->tick == run->previous_tick + 1) ++run->consecutive;
  run->previous_tick = state->tick;
  ++run->calls;
  run->worst_error = 0;
  for (size_t j = 0; j < 6; ++j) {
    const double error = run->reference[j] - state->position[j];
    run->worst_error = fmax(run->worst_error, fabs(error));
    run->torques[j] = (float)(20.0 * error - 1.0 * state->velocity[j]);
  }
  command->torques = run->torques;
  /* Done once every joint has settled at its reference. */
  return run->calls > 200 && run->worst_error < 0.01 && fabs(state->velocity[0]) < 0.05 ? 1 : 0;
}

static robotd_session* acquire_closed_loop(robotd_client* client) {
  robotd_session_request request;
  robotd_session* session = NULL;
  robotd_session_request_init(&request);
  request.device = "arm";
  request.mode = ROBOTD_MODE_TORQUE;
  request.timeout_ms = 2000;
  request.on_release = ROBOTD_BEHAVIOR_DAMPING;
  request.closed_loop = true;
  request.min_command_success_rate = 0.5F;
  request.on_low_success_rate = ROBOTD_LOW_RATE_WARN;
  if (robotd_request_control(client, &request, &session) != ROBOTD_OK) {
    fprintf(stderr, "request_control: %s\n", robotd_last_error());
  }
  return session;
}

static bool control_loop_pd_moves_the_arm_and_robotd_counts_the_answers(fixture* f) {
  robotd_session* session = acquire_closed_loop(f->client);
  CHECK(session != NULL);
  robotd_tick_state first;
  CHECK_OK(robotd_session_next_tick(session, 10000, &first));
  CHECK(strcmp(first.device, "arm") == 0);
  CHECK(first.joint_count == 6);
  CHECK(first.period_ns == 1000000);
  pd_run run = {{0}, {0}, 0, 0, 0, 1.0};
  for (size_t j = 0; j < 6; ++j) run.reference[j] = first.position[j] + 0.3;

  robotd_control_loop_options options;
  robotd_control_loop_report report;
  CHECK_OK(robotd_control_loop_options_init(&options));
  options.state_timeout_ms = 5000; /* generous: a loaded machine */
  options.duration_ms = 30000;
  CHECK_OK(robotd_session_run_control_loop(session, pd_law, &run, &options, &report));
  fprintf(stderr, "[ measured ] %llu calls, %llu of them the tick after the previous, %llu skipped\n",
          (unsigned long long)run.calls, (unsigned long long)run.consecutive, (unsigned long long)report.ticks_skipped);
  /* The law finished: the arm reached the PD law's reference, which only its answers command. */
  CHECK(report.finished);
  CHECK(run.worst_error < 0.01);
  CHECK(report.ticks_seen == run.calls && report.ticks_answered == run.calls);
  CHECK(report.last_tick - report.first_tick + 1 == report.ticks_seen + report.ticks_skipped);
  CHECK(run.consecutive > 0);

  /* robotd counted the answers (its /session_status comes every second). */
  robotd_session_info info;
  const double start = now_s();
  do {
    CHECK_OK(robotd_session_get_info(session, 5000, &info));
    if (info.ticks_answered_in_time + info.ticks_answered_late > 0) break;
    sleep_ms(100);
  } while (now_s() - start < 10.0);
  CHECK(info.closed_loop);
  CHECK(info.ticks_answered_in_time + info.ticks_answered_late > 0);
  CHECK(info.ticks_to_answer >= info.ticks_answered_in_time + info.ticks_answered_late);
  CHECK(fabsf(info.min_command_success_rate - 0.5F) < 1e-6F);
  CHECK(info.on_low_success_rate == ROBOTD_LOW_RATE_WARN);
  robotd_session_free(session);
  return true;
}

static int bad_law(const robotd_tick_state* state, robotd_command* command, void* user_data) {
  (void)state;
  (void)command;
  (void)user_data;
  return 7;
}

static bool closed_loop_arguments_are_checked(fixture* f) {
  robotd_session_request request;
  robotd_session* session = NULL;
  robotd_session_request_init(&request);
  CHECK(request.on_low_success_rate == ROBOTD_LOW_RATE_WARN && !request.closed_loop);
  request.device = "arm";
  request.on_low_success_rate = (robotd_low_rate_action)5;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_request_control(f->client, &request, &session),
             "request->on_low_success_rate is 5: expected ROBOTD_LOW_RATE_WARN or ROBOTD_LOW_RATE_FALLBACK");
  CHECK(session == NULL);

  session = acquire_closed_loop(f->client);
  CHECK(session != NULL);
  robotd_tick_state state;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_run_control_loop(session, NULL, NULL, NULL, NULL), "law is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_next_tick(session, 1000, NULL), "state is NULL");
  robotd_control_loop_options options;
  CHECK_OK(robotd_control_loop_options_init(&options));
  CHECK(options.duration_ms == 0 && options.state_timeout_ms == 200 && options.stop == NULL);
  options.state_timeout_ms = 0;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_run_control_loop(session, pd_law, NULL, &options, NULL),
             "options->state_timeout_ms is 0");
  /* A tick of another device is not answered. */
  CHECK_OK(robotd_session_next_tick(session, 10000, &state));
  robotd_tick_state other = state;
  strcpy(other.device, "gripper");
  const robotd_command keepalive = {0};
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_answer(session, &other, &keepalive), "of device 'gripper'");
  /* A law returning something else than 0 or 1 ends the loop, naming it. */
  options.state_timeout_ms = 5000;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_run_control_loop(session, bad_law, NULL, &options, NULL),
             "the law returned 7");
  robotd_session_free(session);
  return true;
}

static bool example_pd_program_runs_the_law(fixture* f) {
  (void)f;
  FILE* output = popen(EXAMPLE_PD_CONTROL_C " 2>&1", "r");
  CHECK(output != NULL);
  char lines[16][256];
  int count = 0;
  while (count < 16 && fgets(lines[count], sizeof lines[count], output) != NULL) fputs(lines[count++], stderr);
  CHECK(pclose(output) == 0);
  CHECK(count == 8);
  CHECK(strstr(lines[0], " ticks answered (ticks ") != NULL);
  /* Every joint started at 0 and settled at its reference, 0.3 rad. */
  for (int j = 1; j <= 6; ++j)
    CHECK(strstr(lines[j], "+0.30") != NULL && strstr(lines[j], "(reference +0.300)") != NULL);
  CHECK(strncmp(lines[7], "robotd: ", 8) == 0);
  return true;
}

/* ---- main -------------------------------------------------------------------------------- */

/* ---- planned moves and RBTscript ------------------------------------------------------- */

/* Two postures of the test arm, which plans as a PAROL6 ("kinematic_model": "parol6"), clear of
 * its singularities, and the tool poses the PAROL6 model puts them at (kinematics::tool_pose and
 * pose_of, its Euler convention). */
static const double kPostureA[6] = {0.3, -1.4, 2.0, -0.4, 0.6, 0.8};
static const double kPostureB[6] = {0.4, -1.3, 1.9, -0.3, 0.7, 0.9};
static const robotd_pose kPoseA = {{0.205354116, 0.069758867, 0.113302291}, {2.473519361, 0.843256677, -3.140308032}};
static const robotd_pose kPoseB = {{0.175020425, 0.090879026, 0.084637194}, {2.104167985, 0.749339420, -3.030329488}};

/* The arm's measured joints are within 0.005 rad of `target` (the moves arrive within 0.1°). */
static bool arm_is_at(robotd_client* client, const double* target) {
  static robotd_joint_state state;
  CHECK_OK(robotd_next_joint_state(client, "arm", 1000, &state));
  for (size_t j = 0; j < 6; ++j) {
    if (fabs(state.position[j] - target[j]) > 0.005) {
      fprintf(stderr, "joint %zu is at %.4f rad, expected %.4f\n", j, state.position[j], target[j]);
      return false;
    }
  }
  return true;
}

static bool planned_moves_bring_the_arm_and_its_tool_to_their_goals(fixture* f) {
  robotd_session* session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 2000);
  CHECK(session != NULL);
  robotd_move_options options;
  robotd_move_report report;
  CHECK_OK(robotd_move_options_init(&options));
  CHECK(options.duration_s == 0 && options.shape == ROBOTD_SHAPE_DEFAULT && options.stop == NULL);
  options.speed_percent = 60;
  options.acceleration_percent = 60;
  CHECK_OK(robotd_session_move_joints(f->client, session, kPostureA, 6, &options, &report));
  CHECK(!report.stopped && report.fraction_done == 1.0 && report.joint_count == 6);
  CHECK(strstr(report.summary, "arrived") != NULL);
  CHECK(arm_is_at(f->client, kPostureA));

  /* The pose of posture B by IK and a joint move, then back to A's pose on a straight line. */
  CHECK_OK(robotd_move_options_init(&options));
  options.duration_s = 1.0;
  CHECK_OK(robotd_session_move_cartesian(f->client, session, &kPoseB, ROBOTD_PATH_JOINT, &options, &report));
  CHECK(arm_is_at(f->client, kPostureB));
  options.shape = ROBOTD_SHAPE_TRAPEZOID;
  CHECK_OK(robotd_session_move_cartesian(f->client, session, &kPoseA, ROBOTD_PATH_LINE, &options, NULL));
  CHECK(arm_is_at(f->client, kPostureA));

  /* A stop flag already set: the move ends at once, the arm held. */
  volatile int stop = 1;
  options.stop = &stop;
  CHECK_OK(robotd_session_move_joints(f->client, session, kPostureB, 6, &options, &report));
  CHECK(report.stopped);
  CHECK(arm_is_at(f->client, kPostureA));
  robotd_session_free(session);
  return true;
}

static bool planned_move_arguments_are_checked(fixture* f) {
  robotd_session* session = acquire(f->client, NULL, 0, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 2000);
  CHECK(session != NULL);
  robotd_move_options options;
  CHECK_OK(robotd_move_options_init(&options));
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_move_joints(f->client, session, kPostureA, 2, NULL, NULL),
             "robotd_session_move_joints: the target gives 2 joint value(s); device 'arm' has 6 joints");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_move_joints(f->client, session, NULL, 6, NULL, NULL),
             "target_rad is NULL");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_move_joints(NULL, session, kPostureA, 6, NULL, NULL),
             "client is NULL");
  options.duration_s = -1;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_move_joints(f->client, session, kPostureA, 6, &options, NULL),
             "options->duration_s is -1");
  CHECK_OK(robotd_move_options_init(&options));
  options.speed_percent = 150;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_move_joints(f->client, session, kPostureA, 6, &options, NULL),
             "options->speed_percent is 150");
  CHECK_OK(robotd_move_options_init(&options));
  options.shape = (robotd_move_shape)7;
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_move_joints(f->client, session, kPostureA, 6, &options, NULL),
             "options->shape is 7");
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT,
             robotd_session_move_cartesian(f->client, session, &kPoseA, (robotd_cartesian_path)3, NULL, NULL),
             "path is 3");
  const robotd_pose far = {{2.0, 0, 0.3}, {0, 0, 0}};
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT,
             robotd_session_move_cartesian(f->client, session, &far, ROBOTD_PATH_JOINT, NULL, NULL), "");
  robotd_session_free(session);

  const int32_t some[2] = {0, 1};
  session = acquire(f->client, some, 2, ROBOTD_MODE_POSITION, ROBOTD_BEHAVIOR_KEEP, 2000);
  CHECK(session != NULL);
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_session_move_joints(f->client, session, kPostureA, 6, NULL, NULL),
             "a planned move needs a session on the arm's joints of device 'arm'");
  robotd_session_free(session);
  return true;
}

typedef struct statements_seen {
  size_t count;
  size_t last_line;
  uint64_t last_pass;
} statements_seen;

static void count_statement(size_t line, const char* statement, uint64_t pass, void* user_data) {
  statements_seen* seen = (statements_seen*)user_data;
  (void)statement;
  ++seen->count;
  seen->last_line = line;
  seen->last_pass = pass;
}

static bool rbtscript_reports_problems_with_their_line_and_moves_nothing(fixture* f) {
  robotd_rbtscript_report* report = NULL;
  robotd_rbtscript_outcome outcome;
  robotd_rbtscript_problem problem;
  /* A syntax error: the program is not checked against the device. */
  CHECK_OK(robotd_run_rbtscript(f->client, "Delay(1)\nMoveJoint(1,2\n", NULL, &report));
  CHECK_OK(robotd_rbtscript_report_outcome(report, &outcome));
  CHECK(outcome.syntax_errors && outcome.problem_count == 1 && outcome.end == ROBOTD_RBTSCRIPT_NOT_RUN);
  CHECK_OK(robotd_rbtscript_report_problem(report, 0, &problem));
  CHECK(problem.line == 2 && strcmp(problem.statement, "") == 0);
  CHECK(strncmp(problem.description, "line 2, column ", 15) == 0);
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_rbtscript_report_problem(report, 1, &problem),
             "index is 1: the report has 1 problem(s)");
  robotd_rbtscript_report_free(report);

  /* A joint past the arm's limit (±2.5 rad) on line 3, in a dry run and in a run. */
  const char* program = "Begin()\nMoveJoint(10,-60,100,0,20,0,t=2)\nMoveJoint(0,0,170,0,0,0)\nEnd()\n";
  robotd_rbtscript_options options;
  CHECK_OK(robotd_rbtscript_options_init(&options));
  CHECK(options.session_timeout_ms == 2000 && options.loops == 0 && !options.dry_run);
  for (int dry_run = 1; dry_run >= 0; --dry_run) {
    options.dry_run = dry_run == 1;
    CHECK_OK(robotd_run_rbtscript(f->client, program, &options, &report));
    CHECK_OK(robotd_rbtscript_report_outcome(report, &outcome));
    CHECK(!outcome.syntax_errors && outcome.problem_count == 1 && outcome.end == ROBOTD_RBTSCRIPT_NOT_RUN);
    CHECK(strcmp(outcome.device, "arm") == 0 && outcome.moves_planned == 1);
    CHECK_OK(robotd_rbtscript_report_problem(report, 0, &problem));
    CHECK(problem.line == 3 && problem.column == 1);
    CHECK(strcmp(problem.statement, "MoveJoint(0,0,170,0,0,0)") == 0);
    CHECK(strstr(problem.description, "line 3, column 1: MoveJoint(0,0,170,0,0,0): ") == problem.description);
    robotd_rbtscript_report_free(report);
  }
  robotd_rbtscript_report_free(NULL);
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_run_rbtscript(f->client, NULL, NULL, &report), "program_text is NULL");
  options.device = "nowhere";
  CHECK_CALL(ROBOTD_INVALID_ARGUMENT, robotd_run_rbtscript(f->client, "Delay(1)", &options, &report),
             "robotd has no device 'nowhere'");
  return true;
}

static void* raise_after_a_while(void* flag) {
  sleep_ms(300);
  *(volatile int*)flag = 1;
  return NULL;
}

static bool rbtscript_runs_a_program_on_the_arm_until_its_end_or_a_stop(fixture* f) {
  static const double kEnd[6] = {
      0.17453292519943295, -1.0471975511965976, 1.7453292519943295, 0, 0.3490658503988659, 0};
  robotd_rbtscript_report* report = NULL;
  robotd_rbtscript_outcome outcome;
  robotd_rbtscript_options options;
  statements_seen seen = {0, 0, 0};
  CHECK_OK(robotd_rbtscript_options_init(&options));
  options.loops = 2;
  options.on_statement = count_statement;
  options.user_data = &seen;
  CHECK_OK(
      robotd_run_rbtscript(f->client, "MoveJoint(10,-60,100,0,20,0,t=2)\nDelay(0.1)\nLoop()\n", &options, &report));
  CHECK_OK(robotd_rbtscript_report_outcome(report, &outcome));
  CHECK(outcome.end == ROBOTD_RBTSCRIPT_LOOP_LIMIT && outcome.passes == 2 && outcome.problem_count == 0);
  CHECK(seen.count >= 5 && seen.last_line == 3 && seen.last_pass == 2);
  robotd_rbtscript_report_free(report);
  CHECK(arm_is_at(f->client, kEnd));

  /* A long delay, ended by the stop flag from another thread: the arm stays where it was. */
  volatile int stop = 0;
  pthread_t raiser;
  CHECK_OK(robotd_rbtscript_options_init(&options));
  options.stop = &stop;
  CHECK(pthread_create(&raiser, NULL, raise_after_a_while, (void*)&stop) == 0);
  const robotd_status status =
      robotd_run_rbtscript(f->client, "Delay(30)\nMoveJoint(0,0,0,0,0,0)\n", &options, &report);
  pthread_join(raiser, NULL);
  CHECK_OK(status);
  CHECK_OK(robotd_rbtscript_report_outcome(report, &outcome));
  CHECK(outcome.end == ROBOTD_RBTSCRIPT_STOPPED);
  robotd_rbtscript_report_free(report);
  CHECK(arm_is_at(f->client, kEnd));
  return true;
}

typedef struct test_case {
  const char* name;
  bool (*run)(fixture* f);
  bool with_gripper; /* a second device next to the arm */
} test_case;

/* tests/c/CMakeLists.txt registers each name here as the CTest test c_api.<name>. */
static const test_case kCases[] = {
    {"versions_errors_and_connecting_from_the_environment", versions_errors_and_connecting_from_the_environment, false},
    {"list_devices_fills_what_fits", list_devices_fills_what_fits, true},
    {"request_accessors_and_release", request_accessors_and_release, false},
    {"overlapping_request_is_refused_naming_the_holder", overlapping_request_is_refused_naming_the_holder, false},
    {"send_positions_moves_the_arm", send_positions_moves_the_arm, false},
    {"send_command_with_gains_in_mixed_mode", send_command_with_gains_in_mixed_mode, false},
    {"released_session_and_unknown_uuid_fail", released_session_and_unknown_uuid_fail, false},
    {"invalid_arguments_are_named", invalid_arguments_are_named, false},
    {"subscriptions_call_back_until_unsubscribed", subscriptions_call_back_until_unsubscribed, false},
    {"sessions_and_subscriptions_outlive_their_client", sessions_and_subscriptions_outlive_their_client, false},
    {"estop_latches_until_reset", estop_latches_until_reset, false},
    {"device_call_returns_json_or_the_drivers_refusal", device_call_returns_json_or_the_drivers_refusal, false},
    {"silent_session_times_out_into_its_fallback", silent_session_times_out_into_its_fallback, false},
    {"example_program_moves_the_arm", example_program_moves_the_arm, false},
    {"control_loop_pd_moves_the_arm_and_robotd_counts_the_answers",
     control_loop_pd_moves_the_arm_and_robotd_counts_the_answers, false},
    {"closed_loop_arguments_are_checked", closed_loop_arguments_are_checked, false},
    {"example_pd_program_runs_the_law", example_pd_program_runs_the_law, false},
    {"planned_moves_bring_the_arm_and_its_tool_to_their_goals", planned_moves_bring_the_arm_and_its_tool_to_their_goals,
     false},
    {"planned_move_arguments_are_checked", planned_move_arguments_are_checked, false},
    {"rbtscript_reports_problems_with_their_line_and_moves_nothing",
     rbtscript_reports_problems_with_their_line_and_moves_nothing, false},
    {"rbtscript_runs_a_program_on_the_arm_until_its_end_or_a_stop",
     rbtscript_runs_a_program_on_the_arm_until_its_end_or_a_stop, false},
};

static const test_case* find_case(const char* name) {
  for (size_t i = 0; i < sizeof kCases / sizeof kCases[0]; ++i) {
    if (strcmp(kCases[i].name, name) == 0) return &kCases[i];
  }
  return NULL;
}

int main(int argc, char** argv) {
  const test_case* test = argc == 2 ? find_case(argv[1]) : NULL;
  if (test == NULL) {
    fprintf(stderr, "usage: %s <case>; the cases:\n", argv[0]);
    for (size_t i = 0; i < sizeof kCases / sizeof kCases[0]; ++i) fprintf(stderr, "  %s\n", kCases[i].name);
    return 2;
  }
  fixture f;
  if (!test_robotd_start(&f.robotd, test->with_gripper)) {
    test_robotd_stop(&f.robotd);
    return 1;
  }
  /* Before any thread starts: clients connecting from the environment, and the example, find
   * this test's robotd. */
  char domain[16];
  snprintf(domain, sizeof domain, "%d", f.robotd.domain_id);
  setenv("ROBOTD_DOMAIN_ID", domain, 1);

  f.client = connect_as(&f, "c_api_test");
  bool passed = f.client != NULL && test_robotd_wait_ready(f.client, 20000);
  if (!passed) fprintf(stderr, "robotd did not become ready on domain %d\n", f.robotd.domain_id);
  passed = passed && test->run(&f);
  robotd_disconnect(f.client);
  if (!passed) test_robotd_print_log(&f.robotd);
  test_robotd_stop(&f.robotd);
  fprintf(stderr, "%s: %s\n", test->name, passed ? "passed" : "FAILED");
  return passed ? 0 : 1;
}
