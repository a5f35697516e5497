/* Stand-in for the firmware's App/my_fdcan/my_fdcan.h and the HAL receive call: fdcan_send() is
 * the capture point (harness.c records every frame), HAL_FDCAN_GetRxMessage() hands out the
 * crafted replies the harness queued. */
#ifndef ROBOTD_CONFORMANCE_MY_FDCAN_H
#define ROBOTD_CONFORMANCE_MY_FDCAN_H

#include "main.h"

typedef struct {
  uint32_t Identifier;
  uint32_t DataLength; /* the HAL's DLC code: bytes << 16 up to 8, then 9…15 << 16 */
} FDCAN_RxHeaderTypeDef;

#define HAL_OK 0
#define FDCAN_RX_FIFO0 0

void fdcan_send(FDCAN_HandleTypeDef* fdcanHandle, uint32_t id, uint8_t* data, uint16_t size);
uint16_t get_fdcan_data_size(uint32_t dlc);
int HAL_FDCAN_GetRxMessage(FDCAN_HandleTypeDef* fdcanHandle, uint32_t fifo, FDCAN_RxHeaderTypeDef* header,
                           uint8_t* data);

#endif
