#include "hightorque_conformance.hpp"

#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "vector_file.hpp"

#ifndef ROBOTD_HIGHTORQUE_EXAMPLE_CONFIG
#error "ROBOTD_HIGHTORQUE_EXAMPLE_CONFIG names config/examples/hightorque.json"
#endif

namespace robotd::hightorque::conformance {

void verdict(std::string_view group, Outcome outcome, const std::string& what, const std::string& detail,
             std::string_view difference) {
  if (outcome == Outcome::deliberate_difference && !documented(difference)) {
    ADD_FAILURE() << what << ": difference '" << difference << "' is not listed in differences.json";
    outcome = Outcome::failed;
  }
  if (outcome == Outcome::failed) ADD_FAILURE() << "[" << group << "] " << what << "\n" << detail;
  robotd::conformance::record(group, outcome);
}

bool documented(std::string_view difference) {
  static const nlohmann::json listed = robotd::conformance::load_json("differences.json");
  for (const nlohmann::json& entry : listed.at("differences")) {
    if (entry.at("id").get<std::string>() == difference) return true;
  }
  return false;
}

const std::map<std::string, MotorScaling, std::less<>>& example_models() {
  static const std::map<std::string, MotorScaling, std::less<>> models = [] {
    std::ifstream in(ROBOTD_HIGHTORQUE_EXAMPLE_CONFIG);
    if (!in) throw std::runtime_error("cannot open " ROBOTD_HIGHTORQUE_EXAMPLE_CONFIG);
    const nlohmann::json config = nlohmann::json::parse(in, nullptr, true, /*ignore_comments=*/true);
    std::map<std::string, MotorScaling, std::less<>> out;
    for (const auto& [name, model] : config.at("params").at("motor_models").items()) {
      out[name] = MotorScaling{.torque_per_unit = model.value("torque_per_unit", 1.0),
                               .torque_offset_nm = model.value("torque_offset_nm", 0.0),
                               .gain_factor = model.value("gain_factor", 1.0)};
    }
    return out;
  }();
  return models;
}

bool same_float(double robotd, double vendor) { return static_cast<float>(robotd) == static_cast<float>(vendor); }

Bytes bytes_of(const transport::CanMessage& message) {
  return {message.data.begin(), message.data.begin() + message.length};
}

std::string hex(const Bytes& bytes) { return robotd::conformance::hex_text(bytes); }

std::int16_t int16_at(const Bytes& bytes, std::size_t at) {
  return static_cast<std::int16_t>(bytes.at(at) | (bytes.at(at + 1) << 8));
}

}  // namespace robotd::hightorque::conformance
