// robotd's messages as JSON, field for field (enums by name), for robotctl's --json output.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/messages.hpp"

namespace robotctl {

using Json = nlohmann::ordered_json;

Json to_json(const std::vector<robotd::DeviceInfo>& devices);
Json to_json(const robotd::DeviceInfo& device);
Json to_json(const robotd::DeviceStatus& status);
Json to_json(const robotd::SessionStatus& status);
Json to_json(const robotd::JointState& state);
Json to_json(const robotd::Imu& imu);
Json to_json(const robotd::PoseStamped& pose);
Json to_json(const robotd::Joy& joy);
Json to_json(const robotd::PolicyData& data);

/// One line; invalid UTF-8 from a device is replaced rather than failing the output.
std::string compact_text(const Json& json);
/// Indented by two spaces.
std::string pretty_text(const Json& json);

}  // namespace robotctl
