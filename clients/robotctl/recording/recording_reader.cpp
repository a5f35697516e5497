#include "recording/recording_reader.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <system_error>

#include "recording/little_endian.hpp"

namespace robotctl::recording {
namespace {

robotd::Error not_readable(const std::string& path, const std::string& why) {
  return robotd::make_error(robotd::ErrorCode::kInvalidArgument, path + " " + why);
}

// Reads up to `count` bytes; fewer only at the end of the file.
std::string read_bytes(std::ifstream& file, std::size_t count) {
  std::string bytes(count, '\0');
  file.read(bytes.data(), static_cast<std::streamsize>(count));
  bytes.resize(static_cast<std::size_t>(file.gcount()));
  return bytes;
}

}  // namespace

robotd::Result<RecordingReader> RecordingReader::open(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return not_readable(path, "cannot be opened: " + std::generic_category().message(errno));
  const std::string header = read_bytes(file, kFileHeaderBytes);
  const std::string_view expected = "expected a file written by robotctl record (docs/recording.md)";
  if (header.size() < kMagic.size() || !std::equal(kMagic.begin(), kMagic.end(), header.begin())) {
    return not_readable(
        path, "is not a robotd recording: it does not start with the recording signature; " + std::string(expected));
  }
  if (header.size() < kFileHeaderBytes)
    return not_readable(path, "ends inside its file header; " + std::string(expected));
  LittleEndianReader in(std::string_view(header).substr(kMagic.size()));
  const std::uint16_t major = in.u16();
  const std::uint16_t minor = in.u16();
  const std::uint32_t description_bytes = in.u32();
  if (major != kMajorVersion) {
    return not_readable(path, "is a robotd recording of format version " + std::to_string(major) + "." +
                                  std::to_string(minor) + "; this robotctl reads version " +
                                  std::to_string(kMajorVersion) + ".x (use a robotctl of that version)");
  }
  if (description_bytes > kLargestDescriptionBytes) {
    return not_readable(path, "has a description length of " + std::to_string(description_bytes) +
                                  " bytes, over the format's limit: the file is damaged");
  }
  const std::string description_text = read_bytes(file, description_bytes);
  if (description_text.size() < description_bytes) {
    return not_readable(path, "ends inside its description (" + std::to_string(description_text.size()) + " of " +
                                  std::to_string(description_bytes) + " bytes): the file is damaged");
  }
  auto description = parse_description(description_text);
  if (!description) return not_readable(path, description.error().message);

  RecordingReader reader(path, std::move(file));
  reader.description_ = std::move(description.value());
  reader.minor_version_ = minor;
  reader.offset_ = kFileHeaderBytes + description_bytes;
  return reader;
}

std::optional<Record> RecordingReader::next() {
  if (ending_ != Ending::kReading) return std::nullopt;
  const std::string header = read_bytes(file_, kRecordHeaderBytes);
  if (header.empty()) {
    ending_ = Ending::kUnclosed;
    return std::nullopt;
  }
  LittleEndianReader in(header);
  Record record;
  record.kind = in.u8();
  const std::uint32_t payload_bytes = in.u32();
  record.time_ns = in.i64();
  const bool whole_header = header.size() == kRecordHeaderBytes;
  if (whole_header && payload_bytes <= kLargestPayloadBytes) record.payload = read_bytes(file_, payload_bytes);
  if (!whole_header || payload_bytes > kLargestPayloadBytes || record.payload.size() < payload_bytes) {
    ending_ = Ending::kTruncated;
    truncated_bytes_ = header.size() + record.payload.size();
    return std::nullopt;
  }
  offset_ += kRecordHeaderBytes + payload_bytes;
  ++records_;
  if (record.kind == static_cast<std::uint8_t>(RecordKind::kEnd)) ending_ = Ending::kClosed;
  return record;
}

std::string RecordingReader::ending_text() const {
  switch (ending_) {
    case Ending::kUnclosed:
      return path_ + " has no end record after its " + std::to_string(records_) +
             " records: robotctl record did not finish (it was killed, or the disk filled); every record is complete";
    case Ending::kTruncated:
      return path_ + " is cut short: the record at byte " + std::to_string(offset_) + " has only " +
             std::to_string(truncated_bytes_) + " bytes (robotctl record was killed while writing it); the " +
             std::to_string(records_) + " records before it are complete";
    case Ending::kReading:
    case Ending::kClosed:
      break;
  }
  return "";
}

}  // namespace robotctl::recording
