// robotd's DDS surface bounds what a client sends (docs/dds-interface.md, "Limits"): a string or
// list beyond its limit is refused naming the field, its length and the limit, and counted;
// nothing of it is granted, published or logged whole; what the DDS layer itself reports about
// malformed samples reaches the log rate-limited; a command that names no session and no known
// device is counted where robotctl status shows it.
#include <chrono>
#include <sstream>
#include <string>
#include <thread>

#include <dds/dds.h>
#include <gtest/gtest.h>

#include "robotd_fixture.hpp"
#include "robotd_msgs.h"
#include "wire/entity.hpp"
#include "wire/participant.hpp"
#include "wire/qos.hpp"
#include "wire/topics.hpp"

#if !defined(ROBOTCTL_BINARY)
#error "ROBOTCTL_BINARY must point at the robotctl executable under test"
#endif

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr std::size_t kMiB = 1U << 20U;

const ServiceCounters* service(const SessionStatus& status, const std::string& name) {
  for (const auto& counters : status.surface.services) {
    if (counters.service == name) return &counters;
  }
  return nullptr;
}

std::size_t longest_line(const std::string& text) {
  std::istringstream lines(text);
  std::size_t longest = 0;
  for (std::string line; std::getline(lines, line);) longest = std::max(longest, line.size());
  return longest;
}

std::size_t count_lines_containing(const std::string& text, const std::string& part) {
  std::istringstream lines(text);
  std::size_t count = 0;
  for (std::string line; std::getline(lines, line);) count += line.find(part) != std::string::npos ? 1U : 0U;
  return count;
}

class SurfaceLimitsTest : public RobotdTest {
 protected:
  /// The next /session_status whose surface counters satisfy `done` (or the last one seen).
  SessionStatus wait_for_surface(const std::function<bool(const SurfaceCounters&)>& done) {
    const auto deadline = std::chrono::steady_clock::now() + 5s;
    SessionStatus status;
    while (std::chrono::steady_clock::now() < deadline) {
      auto next = client().session_status(2s);
      if (next) status = next.value();
      if (done(status.surface)) break;
      std::this_thread::sleep_for(50ms);
    }
    return status;
  }
};

TEST_F(SurfaceLimitsTest, OversizedRequestFieldsAreRefusedNamingFieldLengthAndLimitAndCounted) {
  start_robotd();
  // A 1 MiB node name: refused, not granted, so /session_status never carries it.
  auto big_name = Client::connect(client_options(domain_.id(), std::string(kMiB, 'n')));
  ASSERT_TRUE(big_name) << big_name.error().message;
  SessionRequest request;
  request.device = "arm";
  auto refused = big_name.value().request_control(request);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kRefused);
  EXPECT_NE(refused.error().message.find("node_name is 1048576 bytes long; the limit is 255 bytes"), std::string::npos)
      << refused.error().message.substr(0, 300);

  // Every other service holds its fields to their limits too.
  auto call = client().device_call("arm", "state", "{\"pad\": \"" + std::string(70'000, 'x') + "\"}");
  ASSERT_FALSE(call);
  EXPECT_NE(call.error().message.find("args_json is 70011 bytes long; the limit is 65536 bytes"), std::string::npos)
      << call.error().message.substr(0, 300);
  auto motors = client().available_motors(std::string(64, 'd'));
  ASSERT_FALSE(motors);
  EXPECT_NE(motors.error().message.find("device is 64 bytes long; the limit is 63 bytes"), std::string::npos)
      << motors.error().message;
  auto zeroing = client().reset_zero("arm", std::vector<std::int32_t>(65, 0));
  ASSERT_FALSE(zeroing);
  EXPECT_NE(zeroing.error().message.find("motor_ids is 65 entries long; the limit is 64 entries"), std::string::npos)
      << zeroing.error().message;

  // An e-stop is never refused for its words: an over-long reason is cut, the e-stop engages.
  auto estop = client().estop("arm", std::string(300, 'r'));
  ASSERT_TRUE(estop) << estop.error().message;
  EXPECT_NE(estop.value().message.find("reason is 300 bytes long; the limit is 255 bytes"), std::string::npos)
      << estop.value().message;
  EXPECT_TRUE(device_status().estop_engaged);
  ASSERT_TRUE(client().reset_estop("arm"));

  const SessionStatus status = wait_for_surface([](const SurfaceCounters& surface) {
    for (const auto& counters : surface.services) {
      if (counters.service == "estop" && counters.oversized == 1) return true;
    }
    return false;
  });
  EXPECT_TRUE(status.sessions.empty());
  EXPECT_TRUE(status.node_names.empty());
  for (const auto& [name, oversized, refusals] :
       {std::tuple{"request_control", 1U, 1U}, std::tuple{"device_call", 1U, 1U},
        std::tuple{"get_available_motors", 1U, 1U}, std::tuple{"reset_zero", 1U, 1U}, std::tuple{"estop", 1U, 0U}}) {
    const ServiceCounters* counters = service(status, name);
    ASSERT_NE(counters, nullptr) << name;
    EXPECT_EQ(counters->oversized, oversized) << name;
    EXPECT_EQ(counters->refused, refusals) << name;
    EXPECT_GE(counters->requests, 1U) << name;
  }

  // robotd logged what was refused, bounded: no line carries the megabyte.
  const std::string log = robotd_->log();
  EXPECT_NE(log.find("node_name is 1048576 bytes long"), std::string::npos) << log;
  EXPECT_LT(longest_line(log), 1000U);
  EXPECT_EQ(log.find(std::string(300, 'n')), std::string::npos);
}

TEST_F(SurfaceLimitsTest, OversizedCommandsAreRejectedAsMalformedAndLoggedBounded) {
  start_robotd();
  SessionRequest request;
  request.device = "arm";
  request.timeout = 10s;
  auto session = client().request_control(request);
  ASSERT_TRUE(session) << session.error().message;

  ControlCommand too_many = {};
  too_many.uuid = session.value().uuid();
  too_many.device = "arm";
  too_many.motor_ids = std::vector<std::int32_t>(65, 0);
  ControlCommand long_frame = too_many;
  long_frame.motor_ids = {0};
  long_frame.positions = {0.2F};
  long_frame.header.frame_id = std::string(kMiB, 'f');
  const CommandCounters before = device_status().commands;
  ASSERT_TRUE(client().publish(too_many));
  ASSERT_TRUE(client().publish(long_frame));
  CommandCounters after = device_status().commands;
  for (int i = 0; i < 100 && after.received < before.received + 2; ++i) after = device_status().commands;
  EXPECT_EQ(after.rejected_malformed, before.rejected_malformed + 2);
  EXPECT_EQ(after.accepted, before.accepted);
  for (const auto& joint : sim_joints()) EXPECT_EQ(joint["command"], "none") << joint.dump();

  const std::string log = robotd_->log();
  EXPECT_NE(log.find("motor_ids is 65 entries long; the limit is 64 entries"), std::string::npos) << log;
  EXPECT_LT(longest_line(log), 1000U);
}

// A command that names no active session and a device robotd does not have cannot be counted
// against any device: robotd counts it in SessionStatus.surface, and robotctl status shows it.
TEST_F(SurfaceLimitsTest, CommandsNamingNoSessionAndNoKnownDeviceAreCountedAndShownByRobotctlStatus) {
  start_robotd();
  const CommandCounters before = device_status().commands;
  ControlCommand stray;
  stray.uuid = "00000000-0000-4000-8000-000000000000";
  stray.device = std::string(kMiB, 'x');
  stray.motor_ids = {0};
  stray.positions = {0.5F};
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(client().publish(stray));
  stray.device = "no_such_device";
  ASSERT_TRUE(client().publish(stray));

  const SessionStatus status = wait_for_surface([](const SurfaceCounters& s) { return s.commands_unattributed >= 4; });
  EXPECT_EQ(status.surface.commands_unattributed, 4U);
  EXPECT_EQ(device_status().commands.received, before.received) << "the arm's counters cannot claim them";

  ChildProcess robotctl(ROBOTCTL_BINARY, {"--domain", std::to_string(domain_.id()), "status"});
  std::string printed;
  while (auto line = robotctl.read_line(10s)) printed += *line + "\n";
  EXPECT_NE(printed.find("4 commands named no active session and no known device"), std::string::npos) << printed;

  // Logged at most once a second, each line bounded: never the megabyte.
  const std::string log = robotd_->log();
  EXPECT_EQ(count_lines_containing(log, "names no known device"), 1U) << log;
  EXPECT_LT(longest_line(log), 1000U);
}

// Truncated requests fail to deserialise inside the DDS layer, which says so once per sample.
// robotd routes those messages into its log, counted, a line a second per kind at most.
TEST_F(SurfaceLimitsTest, ABurstOfTruncatedRequestsCostsAFewLogLinesAndIsCounted) {
  start_robotd();
  wire::DdsSettings settings;
  settings.domain_id = domain_.id();
  auto participant = wire::Participant::create(settings);
  ASSERT_TRUE(participant) << participant.error().message;
  // A ListDevices request under RequestControl's type name: its bytes end where a RequestControl
  // request's motor_ids should begin. Without type information, DDS matches the two by name.
  const dds_topic_descriptor_t& shorter = robotd_msgs_srv_dds__ListDevices_Request__desc;
  const dds_topic_descriptor_t truncated{shorter.m_size,
                                         shorter.m_align,
                                         shorter.m_flagset & ~DDS_TOPIC_XTYPES_METADATA,
                                         shorter.m_nkeys,
                                         "robotd_msgs::srv::dds_::RequestControl_Request_",
                                         shorter.m_keys,
                                         shorter.m_nops,
                                         shorter.m_ops,
                                         shorter.m_meta,
                                         {nullptr, 0},
                                         {nullptr, 0},
                                         shorter.restrict_data_representation};
  const wire::Entity topic(dds_create_topic(participant.value().handle(), &truncated,
                                            wire::request_topic("request_control").c_str(), nullptr, nullptr));
  ASSERT_GT(topic.get(), 0) << dds_strretcode(topic.get());
  const auto qos = wire::service_qos();
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_ALL, 0);  // nothing of the burst lost on the way
  const wire::Entity writer(dds_create_writer(participant.value().handle(), topic.get(), qos.get(), nullptr));
  ASSERT_GT(writer.get(), 0);
  const auto write = [&writer](std::int64_t sequence) {
    robotd_msgs_srv_dds__ListDevices_Request_ sample{};
    sample.client_guid = 7;
    sample.sequence_number = sequence;
    sample.node_name = const_cast<char*>("truncated");
    return dds_write(writer.get(), &sample) == DDS_RETCODE_OK;
  };
  // The first one counted tells that robotd's reader has matched this writer.
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  dds_publication_matched_status_t matched{};
  while (matched.current_count == 0 && std::chrono::steady_clock::now() < deadline) {
    dds_get_publication_matched_status(writer.get(), &matched);
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_GT(matched.current_count, 0U) << "robotd's request reader did not match";
  ASSERT_TRUE(write(0));
  const std::uint64_t before =
      wait_for_surface([](const SurfaceCounters& s) { return s.dds_log_messages >= 1; }).surface.dds_log_messages;
  ASSERT_GE(before, 1U) << "robotd never saw the first truncated request";

  constexpr int kBurst = 2000;
  for (int i = 1; i <= kBurst; ++i) ASSERT_TRUE(write(i));
  const SessionStatus status = wait_for_surface(
      [before](const SurfaceCounters& s) { return s.dds_log_messages >= before + static_cast<unsigned>(kBurst); });
  EXPECT_GE(status.surface.dds_log_messages, before + static_cast<unsigned>(kBurst));

  const std::string log = robotd_->log();
  const std::size_t dds_lines = count_lines_containing(log, "deserialization");
  std::printf("[ measured ] %d truncated requests after the first: %llu DDS layer messages counted, %zu log lines\n",
              kBurst, static_cast<unsigned long long>(status.surface.dds_log_messages - before), dds_lines);
  EXPECT_GE(dds_lines, 1U) << log;
  EXPECT_LE(dds_lines, 20U) << log;
  EXPECT_NE(log.find("DDS: data(application"), std::string::npos) << log;
  EXPECT_LT(longest_line(log), 1000U);
  // robotd still answers.
  EXPECT_TRUE(client().list_devices());
}

}  // namespace
}  // namespace robotd::testing
