// Recordings written into temporary files for the format and replay tests.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "recording/record_codec.hpp"
#include "recording/recording_format.hpp"
#include "recording/recording_writer.hpp"

namespace robotctl::recording::testing {

/// A file name in /tmp, removed when this goes.
class TemporaryPath {
 public:
  TemporaryPath() {
    std::string pattern = "/tmp/robotctl-recording-test-XXXXXX";
    const int fd = mkstemp(pattern.data());
    if (fd >= 0) close(fd);
    path_ = pattern;
  }
  TemporaryPath(const TemporaryPath&) = delete;
  TemporaryPath& operator=(const TemporaryPath&) = delete;
  ~TemporaryPath() { std::filesystem::remove(path_); }

  const std::string& str() const { return path_; }

 private:
  std::string path_;
};

/// A 2-joint arm with limits ±1 rad and 1 rad/s.
inline RecordedDevice two_joint_arm() {
  return RecordedDevice{"arm",        "sim",      "test arm", 1000,       {"shoulder", "elbow"},
                        {-1.0, -1.0}, {1.0, 1.0}, {1.0, 1.0}, {5.0, 5.0}, {10.0, 10.0}};
}

inline Description arm_description() {
  return Description{"1.2.3", 1'700'000'000'000'000'000, 42, {"joint_states", "control_command"}, {two_joint_arm()}};
}

inline ControlCommandRecord position_command(std::vector<std::int32_t> motor_ids, std::vector<float> positions) {
  ControlCommandRecord command;
  command.device = 0;
  command.session = 0x3f2a9c1e;
  command.values.motor_ids = std::move(motor_ids);
  command.values.positions = std::move(positions);
  return command;
}

/// Appends a record through `writer`, encoding `record`.
template <class Record>
void append(RecordingWriter& writer, RecordKind kind, std::int64_t time_ns, const Record& record) {
  const auto payload = encode(record);
  if (payload) (void)writer.append(kind, time_ns, *payload);
}

inline std::uintmax_t file_size(const std::string& path) { return std::filesystem::file_size(path); }

}  // namespace robotctl::recording::testing
