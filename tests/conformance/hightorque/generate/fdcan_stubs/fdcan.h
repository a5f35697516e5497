/* Stand-in for CubeMX's fdcan.h: the two CAN-FD ports motor.c maps (port_maping). */
#ifndef ROBOTD_CONFORMANCE_FDCAN_H
#define ROBOTD_CONFORMANCE_FDCAN_H

#include "main.h"

extern FDCAN_HandleTypeDef hfdcan1;
extern FDCAN_HandleTypeDef hfdcan2;

#endif
