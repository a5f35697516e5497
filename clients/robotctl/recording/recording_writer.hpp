// Writes a robotd recording: the file header at once, then records as they come, through a
// buffer that flush() hands to the kernel. A process killed mid-way leaves a file whose
// complete records all read back (recording_reader.hpp). Not thread-safe: one writer per thread,
// or a lock around it.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "recording/recording_format.hpp"
#include "robotd/result.hpp"

namespace robotctl::recording {

class RecordingWriter {
 public:
  /// Creates (or replaces) `path` and writes the file header.
  static robotd::Result<RecordingWriter> create(const std::string& path, const Description& description);

  /// Appends one record. After a failed write every call fails with the same error, which
  /// names the file and the reason (a full disk, ...).
  robotd::Result<void> append(RecordKind kind, std::int64_t time_ns, std::string_view payload);
  /// Hands the buffered records to the kernel, so that they survive robotctl being killed.
  robotd::Result<void> flush();
  /// Appends the end record, flushes and closes the file; later calls fail.
  robotd::Result<void> finish(std::int64_t time_ns);

  /// Bytes written so far, the file header included.
  std::uint64_t bytes() const { return bytes_; }
  const std::string& path() const { return path_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };

  RecordingWriter(std::string path, std::FILE* file) : path_(std::move(path)), file_(file) {}
  robotd::Result<void> write(std::string_view bytes);
  robotd::Result<void> fail(const std::string& what);

  std::string path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  std::uint64_t bytes_ = 0;
  std::string error_;  // the first failure; empty while every write succeeded
};

}  // namespace robotctl::recording
