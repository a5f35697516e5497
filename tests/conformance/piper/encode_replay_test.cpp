// Every public send call of the SDK, replayed through robotd's codec with the same arguments:
// the same frames, byte for byte, or the same refusal.
#include <exception>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conformance_report.hpp"
#include "differences.hpp"
#include "sdk_calls.hpp"
#include "vector_file.hpp"

namespace robotd::piper::conformance {
namespace {

using nlohmann::json;
using robotd::conformance::hex_text;
using robotd::conformance::load_json_lines;
using robotd::conformance::record;

json frames_json(const std::vector<CanMessage>& frames) {
  json out = json::array();
  for (const CanMessage& frame : frames) {
    out.push_back(
        {{"id", frame.id}, {"extended", frame.extended}, {"data", hex_text(frame.data.data(), frame.length)}});
  }
  return out;
}

/// robotd's result for the call: its frames, or that it refused (and why), or that it has no
/// such call.
json robotd_result(const json& vector) {
  try {
    return {{"frames", frames_json(robotd_frames(vector.at("call").get<std::string>(), vector.at("args")))}};
  } catch (const NotOffered& e) {
    return {{"not_offered", e.what()}};
  } catch (const std::exception&) {  // robotd's codec refused the arguments
    return {{"refused", true}};
  }
}

TEST(EncodeReplay, EverySdkCallEncodesAsTheSdkDoes) {
  const std::vector<json> vectors = load_json_lines("encodes.jsonl");
  ASSERT_FALSE(vectors.empty());
  for (const json& vector : vectors) {
    const json key{{"call", vector.at("call")}, {"args", vector.at("args")}};
    const bool refused = vector.contains("rejected");
    const json sdk = refused ? json{{"refused", true}} : json{{"frames", vector.at("frames")}};
    const char* group = refused ? "rejection" : "encode";
    record(group, judge(group, key, sdk, robotd_result(vector)));
  }
}

}  // namespace
}  // namespace robotd::piper::conformance
