// Replays what the two PAROL6 host codebases (PCrnjak/PAROL6-python-API and
// PCrnjak/PAROL-commander-software) recorded (generate/generate.py) against robotd's codec, joint
// conversions and stream parser. Each vector counts once per vendor it is compared with.
#include <string>
#include <string_view>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conformance_report.hpp"
#include "judge.hpp"
#include "robotd_results.hpp"
#include "vector_file.hpp"

namespace robotd::parol6::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::hex_bytes;
using robotd::conformance::load_json_lines;

// The commander computes steps → rad through degrees, the API directly: one ulp apart at most.
constexpr double kCommanderRadianTolerance = 1e-15;

const Differences& differences() {
  static const Differences loaded = Differences::load();
  return loaded;
}

/// Records the verdict under `group` and fails the test on an undocumented difference.
void check(std::string_view group, std::string_view vendor, const json& vector, const json& vendor_result,
           const json& robotd, const std::string& name, double tolerance = 0.0) {
  const Verdict verdict = judge(differences(), group, vendor, vendor_result, robotd, vector, tolerance);
  robotd::conformance::record(group, verdict.outcome);
  if (verdict.outcome == Outcome::failed) ADD_FAILURE() << group << " / " << name << ":" << verdict.detail;
}

std::string units_name(const json& vector) {
  const std::string joint = "J" + std::to_string(vector.at("joint").get<int>() + 1);
  if (vector.at("kind") == "to_steps") return joint + " " + vector.at("rad").dump() + " rad";
  return joint + " " + vector.at("steps").dump() + " steps";
}

TEST(Parol6Conformance, HostFramesEncodeAsBothVendorsPackThem) {
  const auto vectors = load_json_lines("tx_frames.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    const json robotd = {{"frame", tx_frame(vector.at("input"))}};
    const std::string name = vector.at("name");
    check("tx frames", "api", vector, {{"frame", vector.at("api")}}, robotd, name);
    check("tx frames", "commander", vector, {{"frame", vector.at("commander")}}, robotd, name);
  }
}

TEST(Parol6Conformance, RepliesDecodeAsBothVendorsUnpackThem) {
  const auto vectors = load_json_lines("rx_frames.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    const Bytes body = hex_bytes(vector.at("body").get<std::string>());
    const std::string name = vector.at("name");
    check("rx frames", "api", vector, vector.at("api"), rx_as_api(body), name);
    check("rx frames", "commander", vector, vector.at("commander"), rx_as_commander(body), name);
  }
}

TEST(Parol6Conformance, JointConversionsMatchTheVendors) {
  const auto vectors = load_json_lines("joint_units.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    const int joint = vector.at("joint").get<int>();
    const std::string name = units_name(vector);
    if (vector.at("kind") == "to_steps") {
      const json robotd = to_steps(joint, vector.at("rad").get<double>());
      check("joint units", "api", vector, vector.at("api"), robotd, name);
      check("joint units", "commander", vector, vector.at("commander"),
            {{"position_steps", robotd.at("position_steps")}, {"speed_steps_s", robotd.at("speed_steps_s")}}, name);
    } else {
      const json robotd = to_rad(joint, vector.at("steps").get<std::int32_t>());
      check("joint units", "api", vector, vector.at("api"), robotd, name);
      check("joint units", "commander", vector, vector.at("commander"), robotd, name, kCommanderRadianTolerance);
    }
  }
}

TEST(Parol6Conformance, ReplyStreamsFrameAsTheApiParsesThem) {
  const auto vectors = load_json_lines("framing.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    const Bytes stream = hex_bytes(vector.at("stream").get<std::string>());
    const std::string name = vector.at("name");
    check("framing", "api", vector, vector.at("api"), framing_as_api(stream), name);
    check("framing", "commander", vector, vector.at("commander"), framing_as_commander(stream), name);
  }
}

}  // namespace
}  // namespace robotd::parol6::conformance
