/* Runs the HighTorque CAN-FD firmware SDK (motor_fdcan_h730: hightorque_fdcan.c, motor_many.c,
 * motor.c, convert.c) on the host and prints, one JSON object a line, every frame its calls send
 * and every field its reply parser reads from crafted replies. Built and run by generate.py;
 * the vendor's sources are compiled with the stand-ins in fdcan_stubs/, where fdcan_send() is
 * the capture point. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "convert.h"
#include "hightorque_fdcan.h"
#include "motor.h"
#include "motor_many.h"

/* ---- the stand-ins' state ---------------------------------------------------------------- */

int conformance_motor_errors = 0;
FDCAN_HandleTypeDef hfdcan1 = {1};
FDCAN_HandleTypeDef hfdcan2 = {2};

typedef struct {
  uint32_t id;
  uint8_t length;     /* the CAN-FD length the HAL sends (size rounded up) */
  uint8_t data_bytes; /* how many bytes the caller handed over */
  uint8_t data[64];
} captured_frame;

static captured_frame captured[16];
static int captured_count = 0;

static uint8_t fd_length(uint16_t size) {
  static const uint8_t steps[] = {12, 16, 20, 24, 32, 48, 64};
  if (size <= 8) return (uint8_t)size;
  for (unsigned i = 0; i < sizeof steps; ++i) {
    if (size <= steps[i]) return steps[i];
  }
  return 64;
}

/* The current SDK's fdcan_send sets bit 15 (command frame) itself: hightorque_fdcan.h @1ffbf90d
 * and motor_many.c @1910d4d3 say so and pass the id without it. The HAL sends the size rounded
 * up to a CAN-FD length; what follows the caller's buffer is recorded as 0. */
void fdcan_send(FDCAN_HandleTypeDef* fdcanHandle, uint32_t id, uint8_t* data, uint16_t size) {
  (void)fdcanHandle;
  captured_frame* frame = &captured[captured_count++];
  memset(frame, 0, sizeof *frame);
  frame->id = id | 0x8000u;
  frame->length = fd_length(size);
  frame->data_bytes = (uint8_t)size;
  memcpy(frame->data, data, size);
}

static const uint32_t dlc_codes[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};

uint16_t get_fdcan_data_size(uint32_t dlc) { return dlc_codes[(dlc >> 16) & 0xF]; }

static uint32_t dlc_code(uint8_t length) {
  for (uint32_t code = 0; code < 16; ++code) {
    if (dlc_codes[code] >= length) return code << 16;
  }
  return 15u << 16;
}

static struct {
  int pending;
  uint32_t id;
  uint8_t length;
  uint8_t data[64];
} rx;

int HAL_FDCAN_GetRxMessage(FDCAN_HandleTypeDef* fdcanHandle, uint32_t fifo, FDCAN_RxHeaderTypeDef* header,
                           uint8_t* data) {
  (void)fifo;
  if (!rx.pending || fdcanHandle != &hfdcan1) return 1;
  rx.pending = 0;
  header->Identifier = rx.id;
  header->DataLength = dlc_code(rx.length);
  memcpy(data, rx.data, 64);
  return HAL_OK;
}

/* ---- JSON output ------------------------------------------------------------------------- */

static void print_frames(void) {
  printf("\"frames\":[");
  for (int i = 0; i < captured_count; ++i) {
    printf("%s{\"id\":%u,\"data_bytes\":%u,\"data\":\"", i ? "," : "", captured[i].id, captured[i].data_bytes);
    for (int b = 0; b < captured[i].length; ++b) printf("%s%02x", b ? " " : "", captured[i].data[b]);
    printf("\"}");
  }
  printf("]");
  captured_count = 0;
}

/* %.9g round-trips a float exactly. */
static void print_float(const char* name, float value) { printf("\"%s\":%.9g", name, (double)value); }

/* ---- values ------------------------------------------------------------------------------ */

static uint32_t lcg_state = 12345u;
static float uniform(float low, float high) {
  lcg_state = lcg_state * 1664525u + 1013904223u;
  return low + (high - low) * (float)(lcg_state >> 8) / 16777216.0f;
}

#define RANDOM_VALUES 24
#define MAX_VALUES 64

typedef struct {
  int count;
  float values[MAX_VALUES];
} grid;

static grid make_grid(const float* fixed, int fixed_count, float low, float high) {
  grid g;
  g.count = 0;
  for (int i = 0; i < fixed_count; ++i) g.values[g.count++] = fixed[i];
  for (int i = 0; i < RANDOM_VALUES; ++i) g.values[g.count++] = uniform(low, high);
  return g;
}

static grid positions, velocities, torques, gains, accelerations, electricals;

static void make_grids(void) {
  static const float pos[] = {0,   1e-4f,  -1e-4f,     0.1f,       -0.1f,       0.35f,      -0.35f,      0.7f,
                              1,   -1,     1.5707964f, 3.1415927f, -3.1415927f, 6.2831855f, -6.2831855f, 10,
                              -10, 20.58f, -20.58f,    20.6f,      -20.6f,      25,         -25};
  static const float vel[] = {0, 0.35f, 0.7f, -0.7f, 1, -1, 10, -10, 51.4f, -51.4f, 52, -52};
  static const float tqe[] = {0, 0.01f, 0.35f, -0.35f, 0.7f, 1, -1, 3.3f, 100, -100, 327.67f, 328, -328};
  static const float gain[] = {0, 0.1f, 0.35f, 0.7f, 1, 5, 10, 40, 100, 521, 522, 600, -1};
  static const float acc[] = {0, 1, -1, 10, 100, 200, 205.9f, 206, -206};
  static const float electrical[] = {0, 0.35f, 1, -1, 12, 24, 3276.7f, 4000, -4000};
  positions = make_grid(pos, sizeof pos / sizeof *pos, -22, 22);
  velocities = make_grid(vel, sizeof vel / sizeof *vel, -55, 55);
  torques = make_grid(tqe, sizeof tqe / sizeof *tqe, -330, 330);
  gains = make_grid(gain, sizeof gain / sizeof *gain, 0, 550);
  accelerations = make_grid(acc, sizeof acc / sizeof *acc, -210, 210);
  electricals = make_grid(electrical, sizeof electrical / sizeof *electrical, -3300, 3300);
}

static float pick(const grid* g, int i) { return g->values[i % g->count]; }

/* ---- single-motor frames: convert.c's conversion, then the builder, as motor_many.c does ---- */

typedef enum { W_INT16, W_INT32, W_FLOAT } width_t;
static const char* width_names[] = {"int16", "int32", "float"};
static const data_type_t width_types[] = {TINT16, TINT32, TFLOAT};

static void begin(const char* group, const char* call, width_t width, int motor) {
  printf("{\"group\":\"%s\",\"call\":\"%s\",\"width\":\"%s\",\"motor\":%d,\"args\":{", group, call, width_names[width],
         motor);
}

static void end(void) {
  printf("},");
  print_frames();
  printf("}\n");
}

/* The vendor passes the float results of convert.c to int16_t / int32_t parameters: the implicit
 * conversion is part of what runs. */
#define TURNS_OF(x) conv_to_turns((x), MOTOR_DATA_TYPE_FLAG)
#define GAIN_OF(x) conv_from_turns((x), MOTOR_DATA_TYPE_FLAG)

static void single_mit(width_t w, int motor, float p, float v, float t, float kp, float kd) {
  const data_type_t type = width_types[w];
  begin("single frames", "mit", w, motor);
  print_float("position", p), printf(","), print_float("velocity", v), printf(","), print_float("torque", t);
  printf(","), print_float("kp", kp), printf(","), print_float("kd", kd);
  const float rp = pos_float2int(TURNS_OF(p), type), rv = vel_float2int(TURNS_OF(v), type);
  const float rt = tqe_float2int(t, type), rkp = pid_float2int(GAIN_OF(kp), type),
              rkd = pid_float2int(GAIN_OF(kd), type);
  if (w == W_INT16) hightorque_pos_vel_tqe_kp_kd_int16(&hfdcan1, motor, rp, rv, rt, rkp, rkd);
  if (w == W_INT32) hightorque_pos_vel_tqe_kp_kd_int32(&hfdcan1, motor, rp, rv, rt, rkp, rkd);
  if (w == W_FLOAT) hightorque_pos_vel_tqe_kp_kd_float(&hfdcan1, motor, rp, rv, rt, rkp, rkd);
  end();
}

static void single_one(width_t w, int motor, const char* call, float x) {
  const data_type_t type = width_types[w];
  begin("single frames", call, w, motor);
  if (strcmp(call, "position") == 0) {
    print_float("position", x);
    const float raw = pos_float2int(TURNS_OF(x), type);
    if (w == W_INT16) hightorque_pos_int16(&hfdcan1, motor, raw);
    if (w == W_INT32) hightorque_pos_int32(&hfdcan1, motor, raw);
    if (w == W_FLOAT) hightorque_pos_float(&hfdcan1, motor, raw);
  } else if (strcmp(call, "velocity") == 0) {
    print_float("velocity", x);
    const float raw = vel_float2int(TURNS_OF(x), type);
    if (w == W_INT16) hightorque_vel_int16(&hfdcan1, motor, raw);
    if (w == W_INT32) hightorque_vel_int32(&hfdcan1, motor, raw);
    if (w == W_FLOAT) hightorque_vel_float(&hfdcan1, motor, raw);
  } else if (strcmp(call, "torque") == 0) {
    print_float("torque", x);
    const float raw = tqe_float2int(x, type);
    if (w == W_INT16) hightorque_torque_int16(&hfdcan1, motor, raw);
    if (w == W_INT32) hightorque_torque_int32(&hfdcan1, motor, raw);
    if (w == W_FLOAT) hightorque_torque_float(&hfdcan1, motor, raw);
  } else if (strcmp(call, "voltage") == 0) {
    print_float("voltage_q", x);
    const float d = vol_float2int(0, type), q = vol_float2int(x, type);
    if (w == W_INT16) hightorque_dq_volt_int16(&hfdcan1, motor, d, q);
    if (w == W_INT32) hightorque_dq_volt_int32(&hfdcan1, motor, d, q);
    if (w == W_FLOAT) hightorque_dq_volt_float(&hfdcan1, motor, d, q);
  } else if (strcmp(call, "current") == 0) {
    print_float("current_q", x);
    const float d = cur_float2int(0, type), q = cur_float2int(x, type);
    if (w == W_INT16) hightorque_dq_current_int16(&hfdcan1, motor, d, q);
    if (w == W_INT32) hightorque_dq_current_int32(&hfdcan1, motor, d, q);
    if (w == W_FLOAT) hightorque_dq_current_float(&hfdcan1, motor, d, q);
  }
  end();
}

static void single_three(width_t w, int motor, const char* call, float a, float b, float c) {
  const data_type_t type = width_types[w];
  begin("single frames", call, w, motor);
  if (strcmp(call, "pos_vel_tqe") == 0) {
    print_float("position", a), printf(","), print_float("velocity", b), printf(","), print_float("torque", c);
    const float rp = pos_float2int(TURNS_OF(a), type), rv = vel_float2int(TURNS_OF(b), type);
    const float rt = tqe_float2int(c, type);
    if (w == W_INT16) hightorque_pos_vel_tqe_int16(&hfdcan1, motor, rp, rv, rt);
    if (w == W_INT32) hightorque_pos_vel_tqe_int32(&hfdcan1, motor, rp, rv, rt);
    if (w == W_FLOAT) hightorque_pos_vel_tqe_float(&hfdcan1, motor, rp, rv, rt);
  } else if (strcmp(call, "pos_vel_acc") == 0) {
    print_float("position", a), printf(","), print_float("velocity", b), printf(","), print_float("acceleration", c);
    const float rp = pos_float2int(TURNS_OF(a), type), rv = vel_float2int(TURNS_OF(b), type);
    const float ra = acc_float2int(TURNS_OF(c), type);
    if (w == W_INT16) hightorque_pos_vel_acc_int16(&hfdcan1, motor, rp, rv, ra);
    if (w == W_INT32) hightorque_pos_vel_acc_int32(&hfdcan1, motor, rp, rv, ra);
    if (w == W_FLOAT) hightorque_pos_vel_acc_float(&hfdcan1, motor, rp, rv, ra);
  } else if (strcmp(call, "vel_acc") == 0) {
    print_float("velocity", a), printf(","), print_float("acceleration", b);
    const float rv = vel_float2int(TURNS_OF(a), type), ra = acc_float2int(TURNS_OF(b), type);
    if (w == W_INT16) hightorque_vel_acc_int16(&hfdcan1, motor, rv, ra);
    if (w == W_INT32) hightorque_vel_acc_int32(&hfdcan1, motor, rv, ra);
    if (w == W_FLOAT) hightorque_vel_acc_float(&hfdcan1, motor, rv, ra);
  }
  end();
}

static void single_bare(width_t w, int motor, const char* call) {
  begin("single frames", call, w, motor);
  if (strcmp(call, "stop") == 0) {
    if (w == W_INT16) hightorque_stop_int16(&hfdcan1, motor);
    if (w == W_INT32) hightorque_stop_int32(&hfdcan1, motor);
    if (w == W_FLOAT) hightorque_stop_float(&hfdcan1, motor);
  } else if (strcmp(call, "brake") == 0) {
    if (w == W_INT16) hightorque_brake_int16(&hfdcan1, motor);
    if (w == W_INT32) hightorque_brake_int32(&hfdcan1, motor);
    if (w == W_FLOAT) hightorque_brake_float(&hfdcan1, motor);
  } else if (strcmp(call, "query") == 0) {
    if (w == W_INT16) hightorque_request_state_int16(&hfdcan1, motor);
    if (w == W_INT32) hightorque_request_state_int32(&hfdcan1, motor);
    if (w == W_FLOAT) hightorque_request_state_float(&hfdcan1, motor);
  }
  end();
}

static void single_frames(void) {
  for (int w = W_INT16; w <= W_FLOAT; ++w) {
    const int n = positions.count;
    for (int i = 0; i < n; ++i) {
      single_mit(w, 1 + i % 30, pick(&positions, i), pick(&velocities, i), pick(&torques, i), pick(&gains, i),
                 pick(&gains, i + 7));
    }
    for (int i = 0; i < positions.count; ++i) single_one(w, 3, "position", pick(&positions, i));
    for (int i = 0; i < velocities.count; ++i) single_one(w, 4, "velocity", pick(&velocities, i));
    for (int i = 0; i < torques.count; ++i) single_one(w, 5, "torque", pick(&torques, i));
    for (int i = 0; i < electricals.count; ++i) single_one(w, 6, "voltage", pick(&electricals, i));
    for (int i = 0; i < electricals.count; ++i) single_one(w, 7, "current", pick(&electricals, i));
    for (int i = 0; i < 12; ++i) {
      single_three(w, 8, "pos_vel_tqe", pick(&positions, i * 3), pick(&velocities, i * 5), pick(&torques, i * 2));
      single_three(w, 9, "pos_vel_acc", pick(&positions, i * 5), pick(&velocities, i * 3), pick(&accelerations, i));
      single_three(w, 10, "vel_acc", pick(&velocities, i * 7), pick(&accelerations, i * 3), 0);
    }
    single_bare(w, 11, "stop");
    single_bare(w, 12, "brake");
    single_bare(w, 13, "query");
  }
}

/* ---- system commands --------------------------------------------------------------------- */

static void system_frame(const char* call, int motor, long argument) {
  printf("{\"group\":\"system commands\",\"call\":\"%s\",\"motor\":%d,\"args\":{", call, motor);
  if (strcmp(call, "change_id") == 0) {
    printf("\"new_id\":%ld", argument);
    hightorque_id(&hfdcan1, (uint8_t)motor, (uint8_t)argument);
  } else if (strcmp(call, "status_push") == 0) {
    printf("\"period_us\":%ld", argument);
    hightorque_request_timed_return(&hfdcan1, motor, (uint32_t)argument);
  } else if (strcmp(call, "set_zero") == 0) {
    hightorque_pos_rezero(&hfdcan1, motor);
  } else if (strcmp(call, "save_to_flash") == 0) {
    hightorque_conf_write(&hfdcan1, motor);
  } else if (strcmp(call, "soft_reboot") == 0) {
    hightorque_reset(&hfdcan1, motor);
  } else if (strcmp(call, "firmware_version") == 0) {
    hightorque_request_fw_version(&hfdcan1, motor);
  } else if (strcmp(call, "hardware_version") == 0) {
    hightorque_request_hw_version(&hfdcan1, motor);
  } else if (strcmp(call, "model") == 0) {
    hightorque_request_model(&hfdcan1, motor);
  }
  printf("},\"motor_errors\":%d,", conformance_motor_errors);
  conformance_motor_errors = 0;
  print_frames();
  printf("}\n");
}

static void system_commands(void) {
  static const int motors[] = {1, 5, 30};
  static const char* plain[] = {"set_zero",         "save_to_flash",    "soft_reboot",
                                "firmware_version", "hardware_version", "model"};
  for (unsigned m = 0; m < sizeof motors / sizeof *motors; ++m) {
    for (unsigned c = 0; c < sizeof plain / sizeof *plain; ++c) system_frame(plain[c], motors[m], 0);
  }
  static const long periods[] = {0, 100, 1000, 123456, 4000000000L};
  for (unsigned i = 0; i < sizeof periods / sizeof *periods; ++i) system_frame("status_push", 2, periods[i]);
  static const int changes[][2] = {{1, 2},   {3, 30},  {30, 1}, {1, 0},  {1, 31},
                                   {1, 127}, {1, 200}, {0, 5},  {31, 5}, {127, 3}};
  for (unsigned i = 0; i < sizeof changes / sizeof *changes; ++i)
    system_frame("change_id", changes[i][0], changes[i][1]);
}

/* ---- one-to-many block frames (motor_many.c) --------------------------------------------- */

typedef struct {
  int motor;
  float a, b, c, d, e;
} slot_args;

static void block_vector(const char* call, const slot_args* slots, int count, motor_query_t query) {
  /* Every vector starts from a fresh buffer: a mode change sets every slot to "no value". */
  if (strcmp(call, "stop") == 0) {
    motor_many_brake(PORT1, 1, 0);
  } else {
    motor_many_stop(PORT1, 1, 0);
  }
  printf("{\"group\":\"block frames\",\"call\":\"%s\",\"motors\":%d,\"query\":%d,\"slots\":[", call, MANY_MOTOR_SIZE,
         (int)query);
  for (int i = 0; i < count; ++i) {
    const slot_args* s = &slots[i];
    printf("%s{\"motor\":%d,", i ? "," : "", s->motor);
    if (strcmp(call, "mit") == 0) {
      print_float("position", s->a), printf(","), print_float("velocity", s->b), printf(",");
      print_float("torque", s->c), printf(","), print_float("kp", s->d), printf(","), print_float("kd", s->e);
      motor_many_pos_vel_tqe_kp_kd(PORT1, s->motor, s->a, s->b, s->c, s->d, s->e);
    } else if (strcmp(call, "position") == 0) {
      print_float("position", s->a);
      motor_many_pos(PORT1, s->motor, s->a);
    } else if (strcmp(call, "velocity") == 0) {
      print_float("velocity", s->a);
      motor_many_vel(PORT1, s->motor, s->a);
    } else if (strcmp(call, "torque") == 0) {
      print_float("torque", s->a);
      motor_many_tqe(PORT1, s->motor, s->a);
    } else if (strcmp(call, "voltage") == 0) {
      print_float("voltage_q", s->a);
      motor_many_dq_volt(PORT1, s->motor, s->a);
    } else if (strcmp(call, "current") == 0) {
      print_float("current_q", s->a);
      motor_many_dq_current(PORT1, s->motor, s->a);
    } else if (strcmp(call, "vel_acc") == 0) {
      print_float("velocity", s->a), printf(","), print_float("acceleration", s->b);
      motor_many_vel_acc(PORT1, s->motor, s->a, s->b);
    } else if (strcmp(call, "pos_vel_tqe") == 0) {
      print_float("position", s->a), printf(","), print_float("velocity", s->b), printf(",");
      print_float("torque", s->c);
      motor_many_pos_vel_MAXtqe(PORT1, s->motor, s->a, s->b, s->c);
    } else if (strcmp(call, "pos_vel_acc") == 0) {
      print_float("position", s->a), printf(","), print_float("velocity", s->b), printf(",");
      print_float("acceleration", s->c);
      motor_many_pos_vel_acc(PORT1, s->motor, s->a, s->b, s->c);
    } else if (strcmp(call, "stop") == 0) {
      printf("\"flag\":1");
      motor_many_stop(PORT1, s->motor, 1);
    } else if (strcmp(call, "brake") == 0) {
      printf("\"flag\":1");
      motor_many_brake(PORT1, s->motor, 1);
    } else if (strcmp(call, "soft_reboot") == 0) {
      printf("\"flag\":1");
      motor_many_reset(PORT1, s->motor, 1);
    } else if (strcmp(call, "set_zero") == 0) {
      printf("\"flag\":1");
      motor_many_rezero(PORT1, s->motor, 1);
    }
    printf("}");
  }
  printf("],");
  motor_many_send(PORT1, query);
  print_frames();
  printf("}\n");
}

static slot_args slot_for(int motor, int i) {
  slot_args s = {motor,
                 pick(&positions, i),
                 pick(&velocities, i + 3),
                 pick(&torques, i + 5),
                 pick(&gains, i + 1),
                 pick(&gains, i + 4)};
  return s;
}

static void block_frames(void) {
  static const char* calls[] = {"mit",         "position",    "velocity", "torque", "voltage",     "current", "vel_acc",
                                "pos_vel_tqe", "pos_vel_acc", "stop",     "brake",  "soft_reboot", "set_zero"};
  static const motor_query_t queries[] = {QUERY_MODE_FLAUT_TEMP_POS_VEL_TQE, QUERY_MODE_FLAUT_POS_VEL_TQE,
                                          QUERY_FLAUT_POS_VEL_TQE};
  slot_args slots[MANY_MOTOR_SIZE];
  for (unsigned c = 0; c < sizeof calls / sizeof *calls; ++c) {
    const motor_query_t query = queries[c % 3];
    slots[0] = slot_for(1, (int)c);
    block_vector(calls[c], slots, 1, query);
    slots[0] = slot_for(MANY_MOTOR_SIZE, (int)c + 2);
    block_vector(calls[c], slots, 1, query);
    int count = 0;
    for (int motor = 2; motor <= MANY_MOTOR_SIZE; motor += 3) slots[count++] = slot_for(motor, (int)c * 7 + motor);
    block_vector(calls[c], slots, count, query);
    for (int motor = 1; motor <= MANY_MOTOR_SIZE; ++motor) slots[motor - 1] = slot_for(motor, (int)c * 11 + motor);
    block_vector(calls[c], slots, MANY_MOTOR_SIZE, query);
  }
  /* The electrical grid's values also go through the one-field blocks. */
  for (int i = 0; i < electricals.count; ++i) {
    slots[0].motor = 1 + i % MANY_MOTOR_SIZE;
    slots[0].a = pick(&electricals, i);
    block_vector(i % 2 ? "current" : "voltage", slots, 1, QUERY_MODE_FLAUT_TEMP_POS_VEL_TQE);
  }
}

/* ---- replies: crafted frames through motor_process_state_all() --------------------------- */

static void reply_vector(uint32_t id, const uint8_t* data, uint8_t length) {
  const uint8_t motor = (id >> 8) & 0x7F;
  /* Sentinels show which fields the parser wrote. */
  const int known = motor >= 1 && motor <= MOTOR_MAX_NUM;
  p_motor_state_s state = known ? motor_get_state(PORT1, motor) : NULL;
  if (state) {
    memset(state, 0, sizeof *state);
    state->mode = (motor_mode_t)0xEE;
    state->fault = 0xEE;
    state->position = state->velocity = state->torque = 12345.0f;
    state->temp = 99;
  }
  rx.pending = 1;
  rx.id = id;
  rx.length = length;
  memset(rx.data, 0, sizeof rx.data);
  memcpy(rx.data, data, length);
  motor_process_state_all();
  printf("{\"group\":\"replies\",\"id\":%u,\"data\":\"", id);
  for (int b = 0; b < length; ++b) printf("%s%02x", b ? " " : "", data[b]);
  printf("\",\"vendor\":{\"parsed_motor\":%s", known ? "true" : "false");
  if (state) {
    printf(",\"mode\":%d,\"fault\":%d,", (int)state->mode, state->fault);
    print_float("position", state->position), printf(","), print_float("velocity", state->velocity), printf(",");
    print_float("torque", state->torque);
    printf(",\"temperature\":%d,\"ack\":%d,\"version\":[%d,%d,%d],\"model\":\"%s\"", state->temp, state->ack,
           state->version.major, state->version.minor, state->version.patch, state->model);
  }
  printf("}}\n");
}

static void put16(uint8_t* p, int16_t v) { memcpy(p, &v, 2); }
static void put32(uint8_t* p, int32_t v) { memcpy(p, &v, 4); }
static void putf(uint8_t* p, float v) { memcpy(p, &v, 4); }

static void state_replies(uint8_t code, int motor) {
  static const int16_t raws16[][4] = {{0, 0, 0, 0},
                                      {1, -1, 2, 250},
                                      {10000, 4000, 100, 355},
                                      {-10000, -4000, -100, -5},
                                      {32767, 32767, 32767, 1000},
                                      {-32767, -32767, -32767, 0},
                                      {(int16_t)0x8000, (int16_t)0x8000, (int16_t)0x8000, (int16_t)0x8000},
                                      {1234, -5678, 910, 421}};
  static const int32_t raws32[][4] = {{0, 0, 0, 0},
                                      {100000, 100000, 1000, 35500},
                                      {-123456, 654321, -2500, 42000},
                                      {(int32_t)0x80000000, (int32_t)0x80000000, (int32_t)0x80000000, 0},
                                      {2147483647, -2147483647, 7, 1}};
  static const float rawsf[][4] = {{0, 0, 0, 0}, {0.5f, -1.25f, 3.5f, 35.5f}, {-2.75f, 10, -0.01f, 60}};
  const uint8_t temp_bytes = code == 0x0C ? 1 : 0;
  const uint8_t header = code == 0x0E ? 2 : 3;
  uint8_t data[64];
  for (unsigned i = 0; i < sizeof raws16 / sizeof *raws16; ++i) {
    memset(data, 0, sizeof data);
    data[0] = code;
    data[1] = code == 0x0E ? 0x07 : 0x21;
    if (code != 0x0E) data[2] = (uint8_t)(i * 3);
    uint8_t* at = data + header;
    if (temp_bytes) put16(at, raws16[i][3]), at += 2;
    put16(at, raws16[i][0]), put16(at + 2, raws16[i][1]), put16(at + 4, raws16[i][2]);
    reply_vector((1u << 16) | ((uint32_t)motor << 8), data, (uint8_t)fd_length((uint16_t)(at + 6 - data)));
  }
  for (unsigned i = 0; i < sizeof raws32 / sizeof *raws32; ++i) {
    memset(data, 0, sizeof data);
    data[0] = code;
    data[1] = code == 0x0E ? 0x14 : 0x1D;
    if (code != 0x0E) data[2] = 0;
    uint8_t* at = data + header;
    if (temp_bytes) put32(at, raws32[i][3]), at += 4;
    put32(at, raws32[i][0]), put32(at + 4, raws32[i][1]), put32(at + 8, raws32[i][2]);
    reply_vector((2u << 16) | ((uint32_t)motor << 8), data, (uint8_t)fd_length((uint16_t)(at + 12 - data)));
  }
  for (unsigned i = 0; i < sizeof rawsf / sizeof *rawsf; ++i) {
    memset(data, 0, sizeof data);
    data[0] = code;
    data[1] = code == 0x0E ? 0 : 0x01;
    uint8_t* at = data + header;
    if (temp_bytes) putf(at, rawsf[i][3]), at += 4;
    putf(at, rawsf[i][0]), putf(at + 4, rawsf[i][1]), putf(at + 8, rawsf[i][2]);
    reply_vector((3u << 16) | ((uint32_t)motor << 8), data, (uint8_t)fd_length((uint16_t)(at + 12 - data)));
  }
}

static void replies(void) {
  static const uint8_t codes[] = {0x0B, 0x0C, 0x0E};
  for (unsigned c = 0; c < sizeof codes; ++c) state_replies(codes[c], c == 0 ? 1 : (c == 1 ? 17 : MOTOR_MAX_NUM));
  state_replies(0x0B, MOTOR_MAX_NUM + 1); /* beyond the motors the SDK keeps */

  const uint8_t version[] = {0x04, 0x06, 0x04, 0x04};
  reply_vector((1u << 16) | (2u << 8), version, sizeof version);
  const uint8_t old_version[] = {0x04, 0x09, 0x03, 0x03};
  reply_vector((1u << 16) | (3u << 8), old_version, sizeof old_version);
  const uint8_t hardware[] = {0x05, 0x01, 0x02, 0x03};
  reply_vector((1u << 16) | (3u << 8), hardware, sizeof hardware);
  const uint8_t model[] = {0x07, 0x07, '5', '0', '4', '7', '_', '3', '6', 0};
  reply_vector((1u << 16) | (4u << 8), model, 12);
  const uint8_t long_model[] = {0x07, 0x10, 'P', 'I', '_', 'P', 'L', 'U', 'S',
                                '_',  '6',  '0', '5', '6', '_', '3', '6', 'X'};
  reply_vector((1u << 16) | (4u << 8), long_model, 20);
  const uint8_t ok[] = {0x03, 0x00};
  reply_vector((1u << 16) | (5u << 8), ok, sizeof ok);
  const uint8_t refused[] = {0x03, 0x05};
  reply_vector((1u << 16) | (5u << 8), refused, sizeof refused);
  const uint8_t counter[] = {0x0A, 0x21, 0x00, 0x34, 0x12};
  reply_vector((1u << 16) | (6u << 8), counter, sizeof counter);
  /* A command frame (bit 15) on the bus is not a reply. */
  const uint8_t command[] = {0x0B, 0x21, 0x00, 0x10, 0x27, 0, 0, 0, 0};
  reply_vector((1u << 16) | 0x8000u | (7u << 8), command, 12);
}

int main(int argc, char** argv) {
  const char* part = argc > 1 ? argv[1] : "all";
  make_grids();
  if (strcmp(part, "all") == 0 || strcmp(part, "single") == 0) {
    single_frames();
    system_commands();
    replies();
  }
  if (strcmp(part, "all") == 0 || strcmp(part, "block") == 0) block_frames();
  return 0;
}
