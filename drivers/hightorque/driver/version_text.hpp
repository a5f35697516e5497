#pragma once
// A motor's firmware version as people read it, for op answers and errors.
#include <string>

#include "codec/hightorque_codec.hpp"

namespace robotd::hightorque {

/// "major.minor.patch".
inline std::string version_text(const FirmwareVersion& version) {
  return std::to_string(version.major) + "." + std::to_string(version.minor) + "." + std::to_string(version.patch);
}

}  // namespace robotd::hightorque
