#include "recording/recording_writer.hpp"

#include <cerrno>
#include <system_error>

#include "recording/little_endian.hpp"

namespace robotctl::recording {
namespace {

// Large enough that a 1 kHz stream costs a few writes per second, small enough that robotctl
// being killed loses well under a second of it.
constexpr std::size_t kBufferBytes = std::size_t{64} * 1024;

robotd::Error write_error(const std::string& message) {
  return robotd::make_error(robotd::ErrorCode::kInvalidArgument, message);
}

}  // namespace

robotd::Result<RecordingWriter> RecordingWriter::create(const std::string& path, const Description& description) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    return write_error("cannot create " + path + ": " + std::generic_category().message(errno) +
                       " (expected a writable path for the recording)");
  }
  RecordingWriter writer(path, file);
  std::setvbuf(file, nullptr, _IOFBF, kBufferBytes);
  if (auto written = writer.write(encode_file_header(description)); !written) return written.error();
  return writer;
}

robotd::Result<void> RecordingWriter::append(RecordKind kind, std::int64_t time_ns, std::string_view payload) {
  if (payload.size() > kLargestPayloadBytes) {
    return write_error("a " + kind_name(static_cast<std::uint8_t>(kind)) + " record of " +
                       std::to_string(payload.size()) + " bytes is over the format's limit of " +
                       std::to_string(kLargestPayloadBytes) + " bytes");
  }
  std::string header;
  LittleEndianWriter out(header);
  out.u8(static_cast<std::uint8_t>(kind));
  out.u32(static_cast<std::uint32_t>(payload.size()));
  out.i64(time_ns);
  if (auto written = write(header); !written) return written;
  return write(payload);
}

robotd::Result<void> RecordingWriter::flush() {
  if (!error_.empty()) return write_error(error_);
  if (!file_) return write_error(path_ + " is already closed");
  if (std::fflush(file_.get()) != 0) return fail("flushing");
  return {};
}

robotd::Result<void> RecordingWriter::finish(std::int64_t time_ns) {
  if (auto appended = append(RecordKind::kEnd, time_ns, {}); !appended) return appended;
  if (auto flushed = flush(); !flushed) return flushed;
  if (std::fclose(file_.release()) != 0) return fail("closing");
  return {};
}

robotd::Result<void> RecordingWriter::write(std::string_view bytes) {
  if (!error_.empty()) return write_error(error_);
  if (!file_) return write_error(path_ + " is already closed");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_.get()) != bytes.size()) return fail("writing");
  bytes_ += bytes.size();
  return {};
}

robotd::Result<void> RecordingWriter::fail(const std::string& what) {
  error_ = what + " " + path_ + " failed: " + std::generic_category().message(errno);
  return write_error(error_);
}

}  // namespace robotctl::recording
