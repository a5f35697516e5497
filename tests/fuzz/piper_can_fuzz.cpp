// The PiPER CAN codec (drivers/piper/codec) on any frame a CAN link can deliver, in both MIT
// layouts. A frame that decodes must re-encode into a frame that decodes to the same kind and
// encodes to the same bytes again (one decode/encode round reaches a fixed point); MIT frames,
// whose encoding truncates like the SDK's FloatToUint, to the same values within one
// quantisation step. The status texts the driver builds from decoded bytes must exist for every
// value, and the software version must be printable.
//
// Input: u8 options (bit 0: MIT layout kTorque12), a CAN message (can_message_input.hpp), then the
// rest as firmware reply text for software_version().
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>

#include "can_message_input.hpp"
#include "codec/piper_frames.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace robotd::piper;
using robotd::fuzz::FuzzInput;

CanMessage encode_frame(const Frame& frame, const CodecOptions& options) {
  return std::visit([&](const auto& decoded) { return encode(decoded, options); }, frame);
}

/// One quantisation step of each MIT field: its range over 2^bits − 1 (piper_frames.hpp).
bool within_one_step(const MitControl& a, const MitControl& b, MitLayout layout) {
  const double torque_step = layout == MitLayout::kTorque12 ? 32.0 / 4095 : 16.0 / 255;
  const auto close = [](double x, double y, double step) { return std::abs(x - y) <= step * (1 + 1e-9); };
  return a.joint == b.joint && close(a.position_rad, b.position_rad, 25.0 / 65535) &&
         close(a.velocity_rad_s, b.velocity_rad_s, 90.0 / 4095) && close(a.kp, b.kp, 500.0 / 4095) &&
         close(a.kd, b.kd, 10.0 / 4095) && close(a.torque, b.torque, torque_step);
}

bool same_message(const CanMessage& a, const CanMessage& b) {
  return a.id == b.id && a.extended == b.extended && a.fd == b.fd && a.length == b.length &&
         std::equal(a.data.begin(), a.data.begin() + a.length, b.data.begin());
}

/// The texts diagnostics and the "state" op show for what the arm reports.
void describe(const Frame& frame) {
  if (const auto* status = std::get_if<ArmStatus>(&frame)) {
    FUZZ_CHECK(control_mode_text(status->ctrl_mode) != nullptr);
    FUZZ_CHECK(move_mode_text(status->mode_feed) != nullptr);
    FUZZ_CHECK(arm_status_text(status->arm_status) != nullptr);
    FUZZ_CHECK(teach_status_text(status->teach_status) != nullptr);
  } else if (const auto* info = std::get_if<LowSpeedInfo>(&frame)) {
    static_cast<void>(driver_status_text(info->status_bits));
  } else if (const auto* gripper = std::get_if<GripperFeedback>(&frame)) {
    static_cast<void>(gripper_status_text(gripper->status_bits));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  CodecOptions options;
  options.mit_layout = (input.u8() & 1U) != 0 ? MitLayout::kTorque12 : MitLayout::kTorque8Crc;
  const CanMessage message = robotd::fuzz::read_can_message(input);

  if (const auto frame = decode(message, options)) {
    describe(*frame);
    const CanMessage encoded = encode_frame(*frame, options);
    const auto again = decode(encoded, options);
    FUZZ_CHECK(again.has_value());
    FUZZ_CHECK(again->index() == frame->index());
    if (const auto* mit = std::get_if<MitControl>(&*frame)) {
      FUZZ_CHECK(within_one_step(*mit, std::get<MitControl>(*again), options.mit_layout));
    } else {
      FUZZ_CHECK(same_message(encode_frame(*again, options), encoded));
    }
  }
  static_cast<void>(is_firmware_request(message));

  if (const auto version = software_version(std::string(input.rest_text()))) {
    FUZZ_CHECK(robotd::fuzz::is_printable_ascii(*version));
    static_cast<void>(mit_layout_for(*version));
  }
  return 0;
}
