#pragma once

// What robotd's codec sends for one call of the PiPER SDK's C_PiperInterface_V2, given the same
// arguments (in the SDK's integer units): the SDK call names the frame, robotd builds it from SI
// values through its own codec.

#include <stdexcept>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/piper_frames.hpp"

namespace robotd::piper::conformance {

/// robotd has no counterpart of this call or of this argument (documented as not implemented).
struct NotOffered : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The frames robotd's codec encodes for `call(args…)`, in bus order, with the SDK 0.6.1 codec
/// options (8-bit MIT torque). Throws what robotd's codec throws when it refuses the arguments,
/// NotOffered when robotd has no such call.
std::vector<CanMessage> robotd_frames(std::string_view call, const nlohmann::json& args);

}  // namespace robotd::piper::conformance
