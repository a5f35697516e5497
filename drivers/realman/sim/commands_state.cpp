// State, enable and error commands (spec §4) and the joint limits (§8).
#include <cmath>

#include "controller.hpp"

namespace robotd::realman::sim {
namespace {

// The synthetic readings (README.md): what a resting arm reads, and how current grows with speed.
constexpr std::int64_t kJointVoltageMv = 24'000;
constexpr std::int64_t kJointTemperatureMc = 35'000;
constexpr double kJointRestingCurrentMa = 300;
constexpr double kJointCurrentMaPerRadS = 1500;
constexpr std::int64_t kControllerVoltageMv = 48'000;
constexpr std::int64_t kControllerRestingCurrentMa = 500;
constexpr std::int64_t kControllerTemperatureMc = 40'000;
constexpr const char* kVersion = "robotd-realman-sim 1.0";
constexpr const char* kBuildTime = "simulated";
constexpr std::int64_t kPlanVersion = 0x0100;  // gen 2's Plan_version low 16 bits: 1.0

/// Gen 2's Plan_version high byte for the RM65 variants it names (§4); 0 for other models.
std::int64_t plan_model_code(const std::string& product) {
  if (product == "RM65-B") return 0x6B;
  if (product == "RM65-ZF") return 0x6D;
  if (product == "RM65-SF") return 0x6F;
  return 0;
}

}  // namespace

nlohmann::json Controller::joint_list(const JointValues& values) const {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t j = 0; j < arm_.dof(); ++j) list.push_back(millidegrees_from_rad(values[j]));
  return list;
}

nlohmann::json Controller::pose_list() const {
  const EulerPose pose = arm_.flange_pose().value_or(EulerPose{});  // no DH table: zeros
  nlohmann::json list = nlohmann::json::array();
  for (const double m : pose.position_m) list.push_back(micrometres_from_m(m));
  for (const double rad : pose.euler_rad) list.push_back(milliradians_from_rad(rad));
  return list;
}

std::int64_t Controller::joint_current(std::size_t joint) const {
  if (!arm_.enabled(joint)) return 0;
  const double ma = kJointRestingCurrentMa + kJointCurrentMaPerRadS * std::abs(arm_.velocity()[joint]);
  return std::llround(ma * 1000);
}

std::int64_t Controller::joint_voltage(std::size_t /*joint*/) const { return arm_.powered() ? kJointVoltageMv : 0; }

std::int64_t Controller::joint_temperature(std::size_t /*joint*/) const { return kJointTemperatureMc; }

std::size_t Controller::joint_number(const char* key, std::int64_t number) const {
  if (number < 1 || number > static_cast<std::int64_t>(arm_.dof())) {
    throw Refusal(std::string("\"") + key + "\" names joint " + std::to_string(number) + "; this arm has joints 1 … " +
                  std::to_string(arm_.dof()));
  }
  return static_cast<std::size_t>(number - 1);
}

nlohmann::json Controller::get_current_arm_state(const CommandRequest& /*request*/) {
  nlohmann::json arm_state = {{"joint", joint_list(arm_.position())}, {"pose", pose_list()}};
  add_errors(arm_state);
  return {{"state", "current_arm_state"}, {"arm_state", arm_state}};
}

nlohmann::json Controller::get_joint_degree(const CommandRequest& /*request*/) {
  return {{"state", "joint_degree"}, {"joint", joint_list(arm_.position())}};
}

nlohmann::json Controller::get_arm_all_state(const CommandRequest& /*request*/) {
  nlohmann::json all_state = {{"temperature", per_joint([this](std::size_t j) { return joint_temperature(j); })},
                              {"current", per_joint([this](std::size_t j) { return joint_current(j); })},
                              {"voltage", per_joint([this](std::size_t j) { return joint_voltage(j); })},
                              {"err_flag", per_joint([this](std::size_t j) { return arm_.joint_errors(j); })},
                              {"en_flag", per_joint([this](std::size_t j) { return arm_.enabled(j) ? 1 : 0; })}};
  add_errors(all_state);
  return {{"state", "arm_all_state"}, {"all_state", all_state}};
}

nlohmann::json Controller::get_controller_state(const CommandRequest& /*request*/) {
  std::int64_t current_ma = kControllerRestingCurrentMa;
  for (std::size_t j = 0; j < arm_.dof(); ++j) current_ma += joint_current(j) / 1000;
  return {{"state", "controller_state"},
          {"voltage", kControllerVoltageMv},
          {"current", current_ma},
          {"temperature", kControllerTemperatureMc},
          {"err_flag", arm_.system_errors().empty() ? 0 : arm_.system_errors().front()}};
}

nlohmann::json Controller::get_current_joint_temperature(const CommandRequest& /*request*/) {
  return {{"state", "current_joint_temperature"},
          {"joint_temperature", per_joint([this](std::size_t j) { return joint_temperature(j); })}};
}

nlohmann::json Controller::get_current_joint_current(const CommandRequest& /*request*/) {
  return {{"state", "current_joint_current"},
          {"joint_current", per_joint([this](std::size_t j) { return joint_current(j); })}};
}

nlohmann::json Controller::get_current_joint_voltage(const CommandRequest& /*request*/) {
  return {{"state", "current_joint_voltage"},
          {"joint_voltage", per_joint([this](std::size_t j) { return joint_voltage(j); })}};
}

nlohmann::json Controller::get_joint_en_state(const CommandRequest& /*request*/) {
  return {{"state", "joint_en_state"},
          {"en_state", per_joint([this](std::size_t j) { return arm_.enabled(j) ? 1 : 0; })}};
}

nlohmann::json Controller::get_joint_err_flag(const CommandRequest& /*request*/) {
  return {{"state", "joint_err_flag"},
          {"err_flag", per_joint([this](std::size_t j) { return arm_.joint_errors(j); })},
          {"brake_state", per_joint([this](std::size_t j) { return arm_.enabled(j) ? 0 : 1; })}};
}

nlohmann::json Controller::get_arm_plan_num(const CommandRequest& /*request*/) {
  return {{"state", "arm_plan_num"},
          {"plan_num", 0},
          {"loop_num", nlohmann::json::array()},
          {"loop_cont", nlohmann::json::array()}};
}

nlohmann::json Controller::get_arm_software_info(const CommandRequest& /*request*/) {
  nlohmann::json reply = {{"command", "arm_software_info"},
                          {"Product_version", options_.model},
                          {"algorithm_info", {{"version", kVersion}}},
                          {"ctrl_info", {{"build_time", kBuildTime}, {"version", kVersion}}},
                          {"dynamic_info", {{"model_version", kVersion}}}};
  if (options_.generation == Generation::k4) {
    reply["robot_controller_version"] = "4.0";
    reply["communication_info"] = {{"build_time", kBuildTime}, {"version", kVersion}};
    reply["program_info"] = {{"build_time", kBuildTime}, {"version", kVersion}};
  } else {
    reply["plan_info"] = {{"build_time", kBuildTime}, {"version", kVersion}};
  }
  return reply;
}

nlohmann::json Controller::get_arm_software_version(const CommandRequest& /*request*/) {
  return {{"state", "arm_software_version"},
          {"Plan_version", (plan_model_code(options_.model) << 16) | kPlanVersion},
          {"Product_version", options_.model}};
}

nlohmann::json Controller::set_arm_power(const CommandRequest& request) {
  arm_.set_power(request.boolean("arm_power"));
  return {{"command", "set_arm_power"}, {"arm_power", true}};
}

nlohmann::json Controller::get_arm_power_state(const CommandRequest& /*request*/) {
  return {{"state", "arm_power_state"}, {"power_state", arm_.powered() ? 1 : 0}};
}

nlohmann::json Controller::set_joint_en_state(const CommandRequest& request) {
  const auto fields = request.integers("joint_en_state", 2, 0, static_cast<std::int64_t>(kMaxDof),
                                       "joint number, 1 enable / 0 disable");
  const std::size_t joint = joint_number("joint_en_state", fields[0]);
  if (fields[1] > 1) throw Refusal("\"joint_en_state\"[1] must be 1 (enable) or 0 (disable)");
  if (auto set = arm_.set_enabled(joint, fields[1] == 1); !set) throw Refusal(set.error().message);
  return {{"command", "set_joint_en_state"}, {"joint_en_state", true}};
}

nlohmann::json Controller::set_joint_clear_err(const CommandRequest& request) {
  const std::size_t joint =
      joint_number("joint_clear_err", request.integer("joint_clear_err", 1, static_cast<std::int64_t>(kMaxDof)));
  arm_.set_joint_error(joint, 0);
  return {{"command", "set_joint_clear_err"}, {"joint_clear_err", true}};
}

nlohmann::json Controller::clear_system_err(const CommandRequest& /*request*/) {
  arm_.clear_system_errors();
  return {{"command", "clear_system_err"}, {"clear_state", true}};
}

nlohmann::json Controller::set_init_pose(const CommandRequest& request) {
  const JointValues pose = joints_field(request, "init_pose");
  if (auto within = arm_.check_limits(pose); !within) throw Refusal(within.error().message);
  init_pose_ = pose;
  return {{"command", "set_init_pose"}, {"init_pose", true}};
}

nlohmann::json Controller::get_init_pose(const CommandRequest& /*request*/) {
  return {{"state", "arm_init_pose"}, {"init_pose", joint_list(init_pose_)}};
}

nlohmann::json Controller::get_joint_min_pos(const CommandRequest& /*request*/) {
  return {{"state", "joint_min_pos"}, {"min_pos", joint_list(arm_.model().min_rad)}};
}

nlohmann::json Controller::get_joint_max_pos(const CommandRequest& /*request*/) {
  return {{"state", "joint_max_pos"}, {"max_pos", joint_list(arm_.model().max_rad)}};
}

}  // namespace robotd::realman::sim
