// The arm's answer to the 0x4AF firmware request (spec §5.14): 11 frames, 88 ASCII bytes.
#pragma once

#include <string>
#include <vector>

#include "codec/piper_frames.hpp"

namespace robotd::piper::sim {

inline constexpr int kFirmwareFrames = 11;
inline constexpr const char* kHardwareVersion = "H-V1.2-1";

/// The 88-byte text: hardware version at 0–7, motor ratio 16–17, node type "ARM_MC" at 32–37,
/// `software_version` (8 characters, padded or cut) at 60–67, production date 68–73, node
/// number 76–77; the rest spaces.
std::string firmware_text(const std::string& software_version);

/// That text as the 11 frames of the reply, in order.
std::vector<CanMessage> firmware_reply(const std::string& software_version, const CodecOptions& options);

}  // namespace robotd::piper::sim
