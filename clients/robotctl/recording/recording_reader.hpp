// Reads a robotd recording record by record, so that a long one is never held in memory whole.
// A file cut short (robotctl killed while recording) reads up to its last complete record;
// ending() then says what was lost.
#pragma once

#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

#include "recording/recording_format.hpp"
#include "robotd/result.hpp"

namespace robotctl::recording {

struct Record {
  std::uint8_t kind = 0;     // a RecordKind, or a kind of a newer minor version
  std::int64_t time_ns = 0;  // receive time, ns since the recording began
  std::string payload;
};

class RecordingReader {
 public:
  /// Opens `path` and reads its header. Fails, saying what was found and what is expected,
  /// unless it is a recording of format version kMajorVersion.x.
  static robotd::Result<RecordingReader> open(const std::string& path);

  const std::string& path() const { return path_; }
  const Description& description() const { return description_; }
  std::uint16_t minor_version() const { return minor_version_; }

  /// The next complete record (the end record included), or nullopt when there is none.
  std::optional<Record> next();

  enum class Ending {
    kReading,    // next() has not returned nullopt yet
    kClosed,     // the end record was read: the recording was closed
    kUnclosed,   // the file ends after a complete record, without an end record
    kTruncated,  // the file ends inside a record
  };
  Ending ending() const { return ending_; }
  /// For kUnclosed and kTruncated: what happened, for a person ("" otherwise).
  std::string ending_text() const;

 private:
  RecordingReader(std::string path, std::ifstream file) : path_(std::move(path)), file_(std::move(file)) {}

  std::string path_;
  std::ifstream file_;
  Description description_;
  std::uint16_t minor_version_ = 0;
  Ending ending_ = Ending::kReading;
  std::uint64_t offset_ = 0;           // of the next record
  std::uint64_t truncated_bytes_ = 0;  // of the record cut short
  std::uint64_t records_ = 0;
};

}  // namespace robotctl::recording
