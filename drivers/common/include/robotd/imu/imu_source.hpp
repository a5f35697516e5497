// The IMU a driver attaches: a source that reads an IMU on its own thread and keeps its newest
// sample for the driver's RT read() to copy. A driver whose device has no IMU of its own (the
// PI Plus humanoid's Yesense sits on a separate USB serial line) configures one from a params
// object, starts it on connect and hands latest() to Feedback::imu.
//
//   {"source": "yesense", "serial": {"device": "/dev/ttyUSB0", "baud": 460800}, "timeout_ms": 100}
//
// Threads: start, stop, status, diagnostics — non-RT (the driver's connect/disconnect and
// diagnostics). latest, latest_reading — RT-safe: no lock, no allocation, no system call other
// than reading CLOCK_MONOTONIC, never waits on the reader thread.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "robotd/driver/driver.hpp"
#include "robotd/driver/json_reader.hpp"
#include "robotd/driver/types.hpp"
#include "robotd/imu/imu_reading.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::imu {

enum class LinkState : std::uint8_t {
  kStopped,  // not started, or stopped
  kDown,     // the device cannot be opened or closed under us (unplugged): retried every second
  kSilent,   // open, but no valid sample for timeout_ms (not streaming, wrong baud, paused)
  kUp,       // valid samples arriving
};

const char* to_string(LinkState state) noexcept;

/// What diagnostics() reports, as numbers (tests, drivers that want to act on it).
struct ImuStatus {
  LinkState link = LinkState::kStopped;
  std::uint64_t samples = 0;          // frames that decoded into a sample
  std::uint64_t checksum_errors = 0;  // complete frames whose checksum failed
  std::uint64_t malformed = 0;        // frames with an impossible length or data items that did not decode
  std::uint64_t bytes_discarded = 0;  // bytes skipped while resynchronising
  std::uint64_t sequence_gaps = 0;    // times the device's frame counter skipped (frames lost)
  std::uint64_t opens = 0;            // times the device was opened (1 + reconnects)
  double rate_hz = 0;                 // samples per second over the last second
  std::optional<double> age_ms;       // since the newest sample was read; nullopt before the first
  std::string error;                  // why the link is down or silent; empty when up
  std::string content;                // what the newest sample carried, e.g. "quaternion, gyro, accel"
};

class ImuSource {
 public:
  virtual ~ImuSource() = default;
  ImuSource() = default;
  ImuSource(const ImuSource&) = delete;
  ImuSource& operator=(const ImuSource&) = delete;

  /// Opens the device and starts reading. A device that is not there yet is not an error: the
  /// link is down (status() says why) and the source retries every second. Errors: the reader
  /// thread cannot be started.
  virtual Result<void> start() = 0;
  /// Stops reading and closes the device; latest() is false afterwards. Safe when not started.
  virtual void stop() noexcept = 0;

  /// The newest sample and when it was read (CLOCK_MONOTONIC ns); false (outputs unchanged)
  /// when there is none younger than timeout_ms, or the line is down. RT-safe.
  virtual bool latest_reading(ImuReading& out, std::int64_t& stamp_ns) const noexcept = 0;
  /// latest_reading() as the driver API's sample. RT-safe.
  bool latest(driver::ImuSample& out, std::int64_t& stamp_ns) const noexcept;

  virtual ImuStatus status() const = 0;
  /// "yesense on /dev/ttyUSB0" — which IMU, on what line.
  virtual std::string describe() const = 0;
  /// status() as the driver API's key/value lines, keys prefixed "imu".
  driver::Diagnostics diagnostics() const;
};

struct ImuSourceConfig {
  std::string source = "yesense";
  transport::SerialConfig serial{.device = "/dev/ttyUSB0", .baud = 460'800};  // the Yesense default
  std::int64_t timeout_ms = 100;  // a sample older than this is stale: latest() false, link silent
};

/// Reads an IMU source's params object; problems go to the reader's errors with their key path
/// ("imu.serial.device: …"). Calls reader.finish().
ImuSourceConfig read_imu_source_config(JsonReader& reader);

/// The source `config` names (not started).
std::unique_ptr<ImuSource> make_imu_source(const ImuSourceConfig& config);

/// Reads `params` (named `path` in errors, e.g. "imu") and makes the source; an
/// ErrorCode::kInvalidArgument error lists every problem.
Result<std::unique_ptr<ImuSource>> make_imu_source(const nlohmann::json& params, const std::string& path = "");

}  // namespace robotd::imu
