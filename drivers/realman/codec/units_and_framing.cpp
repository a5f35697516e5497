// The wire's integer units (§1 numeric conventions) and its "\r\n" framing (§1 transport).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

constexpr double kMillidegreesPerRad = 180'000.0 / std::numbers::pi;
constexpr double kMicrometresPerM = 1e6;
constexpr double kMilliradiansPerRad = 1e3;

/// Rounds to the nearest integer. Values beyond int64 (and NaN) saturate instead of taking
/// llround's unspecified result: the controller refuses such a target as beyond the limits.
std::int64_t round_saturating(double value) {
  constexpr double kTwoTo63 = 9223372036854775808.0;
  if (value >= -kTwoTo63 && value < kTwoTo63) return std::llround(value);
  return value < 0 ? std::numeric_limits<std::int64_t>::min() : std::numeric_limits<std::int64_t>::max();
}

}  // namespace

std::int64_t millidegrees_from_rad(double rad) { return round_saturating(rad * kMillidegreesPerRad); }
double rad_from_millidegrees(std::int64_t millidegrees) {
  return static_cast<double>(millidegrees) / kMillidegreesPerRad;
}
std::int64_t micrometres_from_m(double m) { return round_saturating(m * kMicrometresPerM); }
double m_from_micrometres(std::int64_t micrometres) { return static_cast<double>(micrometres) / kMicrometresPerM; }
std::int64_t milliradians_from_rad(double rad) { return round_saturating(rad * kMilliradiansPerRad); }
double rad_from_milliradians(std::int64_t milliradians) {
  return static_cast<double>(milliradians) / kMilliradiansPerRad;
}

std::string frame(const nlohmann::json& message) {
  // Strings robotd puts in a request (an IP address) are not validated as UTF-8: replace bad
  // bytes rather than throw.
  return message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + std::string(kMessageTerminator);
}

void LineSplitter::append(std::string_view bytes) {
  if (discarding_ && !bytes.empty()) {
    std::size_t resume = 0;
    if (discarded_cr_ && bytes.front() == '\n') {
      resume = 1;
    } else if (const auto end = bytes.find(kMessageTerminator); end != std::string_view::npos) {
      resume = end + kMessageTerminator.size();
    } else {
      discarded_cr_ = bytes.back() == '\r';
      return;
    }
    bytes.remove_prefix(resume);
    discarding_ = false;
    discarded_cr_ = false;
  }
  buffer_.append(bytes);

  // A line that outgrows the limit before its terminator arrives is dropped now, not buffered.
  const auto last_end = buffer_.rfind(kMessageTerminator);
  const std::size_t tail_start = last_end == std::string::npos ? 0 : last_end + kMessageTerminator.size();
  const bool ends_with_cr = buffer_.size() > tail_start && buffer_.back() == '\r';
  const std::size_t tail_bytes = buffer_.size() - tail_start - (ends_with_cr ? 1 : 0);
  if (tail_bytes <= max_line_bytes_) return;
  ++oversized_;
  discarding_ = true;
  discarded_cr_ = ends_with_cr;
  buffer_.resize(tail_start);
}

std::optional<std::string> LineSplitter::next() {
  while (true) {
    const auto end = buffer_.find(kMessageTerminator);
    if (end == std::string::npos) return std::nullopt;
    std::string line = buffer_.substr(0, end);
    buffer_.erase(0, end + kMessageTerminator.size());
    if (line.size() > max_line_bytes_) {
      ++oversized_;
      continue;
    }
    if (!line.empty()) return line;
  }
}

void LineSplitter::clear() {
  buffer_.clear();
  discarding_ = false;
  discarded_cr_ = false;
}

}  // namespace robotd::realman
