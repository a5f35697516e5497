// robotd's config: the shipped file is valid, and every problem is reported with the key path
// that caused it and what was expected, all problems at once.
#include "config/config.hpp"

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace robotd::config {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

// The smallest valid config: one simulated device, DDS defaults.
json minimal_config() { return json{{"devices", json::array({json{{"name", "arm"}, {"driver", "sim"}}})}}; }

Result<Config> parse(const json& document) { return parse_config(document.dump(), "test.json"); }

// The error message for an invalid document; fails the test if the document is accepted.
std::string errors_of(const json& document) {
  const Result<Config> result = parse(document);
  if (result.ok()) {
    ADD_FAILURE() << "config was accepted: " << document.dump();
    return "";
  }
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
  return result.error().message;
}

std::string device_errors(const std::string& key, const json& value) {
  json document = minimal_config();
  document["devices"][0][key] = value;
  return errors_of(document);
}

std::size_t count_lines_starting_with(const std::string& text, const std::string& prefix) {
  std::size_t count = 0;
  for (std::size_t at = text.find("\n  "); at != std::string::npos; at = text.find("\n  ", at + 1)) {
    if (text.compare(at + 3, prefix.size(), prefix) == 0) ++count;
  }
  return count;
}

TEST(Config, ShippedConfigParsesWithItsSimulatedDevicesOnLoopback) {
  const Result<Config> config = load_config_file(ROBOTD_SOURCE_DIR "/config/robotd.json");
  ASSERT_TRUE(config.ok()) << config.error().message;
  ASSERT_EQ(config.value().devices.size(), 7u);
  EXPECT_EQ(config.value().devices[0].name, "arm");
  EXPECT_EQ(config.value().devices[1].name, "humanoid");
  EXPECT_EQ(config.value().devices[0].driver, "sim");
  EXPECT_EQ(config.value().devices[1].driver, "sim");
  EXPECT_EQ(config.value().devices[2].driver, "piper");
  EXPECT_FALSE(config.value().devices[2].required) << "the demo runs without the PiPER simulator too";
  EXPECT_EQ(config.value().devices[3].driver, "parol6");
  EXPECT_FALSE(config.value().devices[3].required);
  EXPECT_EQ(config.value().devices[4].driver, "realman");
  EXPECT_EQ(config.value().devices[5].driver, "xarm");
  EXPECT_FALSE(config.value().devices[5].required);
  EXPECT_EQ(config.value().devices[6].driver, "hightorque");
  EXPECT_FALSE(config.value().devices[6].required);
  EXPECT_FALSE(config.value().devices[4].required);
  EXPECT_EQ(config.value().dds.network_interface, "127.0.0.1");
  EXPECT_FALSE(config.value().dds.multicast);
  EXPECT_EQ(config.value().devices[0].params["joint_count"], 6);
}

TEST(Config, AbsentKeysTakeTheDocumentedDefaults) {
  const Result<Config> config = parse(minimal_config());
  ASSERT_TRUE(config.ok()) << config.error().message;
  const DeviceConfig& device = config.value().devices.at(0);
  EXPECT_EQ(device.path, "devices[0]");
  EXPECT_TRUE(device.required);
  EXPECT_EQ(device.reconnect_interval_ms, 1000);
  EXPECT_EQ(device.reconnect_max_interval_ms, 5000);
  EXPECT_EQ(device.rate_hz, 1000);
  EXPECT_EQ(device.rt_priority, 80);
  EXPECT_EQ(device.cpu, -1);
  EXPECT_EQ(device.realtime, rt::RealtimePolicy::kPrefer);
  EXPECT_EQ(device.limit_policy, control::LimitPolicy::kReject);
  EXPECT_EQ(device.safe_behavior, Behavior::kDamping);
  EXPECT_EQ(device.shutdown_behavior, Behavior::kDamping);
  EXPECT_TRUE(device.params.is_object());
  EXPECT_EQ(config.value().daemon.node_name, "robotd");
  EXPECT_EQ(config.value().origin, "test.json");
}

TEST(Config, ExplicitValuesAreRead) {
  json document = minimal_config();
  document["devices"][0]["rate_hz"] = 500;
  document["devices"][0]["rt_priority"] = 90;
  document["devices"][0]["realtime"] = "require";
  document["devices"][0]["limit_policy"] = "clamp";
  document["devices"][0]["safe_behavior"] = "ZERO_TORQUE";
  document["devices"][0]["shutdown_behavior"] = "KEEP";
  document["devices"][0]["params"] = json{{"joint_count", 3}};
  const Result<Config> config = parse(document);
  ASSERT_TRUE(config.ok()) << config.error().message;
  const DeviceConfig& device = config.value().devices.at(0);
  EXPECT_EQ(device.rate_hz, 500);
  EXPECT_EQ(device.rt_priority, 90);
  EXPECT_EQ(device.realtime, rt::RealtimePolicy::kRequire);
  EXPECT_EQ(device.limit_policy, control::LimitPolicy::kClamp);
  EXPECT_EQ(device.safe_behavior, Behavior::kZeroTorque);
  EXPECT_EQ(device.shutdown_behavior, Behavior::kKeep);
  EXPECT_EQ(device.params["joint_count"], 3);
}

TEST(Config, CpuWakeUpLatencyRequestDefaultsToZeroAndMinusOneTurnsItOff) {
  EXPECT_EQ(parse(minimal_config()).value().daemon.cpu_dma_latency_us, 0);
  json document = minimal_config();
  document["daemon"]["cpu_dma_latency_us"] = -1;
  EXPECT_EQ(parse(document).value().daemon.cpu_dma_latency_us, -1);
  document["daemon"]["cpu_dma_latency_us"] = -5;
  EXPECT_NE(errors_of(document).find("daemon.cpu_dma_latency_us: expected an integer in -1..1000000, got -5"),
            std::string::npos);
}

TEST(Config, DdsReceiveThreadPriorityDefaultsBelowTheLoopsAndZeroTurnsItOff) {
  EXPECT_EQ(parse(minimal_config()).value().dds.receive_thread_priority, kDefaultReceiveThreadPriority);
  json document = minimal_config();
  document["dds"]["receive_thread_priority"] = 0;
  EXPECT_EQ(parse(document).value().dds.receive_thread_priority, 0);
  document["dds"]["receive_thread_priority"] = 99;
  EXPECT_THAT(errors_of(document), HasSubstr("dds.receive_thread_priority: expected an integer in 0..98, got 99"));
}

TEST(Config, ALoopMustOutrankTheDdsReceiveThread) {
  json document = minimal_config();
  document["dds"]["receive_thread_priority"] = 40;
  document["devices"][0]["rt_priority"] = 40;
  EXPECT_THAT(errors_of(document), HasSubstr("devices[0].rt_priority: must be above dds.receive_thread_priority (40)"));
  document["devices"][0]["realtime"] = "off";
  EXPECT_TRUE(parse(document).ok()) << "a loop that is not real-time has no priority to compare";
}

TEST(Config, LineAndBlockCommentsAreAllowed) {
  const std::string text = R"(
    // robotd test config
    {
      /* one device */
      "devices": [{"name": "arm", "driver": "sim"}]  // trailing comment
    })";
  const Result<Config> config = parse_config(text, "commented.json");
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(config.value().devices.at(0).name, "arm");
}

TEST(Config, JointLimitOverridesAreReadPerJointWithTheirPath) {
  json document = minimal_config();
  document["devices"][0]["joint_limits"] = json{{"joint2", json{{"velocity_max_rad_s", 0.5}, {"kp_max", 80}}}};
  const Result<Config> config = parse(document);
  ASSERT_TRUE(config.ok()) << config.error().message;
  const auto& overrides = config.value().devices.at(0).joint_limits;
  ASSERT_EQ(overrides.size(), 1u);
  EXPECT_EQ(overrides[0].joint, "joint2");
  EXPECT_EQ(overrides[0].path, "devices[0].joint_limits.joint2");
  EXPECT_EQ(overrides[0].velocity_max_rad_s, 0.5);
  EXPECT_EQ(overrides[0].kp_max, 80.0);
  EXPECT_FALSE(overrides[0].position_min_rad.has_value());
}

TEST(Config, UnknownRootKeyIsNamedWithTheKeysThatExist) {
  json document = minimal_config();
  document["devics"] = json::array();
  const std::string errors = errors_of(document);
  EXPECT_THAT(errors, HasSubstr("devics: unknown key"));
  EXPECT_THAT(errors, HasSubstr("daemon, dds, devices"));
}

TEST(Config, UnknownDaemonKeyIsNamedWithItsPath) {
  json document = minimal_config();
  document["daemon"] = json{{"nodename", "x"}};
  EXPECT_THAT(errors_of(document), HasSubstr("daemon.nodename: unknown key"));
}

TEST(Config, UnknownDdsKeyIsNamedWithItsPath) {
  json document = minimal_config();
  document["dds"] = json{{"multicats", true}};
  EXPECT_THAT(errors_of(document), HasSubstr("dds.multicats: unknown key"));
}

TEST(Config, UnknownDeviceKeyIsNamedWithItsPath) {
  EXPECT_THAT(device_errors("rate", 100), HasSubstr("devices[0].rate: unknown key"));
}

TEST(Config, UnknownJointLimitKeyIsNamedWithItsPath) {
  const std::string errors = device_errors("joint_limits", json{{"joint2", json{{"velocity_max", 1.0}}}});
  EXPECT_THAT(errors, HasSubstr("devices[0].joint_limits.joint2.velocity_max: unknown key"));
}

TEST(Config, WrongTypeNamesWhatWasExpectedAndWhatWasGiven) {
  EXPECT_THAT(device_errors("rate_hz", "fast"),
              HasSubstr("devices[0].rate_hz: expected an integer in 1..10000, got \"fast\""));
}

TEST(Config, WrongTypeForASectionIsReported) {
  json document = minimal_config();
  document["dds"] = 5;
  EXPECT_THAT(errors_of(document), HasSubstr("dds: expected an object, got 5"));
}

TEST(Config, RateOfZeroIsOutOfRange) {
  EXPECT_THAT(device_errors("rate_hz", 0), HasSubstr("devices[0].rate_hz: expected an integer in 1..10000, got 0"));
}

TEST(Config, RtPriorityAbove99IsOutOfRange) {
  EXPECT_THAT(device_errors("rt_priority", 100),
              HasSubstr("devices[0].rt_priority: expected an integer in 1..99, got 100"));
}

TEST(Config, CpuBeyondThisMachineIsOutOfRange) {
  const long cpus = sysconf(_SC_NPROCESSORS_CONF);
  ASSERT_GT(cpus, 0);
  EXPECT_THAT(device_errors("cpu", cpus), HasSubstr("devices[0].cpu: expected an integer in -1.." +
                                                    std::to_string(cpus - 1) + ", got " + std::to_string(cpus)));
  json document = minimal_config();
  document["devices"][0]["cpu"] = cpus - 1;
  const Result<Config> last_cpu = parse(document);
  ASSERT_TRUE(last_cpu.ok()) << last_cpu.error().message;
  EXPECT_EQ(last_cpu.value().devices[0].cpu, cpus - 1);
}

TEST(Config, UnknownRealtimePolicyListsTheChoices) {
  EXPECT_THAT(device_errors("realtime", "always"),
              HasSubstr("devices[0].realtime: expected one of \"require\", \"prefer\", \"off\", got \"always\""));
}

TEST(Config, UnknownLimitPolicyListsTheChoices) {
  EXPECT_THAT(device_errors("limit_policy", "saturate"),
              HasSubstr("devices[0].limit_policy: expected one of \"reject\", \"clamp\", got \"saturate\""));
}

TEST(Config, UnknownSafeBehaviorListsTheChoices) {
  EXPECT_THAT(device_errors("safe_behavior", "BRAKE"),
              HasSubstr("devices[0].safe_behavior: expected one of \"KEEP\", \"DAMPING\", \"ZERO_TORQUE\", got "
                        "\"BRAKE\""));
}

TEST(Config, DuplicateDeviceNamesAreRefused) {
  json document = minimal_config();
  document["devices"].push_back(json{{"name", "arm"}, {"driver", "sim"}});
  EXPECT_THAT(errors_of(document), HasSubstr("devices[1].name: duplicate device name \"arm\""));
}

TEST(Config, DeviceWithoutNameIsRefused) {
  json document = minimal_config();
  document["devices"][0].erase("name");
  EXPECT_THAT(errors_of(document), HasSubstr("devices[0].name: missing; expected a device name"));
}

TEST(Config, DeviceWithoutDriverIsRefused) {
  json document = minimal_config();
  document["devices"][0].erase("driver");
  EXPECT_THAT(errors_of(document), HasSubstr("devices[0].driver: missing; expected a driver plugin name"));
}

TEST(Config, DeviceNameMustBeAnIdentifier) {
  EXPECT_THAT(device_errors("name", "left arm"),
              HasSubstr("devices[0].name: expected a name of letters, digits and _ starting with a letter, got "
                        "\"left arm\""));
}

// 63 characters at most: the longest device name robotd takes in a request (robotd/limits.hpp).
TEST(Config, DeviceNameFitsWhatClientsMaySendAsADevice) {
  EXPECT_THAT(device_errors("name", "a" + std::string(63, '1')), HasSubstr("devices[0].name: expected a name of"));
  json document = minimal_config();
  document["devices"][0]["name"] = "a" + std::string(62, '1');
  EXPECT_TRUE(parse(document).ok());
}

TEST(Config, EmptyDevicesArrayIsRefused) {
  json document = minimal_config();
  document["devices"] = json::array();
  EXPECT_THAT(errors_of(document), HasSubstr("devices: must list at least one device"));
}

TEST(Config, MissingDevicesIsRefused) {
  EXPECT_THAT(errors_of(json::object()), HasSubstr("devices: missing; expected an array with at least one device"));
}

TEST(Config, NoMulticastAndNoPeersIsRefused) {
  json document = minimal_config();
  document["dds"] = json{{"multicast", false}, {"peers", json::array()}};
  EXPECT_THAT(errors_of(document), HasSubstr("dds.peers: must list at least one peer when multicast is false"));
}

TEST(Config, MulticastWithoutPeersIsAccepted) {
  json document = minimal_config();
  document["dds"] = json{{"multicast", true}, {"peers", json::array()}};
  const Result<Config> config = parse(document);
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_TRUE(config.value().dds.multicast);
  EXPECT_TRUE(config.value().dds.peers.empty());
}

TEST(Config, DdsSecurityNamesEveryKeyAtFault) {
  json document = minimal_config();
  document["dds"] = json{{"security", json{{"identity_ca", "/nonexistent/identity_ca.pem"}, {"password", "x"}}}};
  const std::string errors = errors_of(document);
  EXPECT_THAT(errors, HasSubstr("dds.security.identity_ca: no such file '/nonexistent/identity_ca.pem'; expected the "
                                "identity CA's certificate (PEM)"));
  EXPECT_THAT(errors, HasSubstr("dds.security.permissions: not set; expected this participant's permissions document"));
  EXPECT_THAT(errors, HasSubstr("dds.security.password: unknown key"));
  EXPECT_EQ(count_lines_starting_with(errors, "dds.security."), 7u);
}

TEST(Config, DdsSecurityWithItsSixFilesTurnsItOn) {
  std::string directory = "/tmp/robotd-test-config-security-XXXXXX";
  ASSERT_NE(mkdtemp(directory.data()), nullptr);
  const json contents{{"identity_ca", "-----BEGIN CERTIFICATE-----"},
                      {"identity_certificate", "-----BEGIN CERTIFICATE-----"},
                      {"private_key", "-----BEGIN PRIVATE KEY-----"},
                      {"permissions_ca", "-----BEGIN CERTIFICATE-----"},
                      {"governance", "Content-Type: application/x-pkcs7-signature"},
                      {"permissions", "Content-Type: application/x-pkcs7-signature"}};
  json security = json::object();
  for (const auto& [key, text] : contents.items()) {
    security[key] = (std::filesystem::path(directory) / key).string();
    std::ofstream(security[key].get<std::string>()) << text.get<std::string>() << "\n";
  }
  json document = minimal_config();
  document["dds"] = json{{"security", security}};
  const Result<Config> config = parse(document);
  std::filesystem::remove_all(directory);
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_TRUE(config.value().dds.security.enabled());
  EXPECT_EQ(config.value().dds.security.private_key, directory + "/private_key");
  EXPECT_EQ(config.value().dds.security.governance, directory + "/governance");
}

TEST(Config, DdsSecurityIsOffWithoutItsObject) {
  const Result<Config> config = parse(minimal_config());
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_FALSE(config.value().dds.security.enabled());
}

TEST(Config, ParamsMustBeAnObject) {
  EXPECT_THAT(device_errors("params", json::array({1, 2})),
              HasSubstr("devices[0].params: expected an object, got [1,2]"));
}

TEST(Config, JointLimitMinimumMustBeBelowMaximum) {
  const json equal{{"joint1", json{{"position_min_rad", 1.0}, {"position_max_rad", 1.0}}}};
  EXPECT_THAT(device_errors("joint_limits", equal),
              HasSubstr("devices[0].joint_limits.joint1.position_min_rad: must be below position_max_rad"));
  const json inverted{{"joint1", json{{"position_min_rad", 2.0}, {"position_max_rad", -2.0}}}};
  EXPECT_THAT(device_errors("joint_limits", inverted),
              HasSubstr("devices[0].joint_limits.joint1.position_min_rad: must be below position_max_rad"));
}

TEST(Config, EveryProblemIsReportedAtOnceOnItsOwnLine) {
  json document = minimal_config();
  document["colour"] = "blue";
  document["devices"][0]["rate_hz"] = 0;
  document["devices"][0]["rt_priority"] = 100;
  document["devices"].push_back(json{{"name", "arm"}});
  const std::string errors = errors_of(document);
  EXPECT_THAT(errors, HasSubstr("invalid config test.json:"));
  EXPECT_EQ(count_lines_starting_with(errors, "colour:"), 1u) << errors;
  EXPECT_EQ(count_lines_starting_with(errors, "devices[0].rate_hz:"), 1u) << errors;
  EXPECT_EQ(count_lines_starting_with(errors, "devices[0].rt_priority:"), 1u) << errors;
  EXPECT_EQ(count_lines_starting_with(errors, "devices[1].driver:"), 1u) << errors;
  EXPECT_EQ(count_lines_starting_with(errors, "devices[1].name:"), 1u) << errors;
}

TEST(Config, InvalidJsonReportsTheOriginAndTheParsersPosition) {
  const std::string text = "{\n  \"devices\": [\n    {\"name\": \"arm\",, \"driver\": \"sim\"}\n  ]\n}\n";
  const Result<Config> config = parse_config(text, "broken.json");
  ASSERT_FALSE(config.ok());
  EXPECT_EQ(config.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(config.error().message, HasSubstr("broken.json: invalid JSON"));
  EXPECT_THAT(config.error().message, HasSubstr("line 3, column"));
}

TEST(Config, MissingFileIsReportedWithItsPath) {
  const Result<Config> config = load_config_file("/nonexistent/robotd-test/robotd.json");
  ASSERT_FALSE(config.ok());
  EXPECT_EQ(config.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(config.error().message, HasSubstr("cannot read config file '/nonexistent/robotd-test/robotd.json'"));
}

}  // namespace
}  // namespace robotd::config
