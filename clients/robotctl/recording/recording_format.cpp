#include "recording/recording_format.hpp"

#include <ctime>

#include <nlohmann/json.hpp>

#include "recording/little_endian.hpp"

namespace robotctl::recording {
namespace {

using Json = nlohmann::ordered_json;

Json to_json(const RecordedDevice& device) {
  return Json{{"name", device.name},
              {"driver", device.driver},
              {"model", device.model},
              {"rate_hz", device.rate_hz},
              {"joint_names", device.joint_names},
              {"position_min", device.position_min},
              {"position_max", device.position_max},
              {"velocity_max", device.velocity_max},
              {"acceleration_max", device.acceleration_max},
              {"effort_max", device.effort_max}};
}

Json to_json(const Description& description) {
  Json devices = Json::array();
  for (const auto& device : description.devices) devices.push_back(to_json(device));
  return Json{{"robotd_version", description.robotd_version},
              {"start_time_ns", description.start_time_ns},
              {"start_time", utc_time_text(description.start_time_ns)},
              {"domain_id", description.domain_id},
              {"topics", description.topics},
              {"devices", devices}};
}

RecordedDevice recorded_device_from_json(const Json& json) {
  RecordedDevice device;
  json.at("name").get_to(device.name);
  device.driver = json.value("driver", "");
  device.model = json.value("model", "");
  device.rate_hz = json.value("rate_hz", 0.0);
  json.at("joint_names").get_to(device.joint_names);
  json.at("position_min").get_to(device.position_min);
  json.at("position_max").get_to(device.position_max);
  json.at("velocity_max").get_to(device.velocity_max);
  device.acceleration_max = json.value("acceleration_max", std::vector<double>{});
  device.effort_max = json.value("effort_max", std::vector<double>{});
  return device;
}

}  // namespace

std::string kind_name(std::uint8_t kind) {
  switch (static_cast<RecordKind>(kind)) {
    case RecordKind::kJointState:
      return "joint_state";
    case RecordKind::kControlCommand:
      return "control_command";
    case RecordKind::kSessionStatus:
      return "session_status";
    case RecordKind::kDeviceStatus:
      return "device_status";
    case RecordKind::kEnd:
      return "end";
  }
  return "kind " + std::to_string(kind);
}

const std::vector<std::string>& recordable_topics() {
  static const std::vector<std::string> topics = {"joint_states", "control_command", "session_status", "device_status"};
  return topics;
}

RecordedDevice recorded_device(const robotd::DeviceInfo& device) {
  return RecordedDevice{
      device.name,         device.driver,       device.model,        device.rate_hz,          device.joint_names,
      device.position_min, device.position_max, device.velocity_max, device.acceleration_max, device.effort_max};
}

std::string utc_time_text(std::int64_t time_ns) {
  const auto seconds = static_cast<std::time_t>(time_ns / 1'000'000'000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text.data();
}

std::string encode_file_header(const Description& description) {
  const std::string json_text = to_json(description).dump(-1, ' ', false, Json::error_handler_t::replace);
  std::string header(kMagic.begin(), kMagic.end());
  LittleEndianWriter out(header);
  out.u16(kMajorVersion);
  out.u16(kMinorVersion);
  out.u32(static_cast<std::uint32_t>(json_text.size()));
  out.bytes(json_text);
  return header;
}

robotd::Result<Description> parse_description(std::string_view json_text) {
  try {
    const Json json = Json::parse(json_text);
    Description description;
    description.robotd_version = json.value("robotd_version", "");
    json.at("start_time_ns").get_to(description.start_time_ns);
    description.domain_id = json.value("domain_id", 0);
    json.at("topics").get_to(description.topics);
    for (const auto& device : json.at("devices")) description.devices.push_back(recorded_device_from_json(device));
    return description;
  } catch (const Json::exception& error) {
    return robotd::make_error(robotd::ErrorCode::kInvalidArgument,
                              std::string("its description is not what docs/recording.md specifies: ") + error.what());
  }
}

}  // namespace robotctl::recording
