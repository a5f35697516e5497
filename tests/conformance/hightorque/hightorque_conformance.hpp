#pragma once

// What the HighTorque replay tests share: the verdict of one vector (passed, one of the
// documented deliberate differences, not implemented, or failed with a message), the board
// models of config/examples/hightorque.json, and comparisons at the vendor's float precision.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/hightorque_codec.hpp"
#include "conformance_report.hpp"

namespace robotd::hightorque::conformance {

using robotd::conformance::Outcome;
using Bytes = std::vector<std::uint8_t>;

/// Records a vector of `group`. `failed` also fails the running GoogleTest with `what` and
/// `detail`; `deliberate_difference` needs `difference` to be an id of differences.json.
void verdict(std::string_view group, Outcome outcome, const std::string& what, const std::string& detail = {},
             std::string_view difference = {});

/// The deliberate difference ids listed in differences.json.
bool documented(std::string_view difference);

/// The motor models of config/examples/hightorque.json's "motor_models" (a missing model is an
/// error of the config the test reports).
const std::map<std::string, MotorScaling, std::less<>>& example_models();

/// robotd's value, a double, against the vendor's float: equal once rounded to float.
bool same_float(double robotd, double vendor);

/// The bytes of a frame robotd built.
Bytes bytes_of(const transport::CanMessage& message);

std::string hex(const Bytes& bytes);

/// An int16 field of a little-endian byte string.
std::int16_t int16_at(const Bytes& bytes, std::size_t at);

}  // namespace robotd::hightorque::conformance
