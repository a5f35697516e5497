// The rules of DESIGN.md "Sessions": per-motor ownership, disjoint sessions side by side,
// overlap refused naming the holder, every request checked before it is granted.
#include "session/session_table.hpp"

#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "device_models.hpp"

namespace robotd::session {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

constexpr std::int64_t kMs = 1'000'000;

RequestControlRequest request(const std::string& node, std::vector<std::int32_t> motor_ids,
                              ControlMode mode = ControlMode::kPosition, Behavior behavior = Behavior::kKeep) {
  RequestControlRequest r;
  r.node_name = node;
  r.motor_ids = std::move(motor_ids);
  r.control_mode = mode;
  r.default_behavior = behavior;
  r.timeout_ms = 1000;
  return r;
}

// One table over a position-only arm (6 joints), or over that arm and a torque chain (4 joints).
class SessionTableTest : public ::testing::Test {
 protected:
  control::DeviceModel arm_ = test::position_only_arm("arm", 6);
  control::DeviceModel legs_ = test::torque_chain("legs", 4);
  SessionTable one_device_{{&arm_}, SessionLimits{}};
  SessionTable two_devices_{{&arm_, &legs_}, SessionLimits{}};

  // The session's public id is "id-" + its uuid here, to tell the two apart in messages.
  SessionRecord grant_ok(SessionTable& table, const RequestControlRequest& r, const std::string& uuid,
                         std::int64_t now_ns = 0) {
    Result<SessionRecord> granted = table.grant(r, uuid, "id-" + uuid, now_ns, 0);
    EXPECT_TRUE(granted.ok()) << granted.error().message;
    return granted.ok() ? granted.value() : SessionRecord{};
  }

  std::string refusal(SessionTable& table, const RequestControlRequest& r, std::int64_t now_ns = 0) {
    Result<SessionRecord> granted = table.grant(r, "refused-uuid", "refused-id", now_ns, 0);
    if (granted.ok()) {
      ADD_FAILURE() << "request was granted";
      return "";
    }
    EXPECT_EQ(granted.error().code, ErrorCode::kRefused);
    return granted.error().message;
  }
};

TEST_F(SessionTableTest, EmptyMotorIdsClaimEveryMotorOfTheDevice) {
  const SessionRecord record = grant_ok(one_device_, request("planner", {}), "u1");
  EXPECT_THAT(record.motor_ids, ElementsAre(0, 1, 2, 3, 4, 5));
  EXPECT_EQ(record.motors.count(), 6u);
  EXPECT_THAT(one_device_.idle_motors(0), IsEmpty());
}

TEST_F(SessionTableTest, GrantRecordsWhoHoldsWhatAndUntilWhen) {
  RequestControlRequest r = request("planner", {1, 3});
  r.timeout_ms = 250;
  const SessionRecord record = one_device_.grant(r, "u1", "3f2a9c1e", 5 * kMs, 1234).value();
  EXPECT_EQ(record.uuid, "u1");
  EXPECT_EQ(record.session_id, "3f2a9c1e");
  EXPECT_EQ(record.node_name, "planner");
  EXPECT_EQ(record.device, "arm");
  EXPECT_EQ(record.device_index, 0u);
  EXPECT_THAT(record.motor_ids, ElementsAre(1, 3));
  EXPECT_TRUE(record.motors.test(1));
  EXPECT_TRUE(record.motors.test(3));
  EXPECT_EQ(record.motors.count(), 2u);
  EXPECT_EQ(record.timeout_ms, 250);
  EXPECT_EQ(record.granted_ns, 5 * kMs);
  EXPECT_EQ(record.granted_wall_ns, 1234);
  EXPECT_EQ(record.last_command_ns, 5 * kMs);
  EXPECT_NE(one_device_.find("u1"), nullptr);
  EXPECT_EQ(one_device_.find_by_id("3f2a9c1e"), one_device_.find("u1"));
  EXPECT_EQ(one_device_.find("3f2a9c1e"), nullptr) << "the public id is not the capability";
  EXPECT_TRUE(one_device_.any_active(0));
}

TEST_F(SessionTableTest, UnnamedNodeIsShownAsUnnamed) {
  EXPECT_EQ(grant_ok(one_device_, request("", {0}), "u1").node_name, "(unnamed)");
}

TEST_F(SessionTableTest, DisjointSessionsCoexist) {
  grant_ok(one_device_, request("left", {0, 1}), "u1");
  grant_ok(one_device_, request("right", {2, 3}), "u2");
  EXPECT_EQ(one_device_.sessions().size(), 2u);
  EXPECT_THAT(one_device_.idle_motors(0), ElementsAre(4, 5));
}

TEST_F(SessionTableTest, OverlapIsRefusedNamingHolderSessionMotorsAndTimeLeft) {
  grant_ok(one_device_, request("planner", {0, 1, 2}), "uuid-of-planner", 0);
  const std::string message = refusal(one_device_, request("teleop", {3, 2, 1}), 250 * kMs);
  EXPECT_THAT(message, HasSubstr("device 'arm'"));
  EXPECT_THAT(message, HasSubstr("motor(s) 1, 2 held by node 'planner'"));
  EXPECT_THAT(message, HasSubstr("(session id-uuid-of-planner,"));
  EXPECT_THAT(message, Not(HasSubstr("(session uuid-of-planner")));
  EXPECT_THAT(message, HasSubstr("750 ms left"));
  EXPECT_THAT(message, HasSubstr("timeout 1000 ms"));
  EXPECT_EQ(one_device_.sessions().size(), 1u);
}

TEST_F(SessionTableTest, OverlapWithSeveralHoldersNamesEachOfThem) {
  grant_ok(one_device_, request("left", {0}), "u-left");
  grant_ok(one_device_, request("right", {5}), "u-right");
  const std::string message = refusal(one_device_, request("all", {}));
  EXPECT_THAT(message, HasSubstr("motor(s) 0 held by node 'left'"));
  EXPECT_THAT(message, HasSubstr("motor(s) 5 held by node 'right'"));
}

TEST_F(SessionTableTest, InvalidControlModeIsRefused) {
  EXPECT_THAT(refusal(one_device_, request("n", {0}, static_cast<ControlMode>(7))),
              HasSubstr("control_mode 7 is not one of POSITION_MODE=0, TORQUE_MODE=1, MIXED_MODE=2"));
}

TEST_F(SessionTableTest, InvalidDefaultBehaviorIsRefused) {
  EXPECT_THAT(refusal(one_device_, request("n", {0}, ControlMode::kPosition, static_cast<Behavior>(-1))),
              HasSubstr("default_behavior -1 is not one of KEEP_MODE=0, DAMPING_MODE=1, ZERO_TORQUE_MODE=2"));
}

TEST_F(SessionTableTest, AMinimumSuccessRateOutside0To1OrNotANumberIsRefused) {
  for (const float rate : {-0.1F, 1.5F, std::numeric_limits<float>::quiet_NaN()}) {
    RequestControlRequest r = request("n", {0});
    r.min_command_success_rate = rate;
    EXPECT_THAT(refusal(one_device_, r), HasSubstr("is outside 0..1 (the least fraction of ticks answered in time"))
        << rate;
  }
  RequestControlRequest r = request("n", {0});
  r.min_command_success_rate = 0.98F;
  r.on_low_success_rate = LowRateAction::kFallback;
  const SessionRecord granted = grant_ok(one_device_, r, "u1");
  EXPECT_FLOAT_EQ(granted.min_command_success_rate, 0.98F);
  EXPECT_EQ(granted.on_low_success_rate, LowRateAction::kFallback);
}

TEST_F(SessionTableTest, AnUnknownLowSuccessRateActionIsRefused) {
  RequestControlRequest r = request("n", {0});
  r.on_low_success_rate = static_cast<LowRateAction>(2);
  EXPECT_THAT(refusal(one_device_, r),
              HasSubstr("on_low_success_rate 2 is not one of LOW_RATE_WARN=0, LOW_RATE_FALLBACK=1"));
}

TEST_F(SessionTableTest, TimeoutBelowTheMinimumIsRefused) {
  SessionTable table({&arm_}, SessionLimits{20, 5000});
  RequestControlRequest r = request("n", {0});
  r.timeout_ms = 19;
  EXPECT_THAT(refusal(table, r), HasSubstr("timeout_ms 19 is outside 20..5000"));
}

TEST_F(SessionTableTest, TimeoutAboveTheMaximumIsRefused) {
  SessionTable table({&arm_}, SessionLimits{20, 5000});
  RequestControlRequest r = request("n", {0});
  r.timeout_ms = 5001;
  EXPECT_THAT(refusal(table, r), HasSubstr("timeout_ms 5001 is outside 20..5000"));
  r.timeout_ms = 5000;
  grant_ok(table, r, "u1");
}

TEST_F(SessionTableTest, UnknownMotorIdIsRefusedWithTheValidRange) {
  EXPECT_THAT(refusal(one_device_, request("n", {0, 6})),
              HasSubstr("motor id 6 does not exist on device 'arm' (valid: 0..5)"));
  EXPECT_THAT(refusal(one_device_, request("n", {-1})), HasSubstr("motor id -1 does not exist"));
}

TEST_F(SessionTableTest, DuplicateMotorIdIsRefused) {
  EXPECT_THAT(refusal(one_device_, request("n", {2, 4, 2})), HasSubstr("motor id 2 appears twice"));
}

TEST_F(SessionTableTest, TorqueModeIsRefusedOnAPositionOnlyDevice) {
  const std::string message = refusal(one_device_, request("n", {0}, ControlMode::kTorque));
  EXPECT_THAT(message, HasSubstr("device 'arm' (test) supports only POSITION mode, not TORQUE"));
}

TEST_F(SessionTableTest, MixedModeIsRefusedOnAPositionOnlyDevice) {
  EXPECT_THAT(refusal(one_device_, request("n", {0}, ControlMode::kMixed)),
              HasSubstr("supports only POSITION mode, not MIXED"));
}

// A device whose driver only reports (a leader arm moved by hand) is never granted, in any mode,
// and the refusal carries the driver's reason; it lists no control modes.
TEST_F(SessionTableTest, AReadOnlyDeviceIsRefusedWithTheDriversReason) {
  control::DeviceModel leader = test::position_only_arm("leader", 6);
  leader.read_only_reason = "a leader arm only reports what a person moves it to";
  SessionTable table{{&leader}, SessionLimits{}};
  for (const ControlMode mode : {ControlMode::kPosition, ControlMode::kTorque}) {
    EXPECT_THAT(refusal(table, request("n", {}, mode)),
                HasSubstr("device 'leader' (test) takes no commands: a leader arm only reports"));
  }
  EXPECT_THAT(leader.control_modes(), IsEmpty());
  EXPECT_THAT(arm_.control_modes(), ElementsAre(ControlMode::kPosition));
}

TEST_F(SessionTableTest, TorqueAndMixedModesAreGrantedOnATorqueDevice) {
  RequestControlRequest torque = request("n", {0}, ControlMode::kTorque);
  torque.device = "legs";
  EXPECT_EQ(grant_ok(two_devices_, torque, "u1").mode, ControlMode::kTorque);
  RequestControlRequest mixed = request("n", {1}, ControlMode::kMixed);
  mixed.device = "legs";
  EXPECT_EQ(grant_ok(two_devices_, mixed, "u2").mode, ControlMode::kMixed);
}

TEST_F(SessionTableTest, DefaultKpOfTheWrongLengthIsRefused) {
  RequestControlRequest r = request("n", {0, 1});
  r.default_kp = {10.0F};
  EXPECT_THAT(refusal(one_device_, r), HasSubstr("default_kp has 1 values for 2 motors"));
}

TEST_F(SessionTableTest, DefaultKdForAllMotorsMustMatchTheDeviceJointCount) {
  RequestControlRequest r = request("n", {});
  r.default_kd = {1.0F, 1.0F};
  EXPECT_THAT(refusal(one_device_, r), HasSubstr("default_kd has 2 values for 6 motors"));
}

TEST_F(SessionTableTest, DefaultKpBeyondKpMaxIsRefused) {
  RequestControlRequest r = request("n", {0, 3});
  r.default_kp = {50.0F, 101.0F};
  EXPECT_THAT(refusal(one_device_, r), HasSubstr("default_kp 101 for motor 3 is outside 0..100"));
}

TEST_F(SessionTableTest, DefaultKdBeyondKdMaxOrNegativeIsRefused) {
  RequestControlRequest r = request("n", {2});
  r.default_kd = {10.5F};
  EXPECT_THAT(refusal(one_device_, r), HasSubstr("default_kd 10.5 for motor 2 is outside 0..10"));
  r.default_kd = {-1.0F};
  EXPECT_THAT(refusal(one_device_, r), HasSubstr("default_kd -1 for motor 2 is outside 0..10"));
}

TEST_F(SessionTableTest, DefaultGainsWithinLimitsAreKeptWithTheSession) {
  RequestControlRequest r = request("n", {0, 1});
  r.default_kp = {100.0F, 0.0F};
  r.default_kd = {10.0F, 1.0F};
  const SessionRecord record = grant_ok(one_device_, r, "u1");
  EXPECT_THAT(record.default_kp, ElementsAre(100.0F, 0.0F));
  EXPECT_THAT(record.default_kd, ElementsAre(10.0F, 1.0F));
}

TEST_F(SessionTableTest, SlotsRunOutAfterTheMaximumSessionsPerDevice) {
  const control::DeviceModel big = test::position_only_arm("big", kMaxSessionsPerDevice + 1);
  SessionTable table({&big}, SessionLimits{});
  for (std::size_t i = 0; i < kMaxSessionsPerDevice; ++i) {
    grant_ok(table, request("n", {static_cast<std::int32_t>(i)}), "u" + std::to_string(i));
  }
  const auto last = static_cast<std::int32_t>(kMaxSessionsPerDevice);
  EXPECT_THAT(refusal(table, request("n", {last})),
              HasSubstr("device 'big' already has 16 sessions; release one first"));
  ASSERT_TRUE(table.release("u3").ok());
  EXPECT_EQ(grant_ok(table, request("n", {last}), "u-last").slot, 3u);
}

TEST_F(SessionTableTest, ReleaseFreesTheMotors) {
  grant_ok(one_device_, request("n", {0, 1}), "u1");
  const Result<SessionRecord> released = one_device_.release("u1");
  ASSERT_TRUE(released.ok());
  EXPECT_EQ(released.value().uuid, "u1");
  EXPECT_THAT(one_device_.idle_motors(0), ElementsAre(0, 1, 2, 3, 4, 5));
  EXPECT_FALSE(one_device_.any_active());
  EXPECT_EQ(one_device_.find("u1"), nullptr);
  grant_ok(one_device_, request("other", {0, 1}), "u2");
}

TEST_F(SessionTableTest, ReleaseOfAnUnknownUuidIsRefused) {
  grant_ok(one_device_, request("n", {0}), "u1");
  const Result<SessionRecord> released = one_device_.release("no-such-uuid");
  ASSERT_FALSE(released.ok());
  EXPECT_EQ(released.error().code, ErrorCode::kRefused);
  EXPECT_THAT(released.error().message, HasSubstr("no active session has uuid 'no-such-uuid'"));
  EXPECT_TRUE(one_device_.any_active(0));
}

TEST_F(SessionTableTest, ThePublicIdReleasesNothingAndTheRefusalSaysWhy) {
  grant_ok(one_device_, request("teleop", {0}), "u1");
  const Result<SessionRecord> released = one_device_.release("id-u1");
  ASSERT_FALSE(released.ok());
  EXPECT_THAT(released.error().message,
              HasSubstr("'id-u1' is the public id of a session of node 'teleop' on 'arm', not a uuid"));
  EXPECT_THAT(released.error().message, Not(HasSubstr("'u1'")));
  EXPECT_NE(one_device_.find("u1"), nullptr);
}

TEST_F(SessionTableTest, EndWithAStaleGenerationLeavesTheSlotsNewSessionAlone) {
  const SessionRecord first = grant_ok(one_device_, request("n", {0}), "u1");
  ASSERT_TRUE(one_device_.release("u1").ok());
  const SessionRecord second = grant_ok(one_device_, request("n", {0}), "u2");
  ASSERT_EQ(second.slot, first.slot);

  EXPECT_FALSE(one_device_.end(0, first.slot, first.generation).has_value());
  EXPECT_NE(one_device_.find("u2"), nullptr);

  const std::optional<SessionRecord> ended = one_device_.end(0, second.slot, second.generation);
  ASSERT_TRUE(ended.has_value());
  EXPECT_EQ(ended->uuid, "u2");
  EXPECT_FALSE(one_device_.any_active());
}

TEST_F(SessionTableTest, EndOfAnOutOfRangeDeviceOrSlotIsANoOp) {
  const SessionRecord record = grant_ok(one_device_, request("n", {0}), "u1");
  EXPECT_FALSE(one_device_.end(1, record.slot, record.generation).has_value());
  EXPECT_FALSE(one_device_.end(0, static_cast<std::uint8_t>(kMaxSessionsPerDevice), record.generation).has_value());
  EXPECT_TRUE(one_device_.any_active(0));
}

TEST_F(SessionTableTest, IdleMotorsAreThoseNoSessionHolds) {
  grant_ok(one_device_, request("n", {1, 4}), "u1");
  EXPECT_THAT(one_device_.idle_motors(0), ElementsAre(0, 2, 3, 5));
}

TEST_F(SessionTableTest, PositionOnlyDeviceKeepsInsteadOfDampingOrLettingGo) {
  const SessionRecord damping =
      grant_ok(one_device_, request("n", {0}, ControlMode::kPosition, Behavior::kDamping), "u1");
  EXPECT_EQ(damping.requested_behavior, Behavior::kDamping);
  EXPECT_EQ(damping.applied_behavior, Behavior::kKeep);
  const SessionRecord zero =
      grant_ok(one_device_, request("n", {1}, ControlMode::kPosition, Behavior::kZeroTorque), "u2");
  EXPECT_EQ(zero.requested_behavior, Behavior::kZeroTorque);
  EXPECT_EQ(zero.applied_behavior, Behavior::kKeep);
}

TEST_F(SessionTableTest, DampingOnlyDeviceDampsInsteadOfLettingGo) {
  control::BehaviorSupport damping_only;
  damping_only.damping = true;
  const control::DeviceModel damper = test::make_device_model("damper", 2, false, damping_only);
  SessionTable table({&damper}, SessionLimits{});
  EXPECT_EQ(grant_ok(table, request("n", {0}, ControlMode::kPosition, Behavior::kZeroTorque), "u1").applied_behavior,
            Behavior::kDamping);
  EXPECT_EQ(grant_ok(table, request("n", {1}, ControlMode::kPosition, Behavior::kDamping), "u2").applied_behavior,
            Behavior::kDamping);
}

TEST_F(SessionTableTest, EmptyDeviceNameResolvesToTheOnlyDevice) {
  const Result<std::size_t> resolved = one_device_.resolve_device("");
  ASSERT_TRUE(resolved.ok());
  EXPECT_EQ(resolved.value(), 0u);
}

TEST_F(SessionTableTest, EmptyDeviceNameIsRefusedWhenThereAreSeveralListingThem) {
  const Result<std::size_t> resolved = two_devices_.resolve_device("");
  ASSERT_FALSE(resolved.ok());
  EXPECT_THAT(resolved.error().message, HasSubstr("'arm', 'legs'"));
  EXPECT_THAT(resolved.error().message, HasSubstr("say which one"));
}

TEST_F(SessionTableTest, DeviceIsResolvedByNameAndAnUnknownNameListsTheDevices) {
  EXPECT_EQ(two_devices_.resolve_device("legs").value(), 1u);
  const Result<std::size_t> unknown = two_devices_.resolve_device("gripper");
  ASSERT_FALSE(unknown.ok());
  EXPECT_THAT(unknown.error().message, HasSubstr("unknown device 'gripper' (this robotd serves 'arm', 'legs')"));
}

TEST_F(SessionTableTest, SessionsOnDifferentDevicesDoNotConflict) {
  RequestControlRequest on_arm = request("n", {0});
  on_arm.device = "arm";
  RequestControlRequest on_legs = request("n", {0});
  on_legs.device = "legs";
  EXPECT_EQ(grant_ok(two_devices_, on_arm, "u1").device_index, 0u);
  EXPECT_EQ(grant_ok(two_devices_, on_legs, "u2").device_index, 1u);
  EXPECT_THAT(two_devices_.idle_motors(1), ElementsAre(1, 2, 3));
}

TEST_F(SessionTableTest, GenerationsIncreaseWithEveryGrant) {
  std::uint32_t previous = 0;
  for (int i = 0; i < 5; ++i) {
    const SessionRecord record = grant_ok(one_device_, request("n", {0}), "u" + std::to_string(i));
    EXPECT_GT(record.generation, previous);
    previous = record.generation;
    ASSERT_TRUE(one_device_.release(record.uuid).ok());
  }
}

TEST_F(SessionTableTest, SessionsAreListedByDeviceThenGrantTime) {
  RequestControlRequest legs = request("n", {0});
  legs.device = "legs";
  RequestControlRequest arm_late = request("n", {1});
  arm_late.device = "arm";
  RequestControlRequest arm_early = request("n", {2});
  arm_early.device = "arm";
  grant_ok(two_devices_, legs, "legs", 1 * kMs);
  grant_ok(two_devices_, arm_late, "arm-late", 9 * kMs);
  grant_ok(two_devices_, arm_early, "arm-early", 5 * kMs);
  const std::vector<SessionRecord> sessions = two_devices_.sessions();
  ASSERT_EQ(sessions.size(), 3u);
  EXPECT_EQ(sessions[0].uuid, "arm-early");
  EXPECT_EQ(sessions[1].uuid, "arm-late");
  EXPECT_EQ(sessions[2].uuid, "legs");
}

TEST(SessionRecord, TimeLeftCountsDownFromTheLastCommandAndStopsAtZero) {
  SessionRecord record;
  record.timeout_ms = 1000;
  record.last_command_ns = 2000 * kMs;
  EXPECT_EQ(record.time_left_ms(2000 * kMs), 1000);
  EXPECT_EQ(record.time_left_ms(2400 * kMs), 600);
  EXPECT_EQ(record.time_left_ms(3000 * kMs), 0);
  EXPECT_EQ(record.time_left_ms(9000 * kMs), 0);
}

}  // namespace
}  // namespace robotd::session
