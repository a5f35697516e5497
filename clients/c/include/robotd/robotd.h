/* The robotd C API: a small, stable C interface over the robotd C++ client (C99, and C++).
 *
 *   robotd_client* client = NULL;
 *   robotd_session* session = NULL;
 *   robotd_session_request request;
 *   if (robotd_connect(NULL, &client) != ROBOTD_OK) puts(robotd_last_error());
 *   robotd_session_request_init(&request);
 *   request.device = "arm";
 *   if (robotd_request_control(client, &request, &session) != ROBOTD_OK) puts(robotd_last_error());
 *   robotd_send_positions(session, positions_rad, 6);   (repeatedly: robotd times out a silent session)
 *   robotd_session_free(session);                        (releases the motors)
 *   robotd_disconnect(client);
 *
 * Conventions:
 * - Every call that can fail returns a robotd_status; on failure robotd_last_error() says why.
 *   Results go to out-parameters, written only on success (and the count and the items that fit
 *   on ROBOTD_BUFFER_TOO_SMALL).
 * - Handles (robotd_client, robotd_session, robotd_subscription) are opaque; each has one
 *   function that frees it and accepts NULL.
 * - Structs are plain data with fixed-size arrays. Text fields are always NUL-terminated; a
 *   longer text from robotd is cut at the field's capacity.
 * - Units are SI and radians, as on robotd's DDS interface.
 *
 * Threading: a client may be shared by threads. A session, and any one struct, is used by one
 * thread at a time. Callbacks run on the client's dispatch thread (see robotd_subscribe_joint_states).
 *
 * Lifetime: sessions and subscriptions keep their client's DDS connection open, so they may be
 * freed before or after robotd_disconnect; the connection closes when the last of them is freed.
 *
 * docs/clients.md ("C") is the guide. */
#ifndef ROBOTD_ROBOTD_H
#define ROBOTD_ROBOTD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__)
#define ROBOTD_API __attribute__((visibility("default")))
#else
#define ROBOTD_API
#endif

/* In C every int32_t is a value of an enum type; in C++ an enum holds only the values its
 * enumerators span unless it has a fixed underlying type. This gives it one, so that C++ code
 * (the library itself) may read whatever a C caller passed and reject it as invalid. */
#ifdef __cplusplus
#define ROBOTD_ENUM_BASE : int32_t
#else
#define ROBOTD_ENUM_BASE
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* This is a C header: typedef is its only spelling. NOLINTBEGIN(modernize-use-using) */

/* The version of this API: changes when a function or struct of this header changes. */
#define ROBOTD_C_API_VERSION 5

#define ROBOTD_MAX_JOINTS 64     /* joints per device (the driver API's limit) */
#define ROBOTD_NAME_CAPACITY 64  /* device, driver, model and joint names, NUL included */
#define ROBOTD_UUID_CAPACITY 40  /* a session uuid (36 characters, 8-4-4-4-12), NUL included */
#define ROBOTD_TEXT_CAPACITY 256 /* state and fault texts, NUL included */

typedef enum robotd_status ROBOTD_ENUM_BASE {
  ROBOTD_OK = 0,
  ROBOTD_TIMEOUT = 1,          /* no answer or sample within the deadline */
  ROBOTD_NOT_AVAILABLE = 2,    /* robotd (or the service) is not reachable on this DDS domain */
  ROBOTD_REFUSED = 3,          /* robotd answered and said no; robotd_last_error() has its reason */
  ROBOTD_INVALID_ARGUMENT = 4, /* the caller passed something malformed; nothing was sent */
  ROBOTD_TRANSPORT = 5,        /* the DDS layer failed */
  ROBOTD_NOT_PERMITTED = 6,    /* DDS Security: this identity's permissions do not allow it */
  ROBOTD_BUFFER_TOO_SMALL = 7, /* the caller's array holds fewer items than there are */
  ROBOTD_INTERNAL_ERROR = 8    /* out of memory, or a failure inside this library */
} robotd_status;

/* How a session commands its motors. */
typedef enum robotd_control_mode ROBOTD_ENUM_BASE {
  ROBOTD_MODE_POSITION = 0, /* positions (optional velocities, kp, kd) */
  ROBOTD_MODE_TORQUE = 1,   /* torques */
  ROBOTD_MODE_MIXED = 2     /* positions, kp, kd and torques: the MIT law with feed-forward */
} robotd_control_mode;

/* What happens to a session's motors on timeout or release. */
typedef enum robotd_behavior ROBOTD_ENUM_BASE {
  ROBOTD_BEHAVIOR_KEEP = 0,       /* hold where commanded now */
  ROBOTD_BEHAVIOR_DAMPING = 1,    /* kp = 0, kd = the session's default kd */
  ROBOTD_BEHAVIOR_ZERO_TORQUE = 2 /* let go */
} robotd_behavior;

typedef enum robotd_device_state ROBOTD_ENUM_BASE {
  ROBOTD_DEVICE_CONNECTING = 0,
  ROBOTD_DEVICE_RUNNING = 1,
  ROBOTD_DEVICE_FAULT = 2,
  ROBOTD_DEVICE_ESTOP = 3,
  ROBOTD_DEVICE_MAINTENANCE = 4, /* recover or reset_zero in progress */
  ROBOTD_DEVICE_STOPPED = 5
} robotd_device_state;

/* What robotd does when a closed-loop session's command success rate falls below its minimum. */
typedef enum robotd_low_rate_action ROBOTD_ENUM_BASE {
  ROBOTD_LOW_RATE_WARN = 0,    /* log it and flag it in /session_status (success_rate_low) */
  ROBOTD_LOW_RATE_FALLBACK = 1 /* end the session with its on_timeout behavior, as on timeout */
} robotd_low_rate_action;

/* ---- Errors and versions -------------------------------------------------------------- */

/* The calling thread's message for its last call: why it failed, or "" if it succeeded. When
 * robotd refused, it carries robotd's own reason. Valid until this thread's next robotd call. */
ROBOTD_API const char* robotd_last_error(void);
/* "ROBOTD_OK", "ROBOTD_TIMEOUT", ...; "ROBOTD_UNKNOWN_STATUS" for other values. */
ROBOTD_API const char* robotd_status_name(robotd_status status);

/* ROBOTD_C_API_VERSION of the library loaded, which may differ from the header compiled against. */
ROBOTD_API int robotd_c_api_version(void);
/* The robotd project version, e.g. "0.1.0". */
ROBOTD_API const char* robotd_version(void);

/* ---- Connecting ------------------------------------------------------------------------ */

typedef struct robotd_client robotd_client;

typedef struct robotd_client_options {
  int32_t domain_id;
  const char* network_interface; /* address or interface name; NULL or "" = Cyclone DDS picks */
  const char* peers;             /* comma-separated addresses to reach robotd at; NULL or "" = none */
  bool multicast;
  const char* node_name;      /* how robotd names this client, e.g. in a refusal */
  int32_t service_timeout_ms; /* the longest any service call waits, > 0 */
} robotd_client_options;

/* The defaults, as robotd_connect(NULL, ...) uses them: domain 0 on loopback, overridden by
 * ROBOTD_DOMAIN_ID, ROBOTD_DDS_INTERFACE, ROBOTD_DDS_PEERS and ROBOTD_DDS_MULTICAST=1. The
 * strings point into storage of the calling thread, valid until its next call of this function. */
ROBOTD_API robotd_status robotd_client_options_init(robotd_client_options* options);

/* Joins robotd's DDS domain (options NULL = robotd_client_options_init's defaults). Succeeds
 * even if robotd is not running; calls then fail with ROBOTD_NOT_AVAILABLE after the service
 * timeout. A DDS Security identity is taken from ROBOTD_DDS_SECURITY_* in the environment. */
ROBOTD_API robotd_status robotd_connect(const robotd_client_options* options, robotd_client** client);
/* Frees the handle. NULL is allowed. */
ROBOTD_API void robotd_disconnect(robotd_client* client);

/* ---- Devices --------------------------------------------------------------------------- */

typedef struct robotd_device_info {
  char name[ROBOTD_NAME_CAPACITY];
  char driver[ROBOTD_NAME_CAPACITY];
  char model[ROBOTD_NAME_CAPACITY];
  char kinematic_model[ROBOTD_NAME_CAPACITY]; /* the arm model clients plan motion with, e.g. "parol6"; "" when none */
  robotd_device_state state;
  double rate_hz; /* the control loop's rate */
  size_t joint_count;
  char joint_names[ROBOTD_MAX_JOINTS][ROBOTD_NAME_CAPACITY];
  double position_min[ROBOTD_MAX_JOINTS]; /* rad */
  double position_max[ROBOTD_MAX_JOINTS]; /* rad */
  double velocity_max[ROBOTD_MAX_JOINTS]; /* rad/s */
  double effort_max[ROBOTD_MAX_JOINTS];   /* N·m */
} robotd_device_info;

/* The devices robotd drives. *count = how many there are; if that is more than `capacity`, the
 * first `capacity` are filled and ROBOTD_BUFFER_TOO_SMALL is returned. devices may be NULL
 * when capacity is 0 (to ask for the count). */
ROBOTD_API robotd_status robotd_list_devices(robotd_client* client, robotd_device_info* devices, size_t capacity,
                                             size_t* count);

/* ---- Sessions -------------------------------------------------------------------------- */

typedef struct robotd_session robotd_session;

typedef struct robotd_session_request {
  const char* device;         /* NULL or "" = robotd's only device */
  const int32_t* motor_ids;   /* motor_count ids, or NULL with motor_count 0 = every motor */
  size_t motor_count;         /* 0..ROBOTD_MAX_JOINTS */
  robotd_control_mode mode;   /* default POSITION */
  robotd_behavior on_timeout; /* default DAMPING: what robotd does if the session goes silent */
  int32_t timeout_ms;         /* default 1000: silence after which robotd ends the session */
  const float* default_kp;    /* NULL, or motor_count gains for the session's commands */
  const float* default_kd;
  robotd_behavior on_release;   /* default KEEP: what robotd_session_free's release asks for */
  const char* policy_name;      /* NULL or "" = none; else who commands, shown in /session_status (<= 255 bytes) */
  const char* policy_file_name; /* NULL or "" = none; the file that policy was loaded from (<= 1023 bytes) */
  /* Closed loop (see "Closed loop" below). closed_loop: the session reads its device's tick states
   * from the start: robotd_request_control returns once its reader has matched robotd's writer, so
   * the first tick after the grant reaches it (false: the reader is made on the first
   * robotd_session_next_tick / run_control_loop / send_aligned, and robotd publishes no tick
   * states for a session that does not read them). */
  bool closed_loop;
  float min_command_success_rate;             /* 0..1, 0 = none: the least fraction of ticks answered in time */
  robotd_low_rate_action on_low_success_rate; /* default WARN: what robotd does below that minimum */
} robotd_session_request;

ROBOTD_API robotd_status robotd_session_request_init(robotd_session_request* request);

/* Asks robotd for exclusive control of the request's motors. Refused (ROBOTD_REFUSED) when
 * another session holds any of them; robotd_last_error() then names the holder. */
ROBOTD_API robotd_status robotd_request_control(robotd_client* client, const robotd_session_request* request,
                                                robotd_session** session);

/* The session's uuid, public id and granted device; the strings live as long as the session
 * handle. The uuid commands and releases the session: keep it to this program. Others (and
 * /session_status, refusals, robotd's log) know the session by its public id only. */
ROBOTD_API robotd_status robotd_session_uuid(const robotd_session* session, const char** uuid);
ROBOTD_API robotd_status robotd_session_id(const robotd_session* session, const char** session_id);
ROBOTD_API robotd_status robotd_session_device(const robotd_session* session, const char** device);
/* The granted motor ids, in the order send_positions uses. Same capacity rules as list_devices. */
ROBOTD_API robotd_status robotd_session_motor_ids(const robotd_session* session, int32_t* motor_ids, size_t capacity,
                                                  size_t* count);
ROBOTD_API robotd_status robotd_session_mode(const robotd_session* session, robotd_control_mode* mode);
/* What robotd really does on timeout (a position-only arm cannot damp). */
ROBOTD_API robotd_status robotd_session_timeout_behavior(const robotd_session* session, robotd_behavior* behavior);

/* Releases the motors now (robotd applies `behavior`). The handle stays valid for its accessors;
 * commands and a second release fail with ROBOTD_INVALID_ARGUMENT. */
ROBOTD_API robotd_status robotd_release(robotd_session* session, robotd_behavior behavior);
/* Releases the session with this uuid (like robotctl release), e.g. one an earlier run of this
 * program was granted and whose uuid it kept. A public id releases nothing. */
ROBOTD_API robotd_status robotd_release_by_uuid(robotd_client* client, const char* uuid, robotd_behavior behavior);
/* Releases the session with its request's on_release if still active, then frees the handle.
 * May wait up to the service timeout for robotd; robotd_last_error() says why a release failed
 * ("" if it did not). NULL is allowed. */
ROBOTD_API void robotd_session_free(robotd_session* session);

/* ---- Commands -------------------------------------------------------------------------- */

/* One command; zero-initialise it and set what it carries. With motor_ids NULL and count 0 it
 * addresses the session's motors in order, and each array holds one value per session motor;
 * otherwise each array holds `count` values for `motor_ids`. Each array may be NULL. No values
 * at all is a keepalive. Which arrays a mode needs: POSITION positions; TORQUE torques; MIXED
 * positions, kp, kd and torques. robotd's verdict shows in robotd_device_status's counters. */
typedef struct robotd_command {
  const int32_t* motor_ids;
  size_t count;            /* 0..ROBOTD_MAX_JOINTS */
  const float* positions;  /* rad */
  const float* velocities; /* rad/s */
  const float* kp;         /* N·m/rad */
  const float* kd;         /* N·m·s/rad */
  const float* torques;    /* N·m */
} robotd_command;

/* Publishes a command; fails only on malformed input, a released session or a DDS error. */
ROBOTD_API robotd_status robotd_send_command(robotd_session* session, const robotd_command* command);
/* Positions for every motor of the session, in robotd_session_motor_ids order (count = that many). */
ROBOTD_API robotd_status robotd_send_positions(robotd_session* session, const float* positions_rad, size_t count);
/* Renews the session without moving anything. */
ROBOTD_API robotd_status robotd_keepalive(robotd_session* session);

/* ---- State ----------------------------------------------------------------------------- */

typedef struct robotd_joint_state {
  char device[ROBOTD_NAME_CAPACITY];
  int64_t stamp_ns; /* CLOCK_REALTIME */
  size_t joint_count;
  char names[ROBOTD_MAX_JOINTS][ROBOTD_NAME_CAPACITY];
  double position[ROBOTD_MAX_JOINTS]; /* rad */
  double velocity[ROBOTD_MAX_JOINTS]; /* rad/s */
  double effort[ROBOTD_MAX_JOINTS];   /* N·m */
} robotd_joint_state;

typedef struct robotd_device_status {
  char device[ROBOTD_NAME_CAPACITY];
  int64_t stamp_ns; /* CLOCK_REALTIME */
  robotd_device_state state;
  char state_text[ROBOTD_TEXT_CAPACITY];
  int32_t fault_code;
  char fault_text[ROBOTD_TEXT_CAPACITY];
  bool estop_engaged;
  float loop_period_p50_us; /* the control loop's period over its statistics window */
  float loop_period_p99_us;
  float loop_period_max_us;
  uint64_t loop_overruns;     /* ticks missed since start */
  uint64_t commands_accepted; /* since start */
  uint64_t commands_rejected; /* since start, every reason */
} robotd_device_status;

/* The next /joint_states sample robotd publishes for `device` (NULL or "" = any device), or
 * ROBOTD_TIMEOUT after timeout_ms. */
ROBOTD_API robotd_status robotd_next_joint_state(robotd_client* client, const char* device, int32_t timeout_ms,
                                                 robotd_joint_state* state);
/* The same for /device_status. */
ROBOTD_API robotd_status robotd_next_device_status(robotd_client* client, const char* device, int32_t timeout_ms,
                                                   robotd_device_status* status);

/* ---- Closed loop ----------------------------------------------------------------------- */

/* What one tick of a device's loop measured (/<device>/tick_state). A closed-loop session answers
 * it with robotd_session_answer; robotd counts the answer in time when it arrives before the
 * device's next state is measured. */
typedef struct robotd_tick_state {
  char device[ROBOTD_NAME_CAPACITY];
  uint64_t tick;                 /* 1, 2, ... */
  int64_t stamp_ns;              /* the tick's deadline, CLOCK_REALTIME */
  int64_t deadline_steady_ns;    /* the tick's deadline, CLOCK_MONOTONIC */
  int64_t period_ns;             /* the next tick is due at deadline_steady_ns + period_ns */
  int64_t state_ready_steady_ns; /* robotd's loop handed the state over (CLOCK_MONOTONIC) */
  int64_t published_steady_ns;   /* robotd wrote the sample (CLOCK_MONOTONIC) */
  robotd_device_state state;
  size_t joint_count;
  double position[ROBOTD_MAX_JOINTS]; /* rad, in motor id order */
  double velocity[ROBOTD_MAX_JOINTS]; /* rad/s */
  double effort[ROBOTD_MAX_JOINTS];   /* N·m */
  bool has_imu;                       /* the imu_* fields hold this tick's IMU sample */
  double imu_orientation[4];          /* x, y, z, w */
  double imu_angular_velocity[3];     /* rad/s */
  double imu_linear_acceleration[3];  /* m/s² */
} robotd_tick_state;

/* The newest tick state of the session's device newer than the last one this returned, waited for
 * on the calling thread up to timeout_ms (ROBOTD_TIMEOUT). ROBOTD_REFUSED once robotd no longer
 * lists the session in /session_status (it timed out, fell back or was released). */
ROBOTD_API robotd_status robotd_session_next_tick(robotd_session* session, int32_t timeout_ms,
                                                  robotd_tick_state* state);
/* Sends `command` as the answer to `state` (one from robotd_session_next_tick). */
ROBOTD_API robotd_status robotd_session_answer(robotd_session* session, const robotd_tick_state* state,
                                               const robotd_command* command);

/* A control law: fills *command (zeroed before each call) with the answer to *state. The arrays
 * it points command at must stay valid until the law returns. Returns 0 to go on, 1 when this is
 * the last answer (it is sent, then the loop ends). */
typedef int (*robotd_control_law)(const robotd_tick_state* state, robotd_command* command, void* user_data);

typedef struct robotd_control_loop_options {
  int32_t duration_ms;      /* default 0 = no limit; else the loop ends after this long */
  int32_t state_timeout_ms; /* default 200: no new tick for this long ends the loop with ROBOTD_TIMEOUT */
  const volatile int* stop; /* default NULL; else checked before each tick: non-zero (e.g. set by a
                             * signal handler) ends the loop */
} robotd_control_loop_options;

typedef struct robotd_control_loop_report {
  uint64_t ticks_seen;     /* states the law was called with */
  uint64_t ticks_answered; /* answers sent */
  uint64_t ticks_skipped;  /* ticks between two it saw that the loop never saw (too slow a law, or a device
                            * that publishes every Nth tick) */
  uint64_t first_tick;     /* the first and last tick the law was called with (0 = none) */
  uint64_t last_tick;
  bool finished; /* the law returned 1 (else the duration or the stop flag ended the loop) */
} robotd_control_loop_report;

ROBOTD_API robotd_status robotd_control_loop_options_init(robotd_control_loop_options* options);
/* Calls `law` with each new tick state of the session's device and sends its answer, on the
 * calling thread, until the law returns 1, options->duration_ms passes or *options->stop is set
 * (options NULL = the defaults). Fails as robotd_session_next_tick and robotd_session_answer do
 * (ROBOTD_TIMEOUT when ticks stop: robotd_last_error() names the last tick seen), and with
 * ROBOTD_INVALID_ARGUMENT when the law returns something else than 0 or 1, or a malformed
 * command. *report (may be NULL) is filled on success. */
ROBOTD_API robotd_status robotd_session_run_control_loop(robotd_session* session, robotd_control_law law,
                                                         void* user_data, const robotd_control_loop_options* options,
                                                         robotd_control_loop_report* report);
/* "Send aligned" streaming: sleeps until lead_us before the device's next tick is due, then sends
 * `command`. The tick phase comes from the newest tick state if the session reads them, else from
 * /device_status. lead_us < 0 = ROBOTD_DEFAULT_SEND_LEAD_US. */
#define ROBOTD_DEFAULT_SEND_LEAD_US 120 /* robotd::kDefaultSendLead: see docs/clients.md */
ROBOTD_API robotd_status robotd_session_send_aligned(robotd_session* session, const robotd_command* command,
                                                     int32_t lead_us);

/* The session's entry in /session_status as robotd last published it. */
typedef struct robotd_session_info {
  char session_id[ROBOTD_UUID_CAPACITY];
  char node_name[ROBOTD_NAME_CAPACITY];
  char device[ROBOTD_NAME_CAPACITY];
  uint64_t commands_accepted;
  bool closed_loop;                /* the session has answered a tick */
  uint64_t ticks_to_answer;        /* since its first answer */
  uint64_t ticks_answered_in_time; /* applied on the tick after the one answered */
  uint64_t ticks_answered_late;    /* applied on a later tick */
  uint64_t ticks_unanswered;       /* never answered */
  float command_success_rate;      /* in time / to answer over the last 100 ticks to answer, 0..1 */
  float min_command_success_rate;  /* the session's minimum, 0 = none */
  robotd_low_rate_action on_low_success_rate;
  bool success_rate_low; /* below the minimum now */
} robotd_session_info;

/* This session's robotd_session_info, waiting up to timeout_ms for robotd's first
 * /session_status listing it; ROBOTD_REFUSED once robotd no longer lists it. */
ROBOTD_API robotd_status robotd_session_get_info(robotd_session* session, int32_t timeout_ms,
                                                 robotd_session_info* info);

/* ---- Planned moves --------------------------------------------------------------------- */

/* Moves planned in this process (robotd/motion/session_moves.hpp): from the joints robotd
 * measures, on the device's joint limits and the arm model its driver names
 * (robotd_device_info.kinematic_model), streamed through the session at the device's rate until
 * every joint is within 0.1° of its goal (at most 3 s after the plan's end). The call returns
 * when the move has arrived, was stopped, or failed. The timing rules are RBTscript's
 * (docs/rbtscript.md): t overrides v and a; v and a are percent of the leading joint's maximum;
 * with t the polynomial unless told the trapezoid; without any, a conservative trapezoid. */

typedef enum robotd_move_shape ROBOTD_ENUM_BASE {
  ROBOTD_SHAPE_DEFAULT = 0,    /* RBTscript's: the polynomial with t, else the trapezoid */
  ROBOTD_SHAPE_POLYNOMIAL = 1, /* "poly": a quintic, zero speed and acceleration at both ends */
  ROBOTD_SHAPE_TRAPEZOID = 2   /* "trap": with t in thirds (accelerate, cruise, decelerate) */
} robotd_move_shape;

typedef enum robotd_cartesian_path ROBOTD_ENUM_BASE {
  ROBOTD_PATH_JOINT = 0, /* IK of the goal, then a joint move (RBTscript MovePose): the tool's path is not a line */
  ROBOTD_PATH_LINE = 1   /* the tool on a straight line (MoveCart), IK along it; stops before a singularity */
} robotd_cartesian_path;

typedef struct robotd_move_options {
  double duration_s;           /* t: > 0, overrides v and a; default 0 = not given */
  double speed_percent;        /* v: (0, 100] of the leading joint's maximum speed; default 0 = not given */
  double acceleration_percent; /* a: (0, 100] of its maximum acceleration; default 0 = not given */
  robotd_move_shape shape;     /* func; default ROBOTD_SHAPE_DEFAULT */
  const volatile int* stop;    /* default NULL; else non-zero (e.g. set by a signal handler or another thread)
                                * ends the move with the arm held where it is; read every few ms */
} robotd_move_options;

typedef struct robotd_move_report {
  bool stopped; /* the stop flag ended the move: the arm holds where it was measured then */
  uint64_t commands_sent;
  double fraction_done; /* of the planned trajectory, 0..1 */
  size_t joint_count;
  double last_measured[ROBOTD_MAX_JOINTS]; /* rad, where the joints were measured at the end */
  char summary[ROBOTD_TEXT_CAPACITY];      /* e.g. "... arrived within 0.002 rad" */
} robotd_move_report;

/* A pose of the arm model's tool in the device's base frame: m, and the three angles of the arm's
 * own Euler convention (as its vendor writes poses) in rad. */
typedef struct robotd_pose {
  double position_m[3];
  double angles_rad[3];
} robotd_pose;

ROBOTD_API robotd_status robotd_move_options_init(robotd_move_options* options);
/* Moves every joint of the session's device to target_rad (count = the device's joint count).
 * The session must be in POSITION mode on every joint of its device (a request that names no
 * motors); `client` is any client on robotd's domain (it reads the device's limits and state).
 * options NULL = the defaults. ROBOTD_INVALID_ARGUMENT before anything moves for a target of the
 * wrong size or outside the limits, a move too fast for the device, or such a session;
 * ROBOTD_REFUSED on an e-stop, a fault or the end of the session mid-move; ROBOTD_TIMEOUT when
 * the joints do not arrive. *report (may be NULL) is filled on success. */
ROBOTD_API robotd_status robotd_session_move_joints(robotd_client* client, robotd_session* session,
                                                    const double* target_rad, size_t count,
                                                    const robotd_move_options* options, robotd_move_report* report);
/* Moves the tool to *goal along `path`. A line takes only t and the shape. Fails as
 * robotd_session_move_joints does, and with ROBOTD_INVALID_ARGUMENT (nothing moved) when the
 * device names no arm model, the goal is out of reach, or the line meets a singularity or a limit. */
ROBOTD_API robotd_status robotd_session_move_cartesian(robotd_client* client, robotd_session* session,
                                                       const robotd_pose* goal, robotd_cartesian_path path,
                                                       const robotd_move_options* options, robotd_move_report* report);

/* ---- RBTscript -------------------------------------------------------------------------- */

/* Runs an RBTscript program (docs/rbtscript.md) on a device, as robotctl run does: the text is
 * parsed whole; a program without syntax errors is checked whole against the device (a dry run:
 * every move planned on its limits and arm model, every Output and Gripper mapped to its ops);
 * a program without problems then runs, unless only the dry run was asked for, in a POSITION
 * session on every joint of the device, planned here and streamed through robotd. */

typedef enum robotd_rbtscript_end ROBOTD_ENUM_BASE {
  ROBOTD_RBTSCRIPT_NOT_RUN = 0,        /* a dry run, or there were problems: nothing was sent to the device */
  ROBOTD_RBTSCRIPT_END_OF_PROGRAM = 1, /* ran past the last statement */
  ROBOTD_RBTSCRIPT_END = 2,            /* reached End() */
  ROBOTD_RBTSCRIPT_LOOP_LIMIT = 3,     /* reached Loop() after `loops` passes */
  ROBOTD_RBTSCRIPT_STOPPED = 4,        /* the stop flag: the arm holds where it was */
  ROBOTD_RBTSCRIPT_FAILED = 5          /* a statement failed (an e-stop, a refused op): see the outcome's failure */
} robotd_rbtscript_end;

/* Called before each statement of the run (not the dry run), on the calling thread. `statement`
 * is valid only during the call. */
typedef void (*robotd_rbtscript_progress)(size_t line, const char* statement, uint64_t pass, void* user_data);

typedef struct robotd_rbtscript_options {
  const char* device;                     /* NULL or "" = robotd's only device */
  bool dry_run;                           /* true: only check the program; default false */
  uint64_t loops;                         /* default 0 = Loop() runs until stopped; else passes at most */
  const volatile int* stop;               /* default NULL; else non-zero ends the run with the arm held; read
                                           * every few ms */
  robotd_rbtscript_progress on_statement; /* default NULL */
  void* user_data;                        /* passed to on_statement */
  int32_t session_timeout_ms; /* default 2000: robotd damps (or holds) the arm this long after the last command
                               * if this process dies */
} robotd_rbtscript_options;

typedef struct robotd_rbtscript_report robotd_rbtscript_report;

/* One problem: a syntax error or what the dry run found. The strings live as long as the report. */
typedef struct robotd_rbtscript_problem {
  size_t line;             /* 1-based */
  size_t column;           /* 1-based, in bytes */
  const char* statement;   /* the statement as written ("" for a syntax error) */
  const char* message;     /* what is wrong, e.g. "found ')', expected 6 pose values (...)" */
  const char* description; /* all of it on one line: "line 3, column 1: MovePose(...): ..." */
} robotd_rbtscript_problem;

typedef struct robotd_rbtscript_outcome {
  char device[ROBOTD_NAME_CAPACITY]; /* "" when there were syntax errors (no device was asked) */
  bool syntax_errors;                /* the problems are syntax errors: the program was not checked further */
  size_t problem_count;              /* robotd_rbtscript_report_problem 0 .. problem_count - 1 */
  size_t moves_planned;              /* by the dry run, on one pass */
  double pass_seconds;               /* one pass's moves and delays, as planned */
  robotd_rbtscript_end end;
  uint64_t statements_run; /* over all passes */
  uint64_t passes;
  robotd_rbtscript_problem failure; /* end == ROBOTD_RBTSCRIPT_FAILED: the statement and why; else zero */
} robotd_rbtscript_outcome;

ROBOTD_API robotd_status robotd_rbtscript_options_init(robotd_rbtscript_options* options);
/* Parses, checks and (unless a dry run) runs `program_text` (options NULL = the defaults); the
 * call returns when the program has ended, been stopped or failed. Syntax errors, the dry run's
 * problems and a program that fails while running are not errors of the call: *report says what
 * happened (free it with robotd_rbtscript_report_free). Fails (nothing moved) when robotd does
 * not answer, the device is unknown or cannot be planned for, or the session is refused. */
ROBOTD_API robotd_status robotd_run_rbtscript(robotd_client* client, const char* program_text,
                                              const robotd_rbtscript_options* options,
                                              robotd_rbtscript_report** report);
ROBOTD_API robotd_status robotd_rbtscript_report_outcome(const robotd_rbtscript_report* report,
                                                         robotd_rbtscript_outcome* outcome);
/* Problem `index` (< the outcome's problem_count), in line order. */
ROBOTD_API robotd_status robotd_rbtscript_report_problem(const robotd_rbtscript_report* report, size_t index,
                                                         robotd_rbtscript_problem* problem);
/* Frees the report and its strings. NULL is allowed. */
ROBOTD_API void robotd_rbtscript_report_free(robotd_rbtscript_report* report);

/* ---- Subscriptions --------------------------------------------------------------------- */

typedef struct robotd_subscription robotd_subscription;

/* The struct is valid only during the call. */
typedef void (*robotd_joint_state_callback)(const robotd_joint_state* state, void* user_data);
typedef void (*robotd_device_status_callback)(const robotd_device_status* status, void* user_data);

/* Calls `callback` with every sample of every device, on the client's dispatch thread (one
 * thread per client, shared by its subscriptions: a slow callback delays the others). A
 * callback may command sessions and call services, but must not subscribe, unsubscribe or call
 * robotd_next_* on its own client: those fail with ROBOTD_INVALID_ARGUMENT there. */
ROBOTD_API robotd_status robotd_subscribe_joint_states(robotd_client* client, robotd_joint_state_callback callback,
                                                       void* user_data, robotd_subscription** subscription);
ROBOTD_API robotd_status robotd_subscribe_device_status(robotd_client* client, robotd_device_status_callback callback,
                                                        void* user_data, robotd_subscription** subscription);
/* Stops the callbacks and frees the handle; returns after a running callback has finished. NULL
 * is allowed. From a callback of the same client it fails (ROBOTD_INVALID_ARGUMENT) and frees
 * nothing. */
ROBOTD_API robotd_status robotd_unsubscribe(robotd_subscription* subscription);

/* ---- Safety and device operations ------------------------------------------------------ */

/* Engages (latches) the e-stop of `device` (NULL or "" = every device); reason may be NULL. */
ROBOTD_API robotd_status robotd_estop(robotd_client* client, const char* device, const char* reason);
/* robotd_estop that also returns robotd's answer in *report: for each device, whether its loop
 * wrote the e-stop frame to the device and how soon ("reached 'arm' in 0.42 ms"), or that it
 * could not ("NOT confirmed on 'arm' (FAULT: simulated link lost …)": robotd keeps sending it
 * every tick). Allocated by the library: free it with robotd_free_string. */
ROBOTD_API robotd_status robotd_estop_report(robotd_client* client, const char* device, const char* reason,
                                             char** report);
ROBOTD_API robotd_status robotd_reset_estop(robotd_client* client, const char* device);

/* A device operation (a driver op, or robotd's recover / blackbox / loop_timing) with JSON
 * arguments (NULL = "{}"). Finding robotd takes at most the service timeout, the operation up to
 * timeout_ms. On success *result_json is its JSON result, allocated by the library: free it with
 * robotd_free_string. A driver's refusal is ROBOTD_REFUSED with the driver's message. */
ROBOTD_API robotd_status robotd_device_call(robotd_client* client, const char* device, const char* op,
                                            const char* args_json, int32_t timeout_ms, char** result_json);
/* Frees a string the library allocated. NULL is allowed. */
ROBOTD_API void robotd_free_string(char* text);

/* NOLINTEND(modernize-use-using) */

#ifdef __cplusplus
}
#endif

#endif /* ROBOTD_ROBOTD_H */
