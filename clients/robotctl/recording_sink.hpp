// Turns robotd's samples into records of a recording as they arrive, from the client's
// dispatch thread, while the main thread flushes and finally finishes the file. Keeps the
// counts robotctl record reports.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "recording/recording_writer.hpp"
#include "robotd/messages.hpp"
#include "robotd/result.hpp"

namespace robotctl {

class RecordingSink {
 public:
  /// Records samples of the devices in `description` (a command whose device is not among them
  /// is recorded with kUnknownDevice only when `keep_unknown_devices`). A command that names no
  /// device is for `only_device`, robotd's one device ("" when it serves several: robotd alone
  /// knows which device such a command's session is on).
  RecordingSink(recording::RecordingWriter writer, const recording::Description& description, bool keep_unknown_devices,
                std::string only_device);

  void add(const robotd::JointState& state);
  void add(const robotd::ControlCommand& command);
  void add(const robotd::DeviceStatus& status);
  void add(const robotd::SessionStatus& status);

  /// Hands what is buffered to the kernel; fails once any write has failed.
  robotd::Result<void> flush();
  /// Writes the end record and closes the file. Call once, after the subscriptions are gone.
  robotd::Result<void> finish();

  struct Summary {
    double duration_s = 0;
    std::uint64_t bytes = 0;
    std::array<std::uint64_t, 4> records{};  // joint_states, control_command, session_status, device_status
    std::uint64_t unrecordable = 0;          // samples with arrays beyond the format's 65535 values
  };
  Summary summary() const;

 private:
  std::int64_t now_ns() const;
  std::optional<std::uint16_t> device_index(const std::string& device) const;
  void append(recording::RecordKind kind, const std::optional<std::string>& payload);

  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  const bool keep_unknown_devices_;
  const std::string only_device_;
  std::map<std::string, std::uint16_t> device_indices_;
  mutable std::mutex mutex_;
  recording::RecordingWriter writer_;
  Summary summary_;
  std::optional<robotd::Error> error_;  // the first failed write
};

}  // namespace robotctl
