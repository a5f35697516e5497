#pragma once

// robotd's answer to each kind of recorded vector, as JSON with the vendor's field names, so that
// judge() can compare it with what the vendor code recorded.

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace robotd::parol6::conformance {

using Bytes = std::vector<std::uint8_t>;

/// The 56-byte host frame robotd's codec encodes from the generator's input (positions, speeds,
/// command, affected/io bit lists, timeout, gripper[6]), as hex.
nlohmann::json tx_frame(const nlohmann::json& input);

/// A reply body decoded by robotd, in the shape of the API's unpack_rx_frame_into (object
/// detection decoded from the status byte) and of the commander's Unpack_data (raw byte 52).
nlohmann::json rx_as_api(const Bytes& body);
nlohmann::json rx_as_commander(const Bytes& body);

/// robotd's joint conversions: rad, rad/s → microsteps, microsteps/s, and back.
nlohmann::json to_steps(int joint, double rad);
nlohmann::json to_rad(int joint, std::int32_t steps);

/// The frames robotd's driver takes from a reply stream (its resynchronising parser, bodies its
/// decoder accepts): as the API's transport publishes them (per read, fed byte by byte and at
/// once: how many, and the first 52 bytes of the last) and as the commander unpacks them (whole
/// bodies).
nlohmann::json framing_as_api(const Bytes& stream);
nlohmann::json framing_as_commander(const Bytes& stream);

}  // namespace robotd::parol6::conformance
