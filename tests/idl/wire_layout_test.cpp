// robotd's samples on the wire have the layout rmw_cyclonedds writes: the 4-byte
// encapsulation header 00 01 00 00 (plain CDR, little endian), then an XCDR1 body with
// alignment counted from the body start; services put the 16-byte request header
// (client_guid, sequence_number) first. The bytes are taken raw from a reader with
// dds_takecdr, so nothing in robotd decodes them.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include "robotd/messages.hpp"
#include "wire/participant.hpp"
#include "wire/qos.hpp"
#include "wire/service.hpp"
#include "wire/topic_io.hpp"
#include "wire/topics.hpp"
#include "wire_test_support.hpp"

namespace robotd::wire {
namespace {

using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

/// Builds expected XCDR1 bytes by hand: encapsulation header, then little-endian values, each
/// aligned to its size relative to the body start (the byte after the header). Cyclone 0.10
/// pads the body to a multiple of 4 and counts the padding in the low bits of the header's
/// options (XTypes 1.3, 7.6.3.1.2); bytes() does the same.
class Xcdr1 {
 public:
  Xcdr1() : bytes_{0x00, 0x01, 0x00, 0x00} {}

  Xcdr1& u8(std::uint8_t value) { return raw(&value, 1); }
  Xcdr1& boolean(bool value) { return u8(value ? 1 : 0); }
  Xcdr1& i32(std::int32_t value) { return raw(&value, 4); }
  Xcdr1& u32(std::uint32_t value) { return raw(&value, 4); }
  Xcdr1& i64(std::int64_t value) { return raw(&value, 8); }
  Xcdr1& u64(std::uint64_t value) { return raw(&value, 8); }
  Xcdr1& f32(float value) { return raw(&value, 4); }
  Xcdr1& f64(double value) { return raw(&value, 8); }
  Xcdr1& string(const std::string& text) {
    u32(static_cast<std::uint32_t>(text.size() + 1));
    bytes_.insert(bytes_.end(), text.begin(), text.end());
    bytes_.push_back(0);
    return *this;
  }
  Xcdr1& count(std::size_t elements) { return u32(static_cast<std::uint32_t>(elements)); }

  Bytes bytes() const {
    Bytes padded = bytes_;
    const auto padding = static_cast<std::uint8_t>((4 - (padded.size() - 4) % 4) % 4);
    padded.insert(padded.end(), padding, 0);
    padded[3] = padding;
    return padded;
  }

 private:
  // The host is little endian (checked in the test below), so memcpy gives the LE bytes.
  Xcdr1& raw(const void* value, std::size_t size) {
    while ((bytes_.size() - 4) % size != 0) bytes_.push_back(0);
    const auto* first = static_cast<const std::uint8_t*>(value);
    bytes_.insert(bytes_.end(), first, first + size);
    return *this;
  }
  Bytes bytes_;
};

/// Takes one serialized sample from `reader` (waiting up to 5 s) exactly as it travels.
Bytes take_serialized(dds_entity_t reader, dds_sample_info_t* info_out = nullptr) {
  Bytes bytes;
  testing::wait_until([&] {
    ddsi_serdata* serdata = nullptr;
    dds_sample_info_t info{};
    if (dds_takecdr(reader, &serdata, 1, &info, DDS_ANY_STATE) != 1) return false;
    bytes.resize(ddsi_serdata_size(serdata));
    ddsi_serdata_to_ser(serdata, 0, bytes.size(), bytes.data());
    ddsi_serdata_unref(serdata);
    if (info_out != nullptr) *info_out = info;
    return true;
  });
  return bytes;
}

/// A reader that sees T's samples on `topic_name` as raw CDR.
template <class T>
struct RawReader {
  RawReader(const Participant& participant, std::string_view topic_name) {
    auto created = create_topic<T>(participant, topic_name);
    EXPECT_TRUE(created) << created.error().message;
    if (!created) return;
    topic = std::move(created.value());
    reader = Entity(dds_create_reader(participant.handle(), topic.get(), reliable_qos(10).get(), nullptr));
    EXPECT_GT(reader.get(), 0);
  }
  Entity topic;
  Entity reader;
};

std::string hex(const Bytes& bytes) {
  std::string out;
  char cell[4];
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::snprintf(cell, sizeof cell, "%02x%c", bytes[i], (i % 16 == 15) ? '\n' : ' ');
    out += cell;
  }
  return out;
}

::testing::AssertionResult same_bytes(const Bytes& expected, const Bytes& actual) {
  if (expected == actual) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "bytes differ\nexpected (" << expected.size() << " bytes):\n"
                                       << hex(expected) << "\nactual (" << actual.size() << " bytes):\n"
                                       << hex(actual);
}

TEST(WireLayout, HostIsLittleEndianAsTheEncapsulationHeaderClaims) {
  const std::uint32_t one = 1;
  std::uint8_t first = 0;
  std::memcpy(&first, &one, 1);
  EXPECT_EQ(first, 1) << "robotd writes CDR_LE; a big-endian host needs 00 00 headers in these tests";
}

TEST(WireLayout, JointStateIsPlainCdrLittleEndianLikeRmwCyclonedds) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto writer = TopicWriter<JointState>::create(participant.value(), kJointStatesTopic, reliable_qos(10).get());
  ASSERT_TRUE(writer) << writer.error().message;
  RawReader<JointState> raw(participant.value(), kJointStatesTopic);
  ASSERT_TRUE(testing::wait_until([&] { return writer.value().matched_readers() == 1; }));

  JointState state;
  state.header.stamp = Time{1, 2};
  state.header.frame_id = "base";
  state.name = {"a", "bc"};
  state.position = {1.0};
  state.effort = {2.0};
  ASSERT_TRUE(writer.value().write(state));

  // Written out by hand; offsets are relative to the body start (after the 4-byte header).
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x00,                             // encapsulation: CDR_LE, options 0
      0x01, 0x00, 0x00, 0x00,                             //  0: stamp.sec = 1
      0x02, 0x00, 0x00, 0x00,                             //  4: stamp.nanosec = 2
      0x05, 0x00, 0x00, 0x00, 'b',  'a',  's',  'e',  0,  //  8: frame_id, length 5 incl. NUL
      0x00, 0x00, 0x00,                                   // 17: pad to 4
      0x02, 0x00, 0x00, 0x00,                             // 20: name, 2 elements
      0x02, 0x00, 0x00, 0x00, 'a',  0,                    // 24: "a"
      0x00, 0x00,                                         // 30: pad to 4
      0x03, 0x00, 0x00, 0x00, 'b',  'c',  0,              // 32: "bc"
      0x00,                                               // 39: pad to 4
      0x01, 0x00, 0x00, 0x00,                             // 40: position, 1 element
      0x00, 0x00, 0x00, 0x00,                             // 44: pad to 8 for the double
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f,     // 48: 1.0
      0x00, 0x00, 0x00, 0x00,                             // 56: velocity, 0 elements
      0x01, 0x00, 0x00, 0x00,                             // 60: effort, 1 element (already 8-aligned)
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40,     // 64: 2.0
  };
  ASSERT_EQ(expected.size(), 76u);
  const Bytes actual = take_serialized(raw.reader.get());
  EXPECT_TRUE(same_bytes(expected, actual));

  // The hand-written vector and the test's CDR builder agree, so the builder can be trusted
  // for the longer messages below.
  Xcdr1 built;
  built.i32(1).u32(2).string("base").count(2).string("a").string("bc").count(1).f64(1.0).count(0).count(1).f64(2.0);
  EXPECT_TRUE(same_bytes(expected, built.bytes()));
}

TEST(WireLayout, SessionStatusNestsSessionInfoStructsInASequence) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto writer =
      TopicWriter<SessionStatus>::create(participant.value(), kSessionStatusTopic, transient_local_qos(1).get());
  ASSERT_TRUE(writer) << writer.error().message;
  RawReader<SessionStatus> raw(participant.value(), kSessionStatusTopic);
  ASSERT_TRUE(testing::wait_until([&] { return writer.value().matched_readers() == 1; }));

  SessionInfo session;
  session.uuid = "u1";
  session.node_name = "node";
  session.device = "arm";
  session.motor_ids = {3, 4};
  session.control_mode = ControlMode::kMixed;
  session.default_behavior = Behavior::kDamping;
  session.applied_behavior = Behavior::kKeep;
  session.timeout_ms = 500;
  session.time_left_ms = 250;
  session.granted_at = Time{7, 8};
  session.commands_accepted = 0x0102030405060708;
  session.policy_name = "walk";
  session.closed_loop = true;
  session.ticks_to_answer = 100;
  session.ticks_answered_in_time = 97;
  session.ticks_answered_late = 1;
  session.ticks_unanswered = 2;
  session.command_success_rate = 0.97F;
  session.min_command_success_rate = 0.9F;
  session.on_low_success_rate = LowRateAction::kFallback;
  session.success_rate_low = false;
  SessionStatus status;
  status.header = Header{Time{5, 6}, "f"};
  status.state = "active";
  status.policy_name = "p";
  status.policy_file_name = "";
  status.active_uuids = {"u1"};
  status.node_names = {"node"};
  status.motor_counts = {2};
  status.sessions = {session};
  status.surface = SurfaceCounters{9, 10, {ServiceCounters{"estop", 11, 12, 13}}};
  ASSERT_TRUE(writer.value().write(status));

  Xcdr1 expected;
  expected.i32(5).u32(6).string("f").string("active").string("p").string("");
  expected.count(1).string("u1").count(1).string("node").count(1).i32(2);
  expected.count(1);  // sessions
  expected.string("u1").string("node").string("arm").count(2).i32(3).i32(4);
  expected.i32(2).i32(1).i32(0).i32(500).i32(250).i32(7).u32(8);
  expected.u64(0x0102030405060708);                       // 8-aligned relative to the body start
  expected.string("walk").string("");                     // the session's policy_name, policy_file_name
  expected.boolean(true).u64(100).u64(97).u64(1).u64(2);  // closed loop: its ticks (8-aligned after the flag)
  expected.f32(0.97F).f32(0.9F).i32(1).boolean(false);    // rate, minimum, FALLBACK, not low
  expected.u64(9).u64(10).count(1).string("estop").u64(11).u64(12).u64(13);  // surface, after the PI Plus fields
  EXPECT_TRUE(same_bytes(expected.bytes(), take_serialized(raw.reader.get())));
}

TEST(WireLayout, JoyPutsItsNineteenFloatsFirstAndTheHeaderLastLikeThePiPlus) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  const std::string topic = data_topic(kDefaultJoyTopicName);
  auto writer = TopicWriter<Joy>::create(participant.value(), topic, reliable_qos(10).get());
  ASSERT_TRUE(writer) << writer.error().message;
  RawReader<Joy> raw(participant.value(), topic);
  ASSERT_TRUE(testing::wait_until([&] { return writer.value().matched_readers() == 1; }));

  Joy joy;
  joy.l_vertical = 1.0F;
  joy.rt = 0.5F;
  joy.a = 1.0F;
  joy.r = 1.0F;
  joy.header.stamp = Time{7, 8};
  joy.header.frame_id = "js0";
  ASSERT_TRUE(writer.value().write(joy));

  Xcdr1 expected;
  expected.f32(0).f32(1.0F).f32(0).f32(0).f32(0).f32(0.5F).f32(0).f32(0);  // sticks, triggers, d-pad
  expected.f32(1.0F);                                                      // a
  for (int button = 0; button < 9; ++button) expected.f32(0);              // b .. l
  expected.f32(1.0F);                                                      // r
  expected.i32(7).u32(8).string("js0");                                    // header, at offset 76
  EXPECT_TRUE(same_bytes(expected.bytes(), take_serialized(raw.reader.get())));
}

TEST(WireLayout, BodyIsPaddedToFourBytesAndTheHeaderCountsThePadding) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto writer = TopicWriter<ResetZeroResponse>::create(participant.value(), "rt/padding_probe", reliable_qos(1).get());
  ASSERT_TRUE(writer) << writer.error().message;
  RawReader<ResetZeroResponse> raw(participant.value(), "rt/padding_probe");
  ASSERT_TRUE(testing::wait_until([&] { return writer.value().matched_readers() == 1; }));
  ASSERT_TRUE(writer.value().write(ResetZeroResponse{true, "ok"}));

  // 27 body bytes (header 16, bool 1, pad 3, string 4 + 3) padded to 28; options = 1 pad byte.
  // rmw_cyclonedds pads the same way; both sides ignore the options field when reading XCDR1.
  const Bytes expected = {
      0x00, 0x01, 0x00, 0x01,                          // CDR_LE, options: 1 byte of padding
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  0: client_guid (a topic write leaves it 0)
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //  8: sequence_number
      0x01, 0x00, 0x00, 0x00,                          // 16: success, pad
      0x03, 0x00, 0x00, 0x00, 'o',  'k',  0x00,        // 20: message "ok"
      0x00,                                            // 27: padding to a multiple of 4
  };
  EXPECT_TRUE(same_bytes(expected, take_serialized(raw.reader.get())));
  Xcdr1 built;
  built.u64(0).i64(0).boolean(true).string("ok");
  EXPECT_TRUE(same_bytes(expected, built.bytes()));
}

RequestControlRequest sample_request() {
  RequestControlRequest request;
  request.node_name = "n";
  request.motor_ids = {1, 2};
  request.control_mode = ControlMode::kTorque;
  request.default_behavior = Behavior::kZeroTorque;
  request.timeout_ms = 250;
  request.default_kp = {1.5f};
  request.default_kd = {};
  request.device = "dev";
  return request;
}

Xcdr1 request_body(std::uint64_t guid, std::int64_t sequence) {
  Xcdr1 bytes;
  bytes.u64(guid).i64(sequence);
  bytes.string("n").count(2).i32(1).i32(2).i32(1).i32(2).i32(250).count(1).f32(1.5f).count(0).string("dev");
  bytes.string("").string("");  // policy_name, policy_file_name
  bytes.f32(0.0F).i32(0);       // min_command_success_rate, on_low_success_rate
  return bytes;
}

TEST(WireLayout, ServiceClientPutsItsGuidAndSequenceNumberFirst) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  RawReader<RequestControlRequest> requests(participant.value(), request_topic("layout_probe"));
  // A reply writer nobody uses: the client waits for one before it sends.
  auto replies = TopicWriter<RequestControlResponse>::create(participant.value(), reply_topic("layout_probe"),
                                                             service_qos().get());
  ASSERT_TRUE(replies) << replies.error().message;
  auto client =
      ServiceClient<RequestControlRequest, RequestControlResponse>::create(participant.value(), "layout_probe");
  ASSERT_TRUE(client) << client.error().message;

  for (std::int64_t sequence = 1; sequence <= 2; ++sequence) {
    const auto result = client.value()->call(sample_request(), 50ms);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, ErrorCode::kTimeout);

    dds_sample_info_t info{};
    const Bytes actual = take_serialized(requests.reader.get(), &info);
    ASSERT_GE(actual.size(), 20u);
    std::uint64_t guid = 0;
    std::int64_t wire_sequence = 0;
    std::memcpy(&guid, actual.data() + 4, 8);
    std::memcpy(&wire_sequence, actual.data() + 12, 8);
    // rmw_cyclonedds uses the request writer's instance handle as the client guid.
    EXPECT_EQ(guid, info.publication_handle);
    EXPECT_EQ(wire_sequence, sequence);
    EXPECT_TRUE(same_bytes(request_body(info.publication_handle, sequence).bytes(), actual));
  }
}

TEST(WireLayout, ServiceServerEchoesTheRequestHeaderInItsReply) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  auto server =
      ServiceServer<RequestControlRequest, RequestControlResponse>::create(participant.value(), "layout_probe");
  ASSERT_TRUE(server) << server.error().message;
  RawReader<RequestControlResponse> replies(participant.value(), reply_topic("layout_probe"));
  auto request_topic_entity = create_topic<RequestControlRequest>(participant.value(), request_topic("layout_probe"));
  ASSERT_TRUE(request_topic_entity);
  const Entity request_writer(dds_create_writer(participant.value().handle(), request_topic_entity.value().get(),
                                                service_qos().get(), nullptr));
  ASSERT_GT(request_writer.get(), 0);

  // A foreign client's request, header and all, as rmw_cyclonedds would send it.
  constexpr std::uint64_t kGuid = 0x8877665544332211;
  constexpr std::int64_t kSequence = 0x0000000700000009;
  const RequestControlRequest request = sample_request();
  Wire<RequestControlRequest>::C sample{};
  CArena arena;
  Wire<RequestControlRequest>::to_c(request, sample, arena);
  sample.client_guid = kGuid;
  sample.sequence_number = kSequence;
  ASSERT_EQ(dds_write(request_writer.get(), &sample), DDS_RETCODE_OK);

  std::optional<RequestId> received;
  ASSERT_TRUE(testing::wait_until([&] {
    server.value()->take_requests([&](const RequestId& id, RequestControlRequest&&) { received = id; });
    return received.has_value();
  }));
  EXPECT_EQ(received->client_guid, kGuid);
  EXPECT_EQ(received->sequence_number, kSequence);

  RequestControlResponse response;
  response.success = true;
  response.message = "ok";
  response.uuid = "u";
  response.motor_ids = {1, 2};
  response.applied_behavior = Behavior::kDamping;
  response.device = "arm";
  response.session_id = "id";
  ASSERT_TRUE(server.value()->reply(*received, response));

  Xcdr1 expected;
  expected.u64(kGuid).i64(kSequence).boolean(true).string("ok").string("u").count(2).i32(1).i32(2).i32(1).string("arm");
  expected.string("id");
  EXPECT_TRUE(same_bytes(expected.bytes(), take_serialized(replies.reader.get())));
}

}  // namespace
}  // namespace robotd::wire
