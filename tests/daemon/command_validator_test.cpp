// The gate every ControlCommand passes before it may reach a motor. Each rejection carries a
// reason a counter can use and a detail a person can act on.
#include "control/command_validator.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "device_models.hpp"

namespace robotd::control {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A 3-joint device: position -1..1 rad, velocity 2 rad/s, torque 5 N·m, kp 0..100, kd 0..10.
test::JointSpec joint_spec() {
  test::JointSpec spec;
  spec.position_min_rad = -1.0;
  spec.position_max_rad = 1.0;
  spec.velocity_max_rad_s = 2.0;
  spec.effort_max_nm = 5.0;
  spec.kp_max = 100.0;
  spec.kd_max = 10.0;
  return spec;
}

ControlCommand command(std::vector<std::int32_t> motor_ids) {
  ControlCommand c;
  c.uuid = "uuid-1";
  c.motor_ids = std::move(motor_ids);
  return c;
}

// A well-formed MIXED command for motors 0 and 1, every array filled within limits.
ControlCommand mixed_command() {
  ControlCommand c = command({0, 1});
  c.positions = {0.5F, -0.25F};
  c.velocities = {1.0F, -1.5F};
  c.kp = {40.0F, 60.0F};
  c.kd = {1.0F, 2.0F};
  c.torques = {0.5F, -4.0F};
  return c;
}

std::vector<float>& array_named(ControlCommand& c, const std::string& name) {
  if (name == "positions") return c.positions;
  if (name == "velocities") return c.velocities;
  if (name == "kp") return c.kp;
  if (name == "kd") return c.kd;
  return c.torques;
}

class CommandValidatorTest : public ::testing::Test {
 protected:
  DeviceModel model_ = test::make_device_model("arm", 3, true, BehaviorSupport{}, joint_spec());
  ValidatedCommand out_;

  SessionView session(ControlMode mode, std::initializer_list<std::size_t> motors = {0, 1}) const {
    SessionView view;
    view.device = model_.name;
    view.mode = mode;
    for (const auto motor : motors) view.motors.set(motor);
    return view;
  }

  Verdict check(const ControlCommand& c, ControlMode mode = ControlMode::kMixed) {
    return validate_command(c, session(mode), model_, model_.limits, out_);
  }

  // The detail of a rejection for `reason`; fails the test if the verdict differs.
  std::string rejected(const ControlCommand& c, Rejection reason, ControlMode mode = ControlMode::kMixed) {
    const Verdict verdict = check(c, mode);
    if (!verdict.rejection.has_value()) {
      ADD_FAILURE() << "command was accepted";
      return "";
    }
    EXPECT_EQ(*verdict.rejection, reason) << "got " << to_string(*verdict.rejection) << ": " << verdict.detail;
    return verdict.detail;
  }

  void expect_accepted(const ControlCommand& c, ControlMode mode = ControlMode::kMixed) {
    const Verdict verdict = check(c, mode);
    EXPECT_FALSE(verdict.rejection.has_value()) << verdict.detail;
  }
};

TEST_F(CommandValidatorTest, KeepaliveWithoutMotorsOrValuesIsAccepted) {
  expect_accepted(command({}));
  EXPECT_TRUE(out_.keepalive);
  EXPECT_EQ(out_.count, 0u);
}

TEST_F(CommandValidatorTest, PositionsAreCheckedAgainstTheLimitsNarrowedAtRunTimeNotTheModels) {
  std::vector<driver::JointLimits> narrowed = model_.limits;
  narrowed[0].position_max_rad = 0.25;
  ControlCommand c = command({0});
  c.positions = {0.5F};
  const Verdict verdict = validate_command(c, session(ControlMode::kPosition), model_, narrowed, out_);
  ASSERT_TRUE(verdict.rejection.has_value());
  EXPECT_EQ(*verdict.rejection, Rejection::kOutOfRange);
  EXPECT_THAT(verdict.detail, HasSubstr("outside -1..0.25"));
}

TEST_F(CommandValidatorTest, ValuesWithoutMotorIdsAreMalformed) {
  ControlCommand c = command({});
  c.torques = {1.0F};
  EXPECT_THAT(rejected(c, Rejection::kMalformed), HasSubstr("torques has 1 values but motor_ids is empty"));
  EXPECT_FALSE(out_.keepalive);
}

TEST_F(CommandValidatorTest, MoreMotorIdsThanTheDeviceHasJointsAreMalformed) {
  ControlCommand c = command({0, 1, 2, 0});
  c.positions = {0, 0, 0, 0};
  EXPECT_THAT(rejected(c, Rejection::kMalformed, ControlMode::kPosition),
              HasSubstr("motor_ids names 4 motors; device 'arm' has 3"));
}

TEST_F(CommandValidatorTest, PositionModeRequiresPositions) {
  ControlCommand c = command({0});
  c.velocities = {0.1F};
  EXPECT_THAT(rejected(c, Rejection::kMalformed, ControlMode::kPosition),
              HasSubstr("positions is required in POSITION mode"));
}

TEST_F(CommandValidatorTest, PositionModeAcceptsPositionsAlone) {
  ControlCommand c = command({1});
  c.positions = {0.2F};
  expect_accepted(c, ControlMode::kPosition);
}

TEST_F(CommandValidatorTest, TorqueModeRequiresTorquesButNotPositions) {
  ControlCommand c = command({0});
  c.positions = {0.1F};
  EXPECT_THAT(rejected(c, Rejection::kMalformed, ControlMode::kTorque),
              HasSubstr("torques is required in TORQUE mode"));
  ControlCommand torque_only = command({0});
  torque_only.torques = {1.0F};
  expect_accepted(torque_only, ControlMode::kTorque);
}

TEST_F(CommandValidatorTest, MixedModeRequiresPositionsGainsAndTorques) {
  for (const std::string name : {"positions", "kp", "kd", "torques"}) {
    ControlCommand c = mixed_command();
    array_named(c, name).clear();
    EXPECT_THAT(rejected(c, Rejection::kMalformed), HasSubstr(name + " is required in MIXED mode")) << name;
  }
}

TEST_F(CommandValidatorTest, VelocitiesAreOptionalInEveryMode) {
  ControlCommand mixed = mixed_command();
  mixed.velocities.clear();
  expect_accepted(mixed);
  EXPECT_EQ(out_.joints[0].fields & kHasVelocity, 0);
}

TEST_F(CommandValidatorTest, ArrayOfTheWrongLengthIsMalformed) {
  ControlCommand c = mixed_command();
  c.kd = {1.0F};
  EXPECT_THAT(rejected(c, Rejection::kMalformed), HasSubstr("kd has 1 values for 2 motor ids"));
}

TEST_F(CommandValidatorTest, DuplicateMotorIdsAreMalformed) {
  ControlCommand c = command({1, 1});
  c.positions = {0.1F, 0.2F};
  EXPECT_THAT(rejected(c, Rejection::kMalformed, ControlMode::kPosition), HasSubstr("motor id 1 appears twice"));
}

TEST_F(CommandValidatorTest, MotorIdTheDeviceDoesNotHaveIsUnknown) {
  ControlCommand c = command({0, 3});
  c.positions = {0.1F, 0.2F};
  EXPECT_THAT(rejected(c, Rejection::kUnknownMotor, ControlMode::kPosition),
              HasSubstr("motor id 3 does not exist on device 'arm' (valid: 0..2)"));
  c.motor_ids = {-1};
  c.positions = {0.1F};
  EXPECT_THAT(rejected(c, Rejection::kUnknownMotor, ControlMode::kPosition), HasSubstr("motor id -1 does not exist"));
}

TEST_F(CommandValidatorTest, MotorTheSessionDoesNotOwnIsRefusedNamingIt) {
  ControlCommand c = command({0, 2});
  c.positions = {0.1F, 0.2F};
  const std::string detail = rejected(c, Rejection::kNotOwner, ControlMode::kPosition);
  EXPECT_THAT(detail, HasSubstr("the session does not own motor(s) 2 of 'arm'"));
  EXPECT_THAT(detail, Not(HasSubstr("uuid-1"))) << "the detail is logged; the uuid is the session's capability";
}

TEST_F(CommandValidatorTest, CommandForAnotherDeviceIsRefusedNamingBoth) {
  ControlCommand c = mixed_command();
  c.device = "legs";
  EXPECT_THAT(rejected(c, Rejection::kWrongDevice),
              HasSubstr("command names device 'legs' but its session is on device 'arm'"));
}

TEST_F(CommandValidatorTest, CommandNamingTheSessionsOwnDeviceIsAccepted) {
  ControlCommand c = mixed_command();
  c.device = "arm";
  expect_accepted(c);
}

TEST_F(CommandValidatorTest, NanOrInfinityInAnyArrayIsNonFinite) {
  const float kBadValues[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity()};
  for (const std::string name : {"positions", "velocities", "kp", "kd", "torques"}) {
    for (const float bad : kBadValues) {
      ControlCommand c = mixed_command();
      array_named(c, name)[1] = bad;
      EXPECT_THAT(rejected(c, Rejection::kNonFinite), HasSubstr(name + " for motor 1 is not a finite number"))
          << name << " = " << bad;
    }
  }
}

TEST_F(CommandValidatorTest, ValuesBeyondLimitsAreRejectedUnderTheRejectPolicy) {
  struct Case {
    const char* array;
    float value;
    const char* detail;
  };
  const Case cases[] = {
      {"positions", 1.5F, "position 1.5 for motor 0 ('j0') is outside -1..1"},
      {"positions", -1.25F, "position -1.25 for motor 0 ('j0') is outside -1..1"},
      {"velocities", 2.5F, "velocity 2.5 for motor 0 ('j0') is outside -2..2"},
      {"torques", -6.0F, "torque -6 for motor 0 ('j0') is outside -5..5"},
      {"kp", 101.0F, "kp 101 for motor 0 ('j0') is outside 0..100"},
      {"kd", 10.5F, "kd 10.5 for motor 0 ('j0') is outside 0..10"},
  };
  for (const Case& bad : cases) {
    ControlCommand c = mixed_command();
    array_named(c, bad.array)[0] = bad.value;
    EXPECT_THAT(rejected(c, Rejection::kOutOfRange), HasSubstr(bad.detail)) << bad.array;
  }
}

TEST_F(CommandValidatorTest, ValuesBeyondLimitsAreClampedToTheBoundUnderTheClampPolicy) {
  model_.limit_policy = LimitPolicy::kClamp;
  ControlCommand c = mixed_command();
  c.positions[0] = 1.5F;
  c.velocities[0] = -3.0F;
  c.torques[0] = 6.0F;
  c.kp[0] = 150.0F;
  c.kd[0] = 20.0F;
  expect_accepted(c);
  EXPECT_TRUE(out_.clamped);
  EXPECT_FLOAT_EQ(out_.joints[0].position, 1.0F);
  EXPECT_FLOAT_EQ(out_.joints[0].velocity, -2.0F);
  EXPECT_FLOAT_EQ(out_.joints[0].torque, 5.0F);
  EXPECT_FLOAT_EQ(out_.joints[0].kp, 100.0F);
  EXPECT_FLOAT_EQ(out_.joints[0].kd, 10.0F);
  // The other motor's values were within limits and pass unchanged.
  EXPECT_FLOAT_EQ(out_.joints[1].position, -0.25F);
  EXPECT_FLOAT_EQ(out_.joints[1].torque, -4.0F);
}

TEST_F(CommandValidatorTest, AClampedValueNeverLandsBeyondALimitThatIsNotAFloat) {
  // 0.7 and 241.1 are not floats; the nearest floats lie beyond 0.7 and 241.1. A clamped value
  // must stay within the limit, so it is the float just inside.
  test::JointSpec spec = joint_spec();
  spec.position_max_rad = 0.7;
  spec.kp_max = 241.10255146181541;
  model_ = test::make_device_model("arm", 3, true, BehaviorSupport{}, spec);
  model_.limit_policy = LimitPolicy::kClamp;
  ControlCommand c = mixed_command();
  c.positions[0] = 2.0F;
  c.kp[0] = 300.0F;
  expect_accepted(c);
  EXPECT_LE(static_cast<double>(out_.joints[0].position), 0.7);
  EXPECT_GT(static_cast<double>(out_.joints[0].position), 0.7 - 1e-6);
  EXPECT_LE(static_cast<double>(out_.joints[0].kp), 241.10255146181541);
  EXPECT_GT(static_cast<double>(out_.joints[0].kp), 241.1025);
}

TEST_F(CommandValidatorTest, ValuesWithinLimitsAreNotReportedAsClamped) {
  model_.limit_policy = LimitPolicy::kClamp;
  ControlCommand c = mixed_command();
  c.positions[0] = 1.0F;  // exactly on the bound
  expect_accepted(c);
  EXPECT_FALSE(out_.clamped);
}

TEST_F(CommandValidatorTest, NegativeGainsAreRejectedEvenUnderTheClampPolicy) {
  model_.limit_policy = LimitPolicy::kClamp;
  ControlCommand negative_kp = mixed_command();
  negative_kp.kp[1] = -1.0F;
  EXPECT_THAT(rejected(negative_kp, Rejection::kOutOfRange),
              HasSubstr("kp for motor 1 is negative; gains must be >= 0"));
  ControlCommand negative_kd = mixed_command();
  negative_kd.kd[0] = -0.5F;
  EXPECT_THAT(rejected(negative_kd, Rejection::kOutOfRange),
              HasSubstr("kd for motor 0 is negative; gains must be >= 0"));
}

TEST_F(CommandValidatorTest, AcceptedCommandFillsOneUpdatePerMotorInCommandOrder) {
  ControlCommand c = mixed_command();
  c.motor_ids = {1, 0};
  expect_accepted(c);
  EXPECT_FALSE(out_.keepalive);
  EXPECT_FALSE(out_.clamped);
  ASSERT_EQ(out_.count, 2u);
  const JointTargetUpdate& first = out_.joints[0];
  EXPECT_EQ(first.joint, 1);
  EXPECT_EQ(first.fields, kHasPosition | kHasVelocity | kHasKp | kHasKd | kHasTorque);
  EXPECT_FLOAT_EQ(first.position, 0.5F);
  EXPECT_FLOAT_EQ(first.velocity, 1.0F);
  EXPECT_FLOAT_EQ(first.kp, 40.0F);
  EXPECT_FLOAT_EQ(first.kd, 1.0F);
  EXPECT_FLOAT_EQ(first.torque, 0.5F);
  const JointTargetUpdate& second = out_.joints[1];
  EXPECT_EQ(second.joint, 0);
  EXPECT_FLOAT_EQ(second.position, -0.25F);
  EXPECT_FLOAT_EQ(second.torque, -4.0F);
}

TEST_F(CommandValidatorTest, FieldsFlagOnlyTheArraysTheCommandCarried) {
  ControlCommand c = command({0});
  c.positions = {0.3F};
  expect_accepted(c, ControlMode::kPosition);
  ASSERT_EQ(out_.count, 1u);
  EXPECT_EQ(out_.joints[0].fields, kHasPosition);
  ControlCommand torque = command({1});
  torque.torques = {2.0F};
  expect_accepted(torque, ControlMode::kTorque);
  EXPECT_EQ(out_.joints[0].fields, kHasTorque);
  EXPECT_EQ(out_.joints[0].joint, 1);
}

TEST_F(CommandValidatorTest, ARejectedCommandLeavesNoUpdates) {
  ControlCommand good = mixed_command();
  expect_accepted(good);
  ControlCommand bad = mixed_command();
  bad.torques[1] = 99.0F;
  rejected(bad, Rejection::kOutOfRange);
  EXPECT_EQ(out_.count, 0u);
}

TEST(Rejection, EveryReasonHasItsOwnName) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < kRejectionCount; ++i) {
    const std::string name = to_string(static_cast<Rejection>(i));
    EXPECT_NE(name, "unknown") << i;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), kRejectionCount);
  EXPECT_STREQ(to_string(Rejection::kNotOwner), "not_owner");
  EXPECT_STREQ(to_string(Rejection::kOutOfRange), "out_of_range");
}

}  // namespace
}  // namespace robotd::control
