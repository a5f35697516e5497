#include "robotd/imu/imu_source.hpp"

#include <cstdio>
#include <vector>

#include "imu_source_internal.hpp"
#include "yesense_source.hpp"

namespace robotd::imu {
namespace {

constexpr std::int64_t kMaxTimeoutMs = 10'000;
constexpr int kYesenseBaud = 460'800;

}  // namespace

std::string content_of(const ImuReading& reading) {
  std::string text;
  const auto add = [&text](bool present, const char* name) {
    if (!present) return;
    if (!text.empty()) text += ", ";
    text += name;
  };
  add(reading.has_orientation, "orientation");
  add(reading.has_angular_velocity, "gyro");
  add(reading.has_linear_acceleration, "accel");
  add(reading.has_euler, "euler");
  add(reading.has_temperature, "temperature");
  add(reading.has_sample_time, "sample time");
  return text.empty() ? "nothing" : text;
}

const char* to_string(LinkState state) noexcept {
  switch (state) {
    case LinkState::kStopped:
      return "stopped";
    case LinkState::kDown:
      return "down";
    case LinkState::kSilent:
      return "silent";
    case LinkState::kUp:
      return "up";
  }
  return "unknown";
}

bool ImuSource::latest(driver::ImuSample& out, std::int64_t& stamp_ns) const noexcept {
  ImuReading reading;
  if (!latest_reading(reading, stamp_ns)) return false;
  out = to_sample(reading);
  return true;
}

driver::Diagnostics ImuSource::diagnostics() const {
  const ImuStatus now = status();
  std::string link = describe() + " (" + to_string(now.link) + ")";
  if (!now.error.empty()) link += ": " + now.error;
  std::array<char, 160> frames{};
  std::snprintf(frames.data(), frames.size(),
                "%llu samples, %llu checksum errors, %llu malformed, %llu gaps, %llu bytes skipped, %llu opens",
                static_cast<unsigned long long>(now.samples), static_cast<unsigned long long>(now.checksum_errors),
                static_cast<unsigned long long>(now.malformed), static_cast<unsigned long long>(now.sequence_gaps),
                static_cast<unsigned long long>(now.bytes_discarded), static_cast<unsigned long long>(now.opens));
  std::array<char, 32> rate{};
  std::snprintf(rate.data(), rate.size(), "%.1f Hz", now.rate_hz);
  driver::Diagnostics values{{"imu", link}, {"imu_frames", frames.data()}, {"imu_rate", rate.data()}};
  if (now.age_ms) {
    std::array<char, 32> age{};
    std::snprintf(age.data(), age.size(), "%.1f ms", *now.age_ms);
    values.emplace_back("imu_age", age.data());
    values.emplace_back("imu_content", now.content);
  }
  return values;
}

ImuSourceConfig read_imu_source_config(JsonReader& reader) {
  ImuSourceConfig config;
  config.source = reader.string_or("source", config.source, {"yesense"});
  reader.require("serial", "the IMU's serial line: {\"device\": \"/dev/ttyUSB0\", \"baud\": 460800}");
  if (auto serial = reader.object("serial")) {
    const bool baud_given = serial->has("baud");
    config.serial = transport::read_serial_link(*serial);
    if (!baud_given) config.serial.baud = kYesenseBaud;
  }
  config.timeout_ms = reader.integer_or("timeout_ms", config.timeout_ms, 1, kMaxTimeoutMs);
  reader.finish();
  return config;
}

std::unique_ptr<ImuSource> make_imu_source(const ImuSourceConfig& config) {
  // "yesense" is the only source so far; read_imu_source_config refuses any other name.
  return std::make_unique<YesenseSource>(config);
}

Result<std::unique_ptr<ImuSource>> make_imu_source(const nlohmann::json& params, const std::string& path) {
  std::vector<std::string> errors;
  JsonReader reader(params, path, errors);
  const ImuSourceConfig config = read_imu_source_config(reader);
  if (!errors.empty()) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));
  return make_imu_source(config);
}

}  // namespace robotd::imu
