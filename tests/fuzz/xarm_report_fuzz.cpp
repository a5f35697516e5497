// The xArm codec (drivers/xarm/codec) on any byte stream a report port (30000, 30001, 30003)
// can deliver: the size-prefixed splitter, then every packet parsed as the port's report kind.
// A parsed report must re-encode into a packet that parses and encodes to the same bytes again.
//
// Input: u8 options (bits 0–1: report kind real / normal / realtime, 3 = real; bits 2–7: read
// size − 1), then the stream.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/xarm_codec.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace robotd::xarm;
using robotd::fuzz::FuzzInput;

constexpr std::array<ReportKind, 4> kKinds{ReportKind::kReal, ReportKind::kNormal, ReportKind::kRealtime,
                                           ReportKind::kRich};

void read_packet(const Bytes& packet, ReportKind kind) {
  const auto report = parse_report(packet, kind);
  if (!report) return;
  static_cast<void>(motion_state_text(report.value().state));
  static_cast<void>(mode_text(report.value().mode));
  static_cast<void>(controller_error_text(report.value().error_code));
  static_cast<void>(controller_warning_text(report.value().warning_code));

  const Bytes encoded = encode_report(report.value(), kind, report.value().has_force_torque);
  const auto again = parse_report(encoded, kind);
  FUZZ_CHECK(again.ok());
  FUZZ_CHECK(encode_report(again.value(), kind, again.value().has_force_torque) == encoded);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const std::uint8_t options = input.u8();
  const ReportKind kind = kKinds.at(options & 3U);
  ReportSplitter splitter;
  bool broken = false;
  const auto read_size = static_cast<std::uint8_t>(options >> 2);
  robotd::fuzz::feed_in_pieces(input.rest(), read_size, [&](std::span<const std::uint8_t> bytes) {
    splitter.append(bytes);
    while (!broken) {
      const auto next = splitter.next();
      broken = !next.ok();  // the stream lost its framing: the driver reconnects
      if (broken || !next.value()) return;
      FUZZ_CHECK(next.value()->size() <= kMaxReportBytes);
      read_packet(*next.value(), kind);
    }
  });
  return 0;
}
