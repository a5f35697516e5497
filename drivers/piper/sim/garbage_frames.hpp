// Malformed traffic for robustness tests: feedback ids with payloads too short to decode,
// identifiers the protocol does not use (standard and extended) with random payloads. Nothing
// here decodes as a valid PiPER frame, so a driver that sees it must ignore it.
#pragma once

#include <random>

#include "codec/piper_frames.hpp"

namespace robotd::piper::sim {

/// One garbage frame.
CanMessage garbage_frame(std::mt19937& random);

/// Whether `id` (standard) is one the PiPER protocol uses in either direction.
bool is_protocol_id(std::uint32_t id);

}  // namespace robotd::piper::sim
