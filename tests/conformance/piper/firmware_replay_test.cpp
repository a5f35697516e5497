// The firmware version the SDK reports (GetPiperFirmwareVersion) after each chunk of the 0x4AF
// reply, against robotd's software_version() of the same text.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "codec/piper_frames.hpp"
#include "conformance_report.hpp"
#include "differences.hpp"
#include "vector_file.hpp"

namespace robotd::piper::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::hex_bytes;
using robotd::conformance::load_json_lines;
using robotd::conformance::record;

constexpr int kSdkNoVersion = -0x4AF;  // what GetPiperFirmwareVersion returns before "S-V" arrives

TEST(FirmwareReplay, VersionIsReportedAsTheSdkReportsIt) {
  const std::vector<json> vectors = load_json_lines("firmware.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    std::string text;
    json robotd = json::array();
    for (const json& chunk : vector.at("chunks")) {
      const std::vector<std::uint8_t> bytes = hex_bytes(chunk.get<std::string>());
      text.append(bytes.begin(), bytes.end());
      const auto version = software_version(text);
      robotd.push_back(version ? json(*version) : json(kSdkNoVersion));
    }
    record("firmware", judge("firmware", json{{"chunks", vector.at("chunks")}}, vector.at("versions"), robotd));
  }
}

}  // namespace
}  // namespace robotd::piper::conformance
