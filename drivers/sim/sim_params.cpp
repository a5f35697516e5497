#include "sim_params.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "robotd/driver/json_reader.hpp"

namespace robotd::sim {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void read_number(JsonReader& reader, std::string_view key, double& target) {
  if (const auto value = reader.number(key)) target = *value;
}

void read_non_negative(JsonReader& reader, std::string_view key, double& target) {
  if (const auto value = reader.number(key, NumberRange{.min = 0})) target = *value;
}

void read_positive(JsonReader& reader, std::string_view key, double& target) {
  const auto value = reader.number(key);
  if (!value) return;
  if (!(*value > 0)) {
    reader.error(key, "expected a number > 0, got " + format_number(*value));
    return;
  }
  target = *value;
}

/// Overrides each field of `joint` that the object under `reader` sets.
void read_joint_fields(JsonReader& reader, SimJointParams& joint) {
  driver::JointLimits& limits = joint.limits;
  read_number(reader, "position_min_rad", limits.position_min_rad);
  read_number(reader, "position_max_rad", limits.position_max_rad);
  read_positive(reader, "velocity_max_rad_s", limits.velocity_max_rad_s);
  read_positive(reader, "acceleration_max_rad_s2", limits.acceleration_max_rad_s2);
  read_positive(reader, "effort_max_nm", limits.effort_max_nm);
  read_positive(reader, "kp_max", limits.kp_max);
  read_positive(reader, "kd_max", limits.kd_max);
  // The sim can damp and hold on impedance: a default gain of 0 would let a joint go while
  // robotd reported DAMPING or KEEP.
  read_positive(reader, "default_kp", joint.default_kp);
  read_positive(reader, "default_kd", joint.default_kd);
  read_positive(reader, "inertia_kg_m2", joint.inertia_kg_m2);
  read_non_negative(reader, "damping_nm_s_rad", joint.damping_nm_s_rad);
  read_number(reader, "external_torque_nm", joint.external_torque_nm);
  read_number(reader, "initial_position_rad", joint.initial_position_rad);
}

/// Checks that relate fields to each other. With `only_own_keys`, a check is reported only when
/// the object under `reader` sets one of the fields it involves: a problem a joint inherits
/// from joint_defaults is reported once, at joint_defaults.
void check_joint_consistency(JsonReader& reader, const SimJointParams& joint, bool only_own_keys) {
  const auto involves_own_key = [&](std::initializer_list<std::string_view> keys) {
    return !only_own_keys ||
           std::any_of(keys.begin(), keys.end(), [&](std::string_view key) { return reader.has(key); });
  };
  const driver::JointLimits& limits = joint.limits;
  if (!(limits.position_min_rad < limits.position_max_rad) &&
      involves_own_key({"position_min_rad", "position_max_rad"})) {
    reader.error("position_min_rad", "expected less than position_max_rad (" + format_number(limits.position_max_rad) +
                                         "), got " + format_number(limits.position_min_rad));
    return;
  }
  if (joint.default_kp > limits.kp_max && involves_own_key({"default_kp", "kp_max"})) {
    reader.error("default_kp", "expected at most kp_max (" + format_number(limits.kp_max) + "), got " +
                                   format_number(joint.default_kp));
  }
  if (joint.default_kd > limits.kd_max && involves_own_key({"default_kd", "kd_max"})) {
    reader.error("default_kd", "expected at most kd_max (" + format_number(limits.kd_max) + "), got " +
                                   format_number(joint.default_kd));
  }
  const bool initial_within_limits =
      joint.initial_position_rad >= limits.position_min_rad && joint.initial_position_rad <= limits.position_max_rad;
  if (!initial_within_limits && involves_own_key({"initial_position_rad", "position_min_rad", "position_max_rad"})) {
    reader.error("initial_position_rad", "expected within position_min_rad..position_max_rad (" +
                                             format_number(limits.position_min_rad) + ".." +
                                             format_number(limits.position_max_rad) + "), got " +
                                             format_number(joint.initial_position_rad));
  }
}

/// Reads one joint object (or joint_defaults) over `joint`, then checks it as a whole unless a
/// field was already rejected (a rejected field keeps its default and would mislead the checks).
void read_joint(JsonReader& reader, SimJointParams& joint, bool only_own_keys, const std::vector<std::string>& errors) {
  const std::size_t errors_before = errors.size();
  read_joint_fields(reader, joint);
  if (errors.size() == errors_before) check_joint_consistency(reader, joint, only_own_keys);
  reader.finish();
}

bool is_valid_joint_name(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::vector<SimJointParams> read_joint_count(JsonReader& reader, const SimJointParams& defaults) {
  std::vector<SimJointParams> joints;
  const auto count = reader.integer("joint_count", 1, static_cast<std::int64_t>(driver::kMaxJoints));
  if (!count) return joints;
  for (std::int64_t index = 1; index <= *count; ++index) {
    SimJointParams joint = defaults;
    joint.name = "joint" + std::to_string(index);
    joints.push_back(std::move(joint));
  }
  return joints;
}

std::vector<SimJointParams> read_joint_list(JsonReader& reader, const nlohmann::json& params,
                                            const SimJointParams& defaults, std::vector<std::string>& errors) {
  std::vector<SimJointParams> joints;
  std::vector<JsonReader> joint_readers = reader.object_array("joints");
  const bool is_list = params.is_object() && params.contains("joints") && params.at("joints").is_array();
  if (is_list && (joint_readers.empty() || joint_readers.size() > driver::kMaxJoints)) {
    reader.error("joints", "expected 1.." + std::to_string(driver::kMaxJoints) + " joints, got " +
                               std::to_string(joint_readers.size()));
  }
  std::map<std::string, std::string, std::less<>> path_by_name;
  for (JsonReader& joint_reader : joint_readers) {
    SimJointParams joint = defaults;
    joint_reader.require("name", "a joint name of letters, digits and _");
    if (auto name = joint_reader.string("name")) {
      if (!is_valid_joint_name(*name)) {
        joint_reader.error("name", "expected a non-empty name of letters, digits and _, got \"" + *name + "\"");
      } else if (const auto previous = path_by_name.find(*name); previous != path_by_name.end()) {
        joint_reader.error("name", "\"" + *name + "\" is already the name of " + previous->second);
      } else {
        path_by_name.emplace(*name, joint_reader.path());
      }
      joint.name = std::move(*name);
    }
    read_joint(joint_reader, joint, /*only_own_keys=*/true, errors);
    joints.push_back(std::move(joint));
  }
  return joints;
}

}  // namespace

Result<SimParams> parse_sim_params(const nlohmann::json& params) {
  std::vector<std::string> errors;
  JsonReader reader(params, "", errors);
  SimParams out;
  out.model = reader.string_or("model", out.model);
  out.kinematic_model = reader.string_or("kinematic_model", out.kinematic_model);
  out.imu = reader.boolean_or("imu", out.imu);

  SimJointParams defaults;
  if (auto defaults_reader = reader.object("joint_defaults")) {
    read_joint(*defaults_reader, defaults, /*only_own_keys=*/false, errors);
  }

  const bool has_count = reader.has("joint_count");
  const bool has_list = reader.has("joints");
  std::vector<SimJointParams> counted = read_joint_count(reader, defaults);
  std::vector<SimJointParams> listed = read_joint_list(reader, params, defaults, errors);
  if (has_count && has_list) {
    reader.error("joint_count", "give either joint_count or joints, not both");
  } else if (!has_count && !has_list) {
    reader.error("joints",
                 "missing; define the joints with either joint_count (joints named joint1..jointN) or joints (a list "
                 "of named joints)");
  }
  out.joints = has_count ? std::move(counted) : std::move(listed);
  reader.finish();

  if (!errors.empty()) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));
  return out;
}

}  // namespace robotd::sim
