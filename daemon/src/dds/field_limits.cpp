#include "dds/field_limits.hpp"

#include <vector>

#include "robotd/driver/types.hpp"
#include "robotd/limits.hpp"

namespace robotd::dds {
namespace {

static_assert(limits::kJoints == driver::kMaxJoints, "a list of motors holds at most every joint of a device");

// Checks fields in order and keeps the first one beyond its limit.
class Check {
 public:
  Check& text(const char* field, const std::string& value, std::size_t limit) {
    if (!found_ && value.size() > limit) found_ = Oversize{field, value.size(), limit, false};
    return *this;
  }
  template <class T>
  Check& list(const char* field, const std::vector<T>& values, std::size_t limit = limits::kJoints) {
    if (!found_ && values.size() > limit) found_ = Oversize{field, values.size(), limit, true};
    return *this;
  }
  std::optional<Oversize> result() const { return found_; }

 private:
  std::optional<Oversize> found_;
};

// At most `limit` bytes, never ending inside a UTF-8 character.
void cut_text(std::string& text, std::size_t limit) {
  if (text.size() <= limit) return;
  std::size_t end = limit;
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0U) == 0x80U) --end;
  text.resize(end);
}

}  // namespace

std::string Oversize::describe() const {
  const char* unit = is_list ? " entries" : " bytes";
  return std::string(field) + " is " + std::to_string(length) + unit + " long; the limit is " + std::to_string(limit) +
         unit;
}

std::optional<Oversize> find_oversize(const ControlCommand& command) {
  return Check()
      .text("uuid", command.uuid, limits::kUuidBytes)
      .text("device", command.device, limits::kDeviceNameBytes)
      .text("header.frame_id", command.header.frame_id, limits::kFrameIdBytes)
      .list("motor_ids", command.motor_ids)
      .list("positions", command.positions)
      .list("velocities", command.velocities)
      .list("kp", command.kp)
      .list("kd", command.kd)
      .list("torques", command.torques)
      .result();
}

std::optional<Oversize> find_oversize(const RequestControlRequest& request) {
  return Check()
      .text("node_name", request.node_name, limits::kNodeNameBytes)
      .text("device", request.device, limits::kDeviceNameBytes)
      .text("policy_name", request.policy_name, limits::kPolicyNameBytes)
      .text("policy_file_name", request.policy_file_name, limits::kPolicyFileNameBytes)
      .list("motor_ids", request.motor_ids)
      .list("default_kp", request.default_kp)
      .list("default_kd", request.default_kd)
      .result();
}

std::optional<Oversize> find_oversize(const ReleaseControlRequest& request) {
  return Check()
      .text("node_name", request.node_name, limits::kNodeNameBytes)
      .text("uuid", request.uuid, limits::kUuidBytes)
      .result();
}

std::optional<Oversize> find_oversize(const GetAvailableMotorsRequest& request) {
  return Check()
      .text("node_name", request.node_name, limits::kNodeNameBytes)
      .text("device", request.device, limits::kDeviceNameBytes)
      .result();
}

std::optional<Oversize> find_oversize(const ResetZeroRequest& request) {
  return Check().text("device", request.device, limits::kDeviceNameBytes).list("motor_ids", request.motor_ids).result();
}

std::optional<Oversize> find_oversize(const EstopRequest& request) {
  return Check().text("device", request.device, limits::kDeviceNameBytes).result();
}

std::optional<Oversize> find_oversize(const ListDevicesRequest& request) {
  return Check().text("node_name", request.node_name, limits::kNodeNameBytes).result();
}

std::optional<Oversize> find_oversize(const DeviceCallRequest& request) {
  return Check()
      .text("device", request.device, limits::kDeviceNameBytes)
      .text("op", request.op, limits::kOpBytes)
      .text("args_json", request.args_json, limits::kArgsJsonBytes)
      .result();
}

std::optional<Oversize> cut_to_limits(EstopRequest& request) {
  const std::optional<Oversize> found = Check()
                                            .text("node_name", request.node_name, limits::kNodeNameBytes)
                                            .text("reason", request.reason, limits::kReasonBytes)
                                            .result();
  cut_text(request.node_name, limits::kNodeNameBytes);
  cut_text(request.reason, limits::kReasonBytes);
  return found;
}

}  // namespace robotd::dds
