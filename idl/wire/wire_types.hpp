// Wire<T> maps each robotd C++ message to its idlc-generated C type and topic descriptor.
// to_c fills a C sample whose buffers point into `in` (and `arena`); from_c copies out.
#pragma once

#include <dds/dds.h>

#include "robotd/messages.hpp"
#include "robotd_msgs.h"
#include "wire/c_arena.hpp"

namespace robotd::wire {

template <class T>
struct Wire;

#define ROBOTD_WIRE_TYPE(CppType, CType)                        \
  template <>                                                   \
  struct Wire<CppType> {                                        \
    using C = CType;                                            \
    static const dds_topic_descriptor_t& descriptor();          \
    static void to_c(const CppType& in, C& out, CArena& arena); \
    static CppType from_c(const C& in);                         \
  }

ROBOTD_WIRE_TYPE(ControlCommand, robotd_msgs_msg_dds__ControlCommand_);
ROBOTD_WIRE_TYPE(JointState, sensor_msgs_msg_dds__JointState_);
ROBOTD_WIRE_TYPE(TickState, robotd_msgs_msg_dds__TickState_);
ROBOTD_WIRE_TYPE(Imu, sensor_msgs_msg_dds__Imu_);
ROBOTD_WIRE_TYPE(PoseStamped, geometry_msgs_msg_dds__PoseStamped_);
ROBOTD_WIRE_TYPE(Vector3, geometry_msgs_msg_dds__Vector3_);
ROBOTD_WIRE_TYPE(Quaternion, geometry_msgs_msg_dds__Quaternion_);
ROBOTD_WIRE_TYPE(Joy, robotd_msgs_msg_dds__Joy_);
ROBOTD_WIRE_TYPE(PolicyData, robotd_msgs_msg_dds__PolicyData_);
ROBOTD_WIRE_TYPE(SessionStatus, robotd_msgs_msg_dds__SessionStatus_);
ROBOTD_WIRE_TYPE(DeviceStatus, robotd_msgs_msg_dds__DeviceStatus_);
ROBOTD_WIRE_TYPE(RequestControlRequest, robotd_msgs_srv_dds__RequestControl_Request_);
ROBOTD_WIRE_TYPE(RequestControlResponse, robotd_msgs_srv_dds__RequestControl_Response_);
ROBOTD_WIRE_TYPE(ReleaseControlRequest, robotd_msgs_srv_dds__ReleaseControl_Request_);
ROBOTD_WIRE_TYPE(ReleaseControlResponse, robotd_msgs_srv_dds__ReleaseControl_Response_);
ROBOTD_WIRE_TYPE(GetAvailableMotorsRequest, robotd_msgs_srv_dds__GetAvailableMotors_Request_);
ROBOTD_WIRE_TYPE(GetAvailableMotorsResponse, robotd_msgs_srv_dds__GetAvailableMotors_Response_);
ROBOTD_WIRE_TYPE(ResetZeroRequest, robotd_msgs_srv_dds__ResetZero_Request_);
ROBOTD_WIRE_TYPE(ResetZeroResponse, robotd_msgs_srv_dds__ResetZero_Response_);
ROBOTD_WIRE_TYPE(EstopRequest, robotd_msgs_srv_dds__Estop_Request_);
ROBOTD_WIRE_TYPE(EstopResponse, robotd_msgs_srv_dds__Estop_Response_);
ROBOTD_WIRE_TYPE(ListDevicesRequest, robotd_msgs_srv_dds__ListDevices_Request_);
ROBOTD_WIRE_TYPE(ListDevicesResponse, robotd_msgs_srv_dds__ListDevices_Response_);
ROBOTD_WIRE_TYPE(DeviceCallRequest, robotd_msgs_srv_dds__DeviceCall_Request_);
ROBOTD_WIRE_TYPE(DeviceCallResponse, robotd_msgs_srv_dds__DeviceCall_Response_);

#undef ROBOTD_WIRE_TYPE

}  // namespace robotd::wire
