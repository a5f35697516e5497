/* Declarations for the firmware's convert.c (src/convert/convert.c @e5469383). The convert.h of
 * that version (with TINT16_NOHDR) is not in the public store, so these are ours, written from
 * what convert.c, hightorque_fdcan.h and motor.c of those commits use:
 * - data_type_t in CAN id bits 17:16 (hightorque_fdcan.h: TINT16_NOHDR 00, TINT16 01, TINT32 10,
 *   TFLOAT 11; motor.c: "TINT16_NOHDR=0, TINT16=1, TINT32=2, TFLOAT=3");
 * - MY_2PI, BROADCAST_ID and the NAN_* markers as in the stored convert.h @1029bdcf;
 * - MOTOR_DATA_TYPE_FLAG = RADIAN_2PI: the SDK's radian configuration (its default is TURNS),
 *   because robotd's commands are in radians; MOTOR_ERR() counts instead of blinking a LED. */
#ifndef _CONVERT_H
#define _CONVERT_H

#include <math.h>

#include "main.h"

#ifndef MOTOR_DATA_TYPE_FLAG
#define MOTOR_DATA_TYPE_FLAG RADIAN_2PI
#endif
#define BROADCAST_ID 0x7F

extern int conformance_motor_errors;
static inline void MOTOR_ERR(void) { ++conformance_motor_errors; }

#define MY_2PI (6.28318530717f)
#define MY_PI (3.14159265358f)

#define NAN_FLOAT NAN
#define NAN_INT32 0x80000000
#define NAN_INT16 0x8000
#define NAN_INT8 0x80

typedef enum { RADIAN_2PI = 0, ANGLE_360, TURNS } pos_vel_type_t;
typedef enum { TINT16_NOHDR = 0, TINT16 = 1, TINT32 = 2, TFLOAT = 3 } data_type_t;

float conv_to_turns(const float in_data, const pos_vel_type_t type);
float conv_from_turns(const float in_data, const pos_vel_type_t type);
float cur_float2int(const float in_data, const data_type_t type);
float vol_float2int(const float in_data, const data_type_t type);
float pos_float2int(const float in_data, const data_type_t type);
float vel_float2int(const float in_data, const data_type_t type);
float tqe_float2int(const float in_data, const data_type_t type);
float acc_float2int(const float in_data, const data_type_t type);
float pid_float2int(const float in_data, const data_type_t type);
float cur_int2float(const float in_data, const data_type_t type);
float vol_int2float(const float in_data, const data_type_t type);
float pos_int2float(const float in_data, const data_type_t type);
float vel_int2float(const float in_data, const data_type_t type);
float tqe_int2float(const float in_data, const data_type_t type);
float acc_int2float(const float in_data, const data_type_t type);
float pid_int2float(const float in_data, const data_type_t type);
float temp_int2float(const float in_data, const data_type_t type);
void my_memcpy(void* p1, const void* p2, const int16_t len);

#endif
