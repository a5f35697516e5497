// The RealMan codec (drivers/realman/codec) on any byte stream the controller's TCP port or
// its UDP push can deliver: the "\r\n" line splitter, then every line parsed as a message and
// read by each reply parser the driver uses, and as a real-time push datagram. Whatever parses
// must hold finite values within the codec's documented sizes.
//
// Input: u8 read size − 1, u8 line limit (× 16 bytes, 0: the default 64 KiB), u8 the push's
// speed unit (modulo 3, SpeedUnit's order), then the stream.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "codec/realman_codec.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace robotd::realman;
using robotd::fuzz::all_finite;
using robotd::fuzz::FuzzInput;

void describe_errors(const std::vector<std::uint16_t>& errors) {
  for (const std::uint16_t code : errors) {
    FUZZ_CHECK(code != 0);
    static_cast<void>(system_error_text(code));
    static_cast<void>(system_error_is_severe(code));
  }
}

void read_message(std::string_view line) {
  const auto message = parse_message(line);
  if (!message) return;
  if (const auto shape = reply_shape(message.value().key)) {
    static_cast<void>(reply_success(message.value(), *shape, message.value().key));
  }
  static_cast<void>(parse_trajectory_event(message.value()));
  describe_errors(collect_errors(message.value().body));
  if (const auto state = parse_current_arm_state(message.value())) {
    FUZZ_CHECK(state.value().dof <= kMaxDof);
    FUZZ_CHECK(all_finite(state.value().joints_rad));
    describe_errors(state.value().errors);
  }
  if (const auto gripper = parse_gripper_state(message.value())) {
    static_cast<void>(gripper_mode_text(gripper.value().mode));
    static_cast<void>(gripper_error_text(gripper.value().error_bits));
  }
  if (const auto info = parse_software_info(message.value())) {
    if (const auto model = find_model(info.value().product_version)) FUZZ_CHECK(model->dof <= kMaxDof);
  }
}

constexpr std::array<SpeedUnit, 3> kSpeedUnits{SpeedUnit::kCentiDegreesPerSecond, SpeedUnit::kCentiRpm,
                                               SpeedUnit::kFiftiethDegreesPerSecond};

void read_push(std::string_view datagram, SpeedUnit unit) {
  const auto push = parse_realtime_push(datagram, unit);
  if (!push) return;
  const RealtimePush& values = push.value();
  FUZZ_CHECK(values.dof <= kMaxDof);
  FUZZ_CHECK(all_finite(values.position_rad) && all_finite(values.speed_rad_s) && all_finite(values.current_a));
  FUZZ_CHECK(all_finite(values.voltage_v) && all_finite(values.temperature_c));
  FUZZ_CHECK(all_finite(values.position_m) && all_finite(values.quaternion_wxyz) && all_finite(values.euler_rad));
  for (const std::uint16_t bits : values.joint_errors) static_cast<void>(joint_error_text(bits));
  describe_errors(values.errors);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const std::uint8_t piece = input.u8();
  const std::size_t limit = input.u8();
  const SpeedUnit unit = kSpeedUnits.at(input.u8() % kSpeedUnits.size());
  LineSplitter splitter = limit == 0 ? LineSplitter() : LineSplitter(limit * 16);
  robotd::fuzz::feed_in_pieces(input.rest(), piece, [&](std::span<const std::uint8_t> bytes) {
    splitter.append({reinterpret_cast<const char*>(bytes.data()), bytes.size()});
    while (const auto line = splitter.next()) {
      FUZZ_CHECK(!line->empty() && (limit == 0 || line->size() <= limit * 16));
      read_message(*line);
      read_push(*line, unit);
    }
  });
  return 0;
}
