/* Stand-in for the STM32 CubeMX main.h the HighTorque motor_fdcan_h730 sources include: plain
 * C types and the few symbols of the firmware build that are not in the sources we compile. */
#ifndef ROBOTD_CONFORMANCE_MAIN_H
#define ROBOTD_CONFORMANCE_MAIN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* Keil/ARM-GCC spelling of a packed enum in motor.h and motor_many.h. */
#define __packed __attribute__((packed))

typedef struct {
  int Instance; /* tells the two ports apart (motor.c compares ->Instance) */
} FDCAN_HandleTypeDef;

/* hightorque_id() checks ids against MOTOR_ID_MIN, defined in a header of the firmware project
 * that is not stored with these sources; 1 is the lowest motor id of the protocol. */
#ifndef MOTOR_ID_MIN
#define MOTOR_ID_MIN 1
#endif

/* motor.c @1910d4d3 names the 0x0E reply FLAUT_POS_VEL_TQE; its motor.h calls the same code
 * QUERY_FLAUT_POS_VEL_TQE = 0x0E and no stored header defines the short name. */
#define FLAUT_POS_VEL_TQE 0x0E

#endif
