// Every Wire<T> carries every field: a value with non-default data in each field survives
// to_c → from_c unchanged, and survives a real DDS write → read (Cyclone's serializer, driven
// by the idlc descriptor) unchanged too.
#include <chrono>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "robotd/messages.hpp"
#include "wire/participant.hpp"
#include "wire/qos.hpp"
#include "wire/topic_io.hpp"
#include "wire/wire_types.hpp"
#include "wire_test_support.hpp"

namespace robotd {

// Field-by-field equality, so a failure names a type and the tuples show which field differs.
// Each list must name every field of its struct.
inline auto fields(const Time& m) { return std::tie(m.sec, m.nanosec); }
inline auto fields(const Header& m) { return std::tie(m.stamp.sec, m.stamp.nanosec, m.frame_id); }
inline auto fields(const Vector3& m) { return std::tie(m.x, m.y, m.z); }
inline auto fields(const Quaternion& m) { return std::tie(m.x, m.y, m.z, m.w); }
inline auto fields(const KeyValue& m) { return std::tie(m.key, m.value); }
inline auto fields(const SessionInfo& m) {
  return std::tie(m.uuid, m.node_name, m.device, m.motor_ids, m.control_mode, m.default_behavior, m.applied_behavior,
                  m.timeout_ms, m.time_left_ms, m.granted_at.sec, m.granted_at.nanosec, m.commands_accepted,
                  m.policy_name, m.policy_file_name, m.closed_loop, m.ticks_to_answer, m.ticks_answered_in_time,
                  m.ticks_answered_late, m.ticks_unanswered, m.command_success_rate, m.min_command_success_rate,
                  m.on_low_success_rate, m.success_rate_low);
}
inline auto fields(const LoopStatistics& m) {
  return std::tie(m.rate_hz, m.realtime, m.ticks, m.overruns, m.window_ticks, m.period_p50_us, m.period_p99_us,
                  m.period_max_us, m.wake_latency_p50_us, m.wake_latency_p99_us, m.wake_latency_max_us,
                  m.execution_p50_us, m.execution_p99_us, m.execution_max_us, m.rt_heap_allocations,
                  m.tick_deadline_steady_ns, m.period_ns);
}
inline auto fields(const CommandCounters& m) {
  return std::tie(m.received, m.accepted, m.clamped, m.rejected_unknown_session, m.rejected_wrong_device,
                  m.rejected_not_owner, m.rejected_unknown_motor, m.rejected_malformed, m.rejected_non_finite,
                  m.rejected_out_of_range, m.rejected_estop, m.rejected_fault, m.dropped_stale);
}
inline auto fields(const DeviceInfo& m) {
  return std::tie(m.name, m.driver, m.driver_version, m.model, m.kinematic_model, m.rate_hz, m.native_rate_hz,
                  m.joint_names, m.position_min, m.position_max, m.velocity_max, m.acceleration_max, m.effort_max,
                  m.control_modes, m.behavior_map, m.ops, m.state);
}
inline auto fields(const ControlCommand& m) {
  return std::tie(m.header, m.uuid, m.motor_ids, m.positions, m.velocities, m.kp, m.kd, m.torques, m.device,
                  m.sent_steady_ns, m.answers_tick);
}
inline auto fields(const TickState& m) {
  return std::tie(m.header, m.tick, m.deadline_steady_ns, m.period_ns, m.state_ready_steady_ns, m.published_steady_ns,
                  m.state, m.position, m.velocity, m.effort, m.has_imu, m.imu_orientation, m.imu_angular_velocity,
                  m.imu_linear_acceleration);
}
inline auto fields(const JointState& m) { return std::tie(m.header, m.name, m.position, m.velocity, m.effort); }
inline auto fields(const PoseStamped& m) { return std::tie(m.header, m.position, m.orientation); }
inline auto fields(const Imu& m) {
  return std::tie(m.header, m.orientation, m.angular_velocity, m.linear_acceleration);
}
inline auto fields(const Joy& m) {
  return std::tie(m.l_horizontal, m.l_vertical, m.lt, m.r_horizontal, m.r_vertical, m.rt, m.dpad_horizontal,
                  m.dpad_vertical, m.a, m.b, m.x, m.y, m.lb, m.rb, m.back, m.start, m.center, m.l, m.r, m.header);
}
inline auto fields(const PolicyData& m) { return std::tie(m.header, m.data_type, m.data); }
inline auto fields(const ServiceCounters& m) { return std::tie(m.service, m.requests, m.refused, m.oversized); }
inline auto fields(const SurfaceCounters& m) {
  return std::tie(m.commands_unattributed, m.dds_log_messages, m.services);
}
inline auto fields(const SessionStatus& m) {
  return std::tie(m.header, m.state, m.policy_name, m.policy_file_name, m.active_uuids, m.node_names, m.motor_counts,
                  m.sessions, m.surface);
}
inline auto fields(const DeviceStatus& m) {
  return std::tie(m.header, m.device, m.driver, m.state, m.state_text, m.fault_code, m.fault_text, m.estop_engaged,
                  m.loop, m.commands, m.driver_values, m.joint_states_published);
}
inline auto fields(const RequestControlRequest& m) {
  return std::tie(m.node_name, m.motor_ids, m.control_mode, m.default_behavior, m.timeout_ms, m.default_kp,
                  m.default_kd, m.device, m.policy_name, m.policy_file_name, m.min_command_success_rate,
                  m.on_low_success_rate);
}
inline auto fields(const RequestControlResponse& m) {
  return std::tie(m.success, m.message, m.uuid, m.motor_ids, m.applied_behavior, m.device, m.session_id);
}
inline auto fields(const ReleaseControlRequest& m) { return std::tie(m.node_name, m.uuid, m.release_mode); }
inline auto fields(const ReleaseControlResponse& m) { return std::tie(m.success, m.message, m.applied_behavior); }
inline auto fields(const GetAvailableMotorsRequest& m) { return std::tie(m.node_name, m.device); }
inline auto fields(const GetAvailableMotorsResponse& m) {
  return std::tie(m.motor_ids, m.motor_names, m.success, m.message);
}
inline auto fields(const ResetZeroRequest& m) { return std::tie(m.device, m.motor_ids, m.timeout_ms); }
inline auto fields(const ResetZeroResponse& m) { return std::tie(m.success, m.message); }
inline auto fields(const EstopRequest& m) { return std::tie(m.node_name, m.device, m.engage, m.reason); }
inline auto fields(const EstopResponse& m) { return std::tie(m.success, m.message); }
inline auto fields(const ListDevicesRequest& m) { return std::tie(m.node_name); }
inline auto fields(const ListDevicesResponse& m) { return std::tie(m.devices); }
inline auto fields(const DeviceCallRequest& m) { return std::tie(m.device, m.op, m.args_json); }
inline auto fields(const DeviceCallResponse& m) { return std::tie(m.success, m.message, m.result_json); }

// Found by ADL for the nested structs and vectors of structs inside the tuples above.
template <class T>
auto operator==(const T& a, const T& b) -> decltype(fields(a) == fields(b)) {
  return fields(a) == fields(b);
}

}  // namespace robotd

namespace robotd::wire {
namespace {

using namespace std::chrono_literals;

// Sample values: every field differs from its default and from its neighbours, so a field
// dropped, defaulted or swapped with another of the same type shows up.
Header header(std::int32_t sec) { return Header{Time{sec, 123'456'789u}, "frame_" + std::to_string(sec)}; }

SessionInfo session(int n) {
  SessionInfo s;
  s.uuid = "uuid-" + std::to_string(n);
  s.node_name = "node-" + std::to_string(n);
  s.device = "arm";
  s.motor_ids = {n, n + 1};
  s.control_mode = ControlMode::kMixed;
  s.default_behavior = Behavior::kZeroTorque;
  s.applied_behavior = Behavior::kDamping;
  s.timeout_ms = 1500 + n;
  s.time_left_ms = 700 + n;
  s.granted_at = Time{1'700'000'000, 42u};
  s.commands_accepted = std::uint64_t{9'000'000'000} + static_cast<std::uint32_t>(n);
  s.policy_name = "policy-" + std::to_string(n);
  s.policy_file_name = "/opt/policies/" + std::to_string(n) + ".onnx";
  s.closed_loop = true;
  s.ticks_to_answer = std::uint64_t{5'000'000'000} + static_cast<std::uint32_t>(n);
  s.ticks_answered_in_time = 4'000'000'000U + static_cast<std::uint32_t>(n);
  s.ticks_answered_late = 300U + static_cast<std::uint32_t>(n);
  s.ticks_unanswered = 20U + static_cast<std::uint32_t>(n);
  s.command_success_rate = 0.5F + 0.125F * static_cast<float>(n);
  s.min_command_success_rate = 0.25F;
  s.on_low_success_rate = LowRateAction::kFallback;
  s.success_rate_low = true;
  return s;
}

DeviceInfo device_info(int n) {
  DeviceInfo d;
  d.name = "dev" + std::to_string(n);
  d.driver = "sim";
  d.driver_version = "1.2.3";
  d.model = "six-axis";
  d.kinematic_model = "parol6";
  d.rate_hz = 1000.0;
  d.native_rate_hz = 250.0;
  d.joint_names = {"j1", "j2"};
  d.position_min = {-1.5, -2.5};
  d.position_max = {1.5, 2.5};
  d.velocity_max = {3.0, 3.5};
  d.acceleration_max = {10.0, 11.0};
  d.effort_max = {40.0, 41.0};
  d.control_modes = {"POSITION", "TORQUE"};
  d.behavior_map = {0, 0, 1};
  d.ops = {"gripper: open or close", "home: go home"};
  d.state = DeviceState::kMaintenance;
  return d;
}

template <class T>
T sample();

template <>
ControlCommand sample() {
  return ControlCommand{header(1),    "uuid",       {1, 2}, {0.1f, 0.2f},    {0.3f, 0.4f}, {5.f, 6.f},
                        {0.5f, 0.6f}, {1.1f, 1.2f}, "arm",  123'456'789'012, 9'876'543'210};
}
template <>
TickState sample() {
  TickState s;
  s.header = header(12);
  s.tick = 9'000'000'001;
  s.deadline_steady_ns = 1'000'000'000'123;
  s.period_ns = 1'000'000;
  s.state_ready_steady_ns = 1'000'000'010'000;
  s.published_steady_ns = 1'000'000'020'000;
  s.state = DeviceState::kRunning;
  s.position = {0.5, -0.5};
  s.velocity = {1.5, -1.5};
  s.effort = {2.5, -2.5};
  s.has_imu = true;
  s.imu_orientation = Quaternion{0.1, 0.2, 0.3, 0.9};
  s.imu_angular_velocity = Vector3{1, 2, 3};
  s.imu_linear_acceleration = Vector3{4, 5, 9.81};
  return s;
}
template <>
JointState sample() {
  return JointState{header(2), {"j1", "j2"}, {0.5, -0.5}, {1.5, -1.5}, {2.5, -2.5}};
}
template <>
PoseStamped sample() {
  return PoseStamped{header(9), Vector3{0.25, -0.5, 0.75}, Quaternion{0.5, 0.5, 0.5, 0.5}};
}
template <>
Imu sample() {
  return Imu{header(3), Quaternion{0.1, 0.2, 0.3, 0.9}, Vector3{1, 2, 3}, Vector3{4, 5, 9.81}};
}
template <>
Vector3 sample() {
  return Vector3{10.5, -20.25, 30.125};
}
template <>
Quaternion sample() {
  return Quaternion{0.1, -0.2, 0.3, 0.92};
}
template <>
Joy sample() {
  // Every field a different value, so a swapped pair shows.
  return Joy{-0.25F, 0.5F, 0.75F, -1.0F, 1.0F, 0.125F, -1.0F, 1.0F,  2.0F,  3.0F,
             4.0F,   5.0F, 6.0F,  7.0F,  8.0F, 9.0F,   10.0F, 11.0F, 12.0F, header(10)};
}
template <>
PolicyData sample() {
  return PolicyData{header(11), "action", {0.5, -1.5, 1e-9}};
}
template <>
SessionStatus sample() {
  return SessionStatus{header(4),
                       "active",
                       "per_motor",
                       "/etc/robotd/policy.json",
                       {"uuid-1", "uuid-2"},
                       {"node-1", "node-2"},
                       {2, 2},
                       {session(1), session(2)},
                       {41, 42, {{"request_control", 43, 44, 45}, {"estop", 46, 47, 48}}}};
}
template <>
DeviceStatus sample() {
  DeviceStatus s;
  s.header = header(5);
  s.device = "arm";
  s.driver = "sim";
  s.state = DeviceState::kFault;
  s.state_text = "FAULT";
  s.fault_code = -17;
  s.fault_text = "over temperature";
  s.estop_engaged = true;
  s.loop = LoopStatistics{1000.0, true, 1'000'001, 3,     4096,  999.5f, 1001.5f,           1020.f,   12.f,
                          30.f,   55.f, 80.f,      150.f, 210.f, 0,      1'000'000'000'123, 1'000'000};
  s.commands = CommandCounters{101, 90, 7, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  s.driver_values = {{"bus_voltage_v", "24.1"}, {"temperature_c", "41"}};
  s.joint_states_published = 123456;
  return s;
}
template <>
RequestControlRequest sample() {
  return RequestControlRequest{"node",
                               {3, 4},
                               ControlMode::kTorque,
                               Behavior::kZeroTorque,
                               2500,
                               {30.f, 31.f},
                               {1.f, 1.5f},
                               "arm",
                               "walk",
                               "walk_v3.onnx",
                               0.95F,
                               LowRateAction::kFallback};
}
template <>
RequestControlResponse sample() {
  return RequestControlResponse{true, "granted", "uuid-9", {3, 4}, Behavior::kDamping, "arm", "3f2a9c1e"};
}
template <>
ReleaseControlRequest sample() {
  return ReleaseControlRequest{"node", "uuid-9", Behavior::kZeroTorque};
}
template <>
ReleaseControlResponse sample() {
  return ReleaseControlResponse{true, "released", Behavior::kDamping};
}
template <>
GetAvailableMotorsRequest sample() {
  return GetAvailableMotorsRequest{"node", "arm"};
}
template <>
GetAvailableMotorsResponse sample() {
  return GetAvailableMotorsResponse{{5, 6, 7}, {"j5", "j6", "j7"}, true, "3 free"};
}
template <>
ResetZeroRequest sample() {
  return ResetZeroRequest{"arm", {1, 2}, 7000};
}
template <>
ResetZeroResponse sample() {
  return ResetZeroResponse{true, "zeroed"};
}
template <>
EstopRequest sample() {
  return EstopRequest{"node", "arm", false, "test over"};
}
template <>
EstopResponse sample() {
  return EstopResponse{true, "reset"};
}
template <>
ListDevicesRequest sample() {
  return ListDevicesRequest{"node"};
}
template <>
ListDevicesResponse sample() {
  return ListDevicesResponse{{device_info(1), device_info(2)}};
}
template <>
DeviceCallRequest sample() {
  return DeviceCallRequest{"arm", "gripper", R"({"width_m": 0.04})"};
}
template <>
DeviceCallResponse sample() {
  return DeviceCallResponse{true, "done", R"({"width_m": 0.039})"};
}

template <class Tuple, std::size_t... I>
std::vector<std::size_t> positions_of_equal_fields(const Tuple& a, const Tuple& b, std::index_sequence<I...>) {
  std::vector<std::size_t> equal;
  ((std::get<I>(a) == std::get<I>(b) ? equal.push_back(I) : void()), ...);
  return equal;
}
template <class Tuple>
std::vector<std::size_t> positions_of_equal_fields(const Tuple& a, const Tuple& b) {
  return positions_of_equal_fields(a, b, std::make_index_sequence<std::tuple_size_v<Tuple>>{});
}

template <class T>
class WireConversion : public ::testing::Test {};

using AllWireTypes =
    ::testing::Types<ControlCommand, TickState, JointState, Imu, PoseStamped, Vector3, Quaternion, Joy, PolicyData,
                     SessionStatus, DeviceStatus, RequestControlRequest, RequestControlResponse, ReleaseControlRequest,
                     ReleaseControlResponse, GetAvailableMotorsRequest, GetAvailableMotorsResponse, ResetZeroRequest,
                     ResetZeroResponse, EstopRequest, EstopResponse, ListDevicesRequest, ListDevicesResponse,
                     DeviceCallRequest, DeviceCallResponse>;

// Names each typed test after its DDS type, e.g. WireConversion/RequestControl_Request.
struct TypeNames {
  template <class T>
  static std::string GetName(int /*index*/) {
    const std::string type_name = Wire<T>::descriptor().m_typename;  // pkg::srv::dds_::Name_Request_
    const std::string last = type_name.substr(type_name.rfind("::") + 2);
    return last.substr(0, last.size() - 1);
  }
};
TYPED_TEST_SUITE(WireConversion, AllWireTypes, TypeNames);

TYPED_TEST(WireConversion, SampleSetsEveryFieldToANonDefaultValue) {
  // Guards the tests below: a field left at its default would round-trip even if dropped.
  const TypeParam value = sample<TypeParam>();
  const TypeParam default_value{};
  EXPECT_EQ(positions_of_equal_fields(fields(value), fields(default_value)), std::vector<std::size_t>{})
      << "these fields of the sample still hold their default value";
}

TYPED_TEST(WireConversion, ToCThenFromCGivesTheSameValue) {
  const TypeParam value = sample<TypeParam>();
  typename Wire<TypeParam>::C c{};
  CArena arena;
  Wire<TypeParam>::to_c(value, c, arena);
  const TypeParam back = Wire<TypeParam>::from_c(c);
  EXPECT_EQ(fields(back), fields(value));
}

TYPED_TEST(WireConversion, SurvivesADdsWriteAndRead) {
  const testing::PrivateDomain domain;
  auto participant = Participant::create(domain.settings());
  ASSERT_TRUE(participant) << participant.error().message;
  const std::string topic = "rt/wire_conversion_" + TypeNames::GetName<TypeParam>(0);
  auto writer = TopicWriter<TypeParam>::create(participant.value(), topic, reliable_qos(1).get());
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = TopicReader<TypeParam>::create(participant.value(), topic, reliable_qos(1).get());
  ASSERT_TRUE(reader) << reader.error().message;
  ASSERT_TRUE(testing::wait_until([&] { return writer.value().matched_readers() == 1; }));

  const TypeParam value = sample<TypeParam>();
  ASSERT_TRUE(writer.value().write(value));
  std::vector<TypeParam> received;
  ASSERT_TRUE(testing::wait_until([&] {
    reader.value().take_each(
        [&](TypeParam&& sample, const dds_sample_info_t&) { received.push_back(std::move(sample)); });
    return !received.empty();
  }));
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(fields(received.front()), fields(value));
}

}  // namespace
}  // namespace robotd::wire
