// One device's RT loop, driven tick by tick at synthetic times: a recording driver stands in
// for the hardware, and the test plays the service side (control events, command snapshots,
// e-stop, maintenance, shutdown) through the DeviceChannel exactly as robotd does.
#include "device/control_loop.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "device/command_mailbox.hpp"
#include "device_models.hpp"

namespace robotd::device {
namespace {

using driver::JointCommandKind;
using ::testing::HasSubstr;

constexpr std::int64_t kMsNs = 1'000'000;
constexpr std::int64_t kPeriodNs = kMsNs;  // 1 kHz
constexpr double kDt = 0.001;

// Returns scripted feedback and records every frame it is asked to write.
class RecordingDriver final : public driver::Driver {
 public:
  RecordingDriver() { frames.reserve(4096); }

  Result<void> configure(const nlohmann::json& /*params*/) override { return {}; }
  driver::DeviceDescription describe() const override { return {}; }
  Result<void> connect() override { return {}; }
  void disconnect() noexcept override {}
  Result<void> recover() override { return {}; }
  Result<void> reset_zero(std::span<const int> /*joints*/) override { return {}; }
  void abort_maintenance() noexcept override { ++abort_requests; }

  driver::IoResult read(driver::Feedback& out, driver::FaultInfo& fault) noexcept override {
    ++reads;
    if (read_result == driver::IoResult::kOk) out = feedback;
    if (read_result == driver::IoResult::kFault || read_result == driver::IoResult::kDisconnected) {
      fault = fault_to_report;
    }
    return read_result;
  }
  driver::IoResult write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept override {
    frames.push_back(command);
    if (write_result != driver::IoResult::kOk) fault = fault_to_report;
    return write_result;
  }

  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& /*args*/) override {
    return make_error(ErrorCode::kRefused, "no op " + op);
  }
  driver::Diagnostics diagnostics() const override { return {}; }

  driver::Feedback feedback{};
  driver::IoResult read_result = driver::IoResult::kOk;
  driver::IoResult write_result = driver::IoResult::kOk;
  driver::FaultInfo fault_to_report{};
  std::vector<driver::CommandFrame> frames;
  int reads = 0;
  int abort_requests = 0;
};

control::JointTargetUpdate position_target(std::uint8_t joint, float position) {
  control::JointTargetUpdate update;
  update.joint = joint;
  update.fields = control::kHasPosition;
  update.position = position;
  return update;
}

control::JointTargetUpdate torque_target(std::uint8_t joint, float torque) {
  control::JointTargetUpdate update;
  update.joint = joint;
  update.fields = control::kHasTorque;
  update.torque = torque;
  return update;
}

// Device "legs": 3 joints, torque-capable, can damp and let go; position ±2 rad, 1 rad/s,
// 10 rad/s², default gains kp 50, kd 2. Feedback silence faults after 50 ms; the shutdown
// stop lasts 20 ms.
class ControlLoopTest : public ::testing::Test {
 protected:
  ControlLoopTest() {
    settings_.rate_hz = 1000;
    settings_.feedback_timeout_ns = 50 * kMsNs;
    settings_.safe_behavior = Behavior::kDamping;
    settings_.shutdown_behavior = Behavior::kDamping;
    settings_.shutdown_duration_ns = 20 * kMsNs;
    settings_.warmup_ticks = 1'000'000;
    loop_ = std::make_unique<ControlLoop>(driver_, model_, *channel_, settings_);
  }

  void tick() {
    now_ns_ += kPeriodNs;
    loop_->tick(now_ns_, now_ns_);
  }
  void run_ms(int ms) {
    for (int i = 0; i < ms; ++i) tick();
  }

  const driver::CommandFrame& frame() const {
    static const driver::CommandFrame kNone{};
    EXPECT_FALSE(driver_.frames.empty()) << "the loop wrote no frame";
    return driver_.frames.empty() ? kNone : driver_.frames.back();
  }
  const driver::JointCommand& joint(std::size_t j) const { return frame().joints[j]; }

  void set_measured(std::size_t j, double position, double velocity = 0) {
    driver_.feedback.joints[j].position_rad = position;
    driver_.feedback.joints[j].velocity_rad_s = velocity;
  }
  // The driver follows the position setpoint it is sent, as a stiff servo would.
  void follow_setpoint(std::size_t j) { set_measured(j, joint(j).position_rad, joint(j).velocity_rad_s); }

  // Steps of the setpoint of joint j over the frames written so far, from frame `first`.
  std::vector<double> setpoint_steps(std::size_t j, std::size_t first) const {
    std::vector<double> steps;
    for (std::size_t f = first + 1; f < driver_.frames.size(); ++f) {
      steps.push_back(driver_.frames[f].joints[j].position_rad - driver_.frames[f - 1].joints[j].position_rad);
    }
    return steps;
  }

  ControlEvent session_start(std::uint8_t slot, std::uint32_t generation, ControlMode mode,
                             std::initializer_list<std::size_t> motors, Behavior fallback = Behavior::kDamping,
                             std::int64_t timeout_ns = 1000 * kMsNs) const {
    ControlEvent event;
    event.type = ControlEvent::Type::kSessionStart;
    event.slot = slot;
    event.generation = generation;
    event.mode = mode;
    event.behavior = fallback;
    event.timeout_ns = timeout_ns;
    event.granted_ns = now_ns_;
    for (const auto motor : motors) event.motors.set(motor);
    event.default_kp.fill(kNoGain);
    event.default_kd.fill(kNoGain);
    return event;
  }
  void start(const ControlEvent& event) { ASSERT_TRUE(channel_->post(event)); }
  void start(std::uint8_t slot, std::uint32_t generation, ControlMode mode, std::initializer_list<std::size_t> motors) {
    start(session_start(slot, generation, mode, motors));
  }
  void release(std::uint8_t slot, std::uint32_t generation, Behavior behavior) {
    ControlEvent event;
    event.type = ControlEvent::Type::kSessionRelease;
    event.slot = slot;
    event.generation = generation;
    event.behavior = behavior;
    ASSERT_TRUE(channel_->post(event));
  }

  // What the command intake does with an accepted command, 1 µs after the last tick: write it
  // into the device's mailbox.
  void send(std::uint8_t slot, std::uint32_t generation, const control::JointTargetUpdate& update) {
    control::ValidatedCommand command;
    command.count = 1;
    command.joints[0] = update;
    mailbox_.post(slot, generation, command, now_ns_ + 1000, 0);
  }
  // A closed-loop client's answer to the state of tick `tick`.
  void answer(std::uint8_t slot, std::uint32_t generation, const control::JointTargetUpdate& update,
              std::uint64_t tick) {
    control::ValidatedCommand command;
    command.count = 1;
    command.joints[0] = update;
    mailbox_.post(slot, generation, command, now_ns_ + 1000, 0, tick);
  }
  // The state the loop published last.
  LoopState newest_state() {
    if (const LoopState* fresh = channel_->state.take()) state_ = *fresh;
    return state_;
  }
  void keepalive(std::uint8_t slot, std::uint32_t generation) {
    control::ValidatedCommand command;
    command.keepalive = true;
    mailbox_.post(slot, generation, command, now_ns_ + 1000, 0);
  }

  std::vector<LoopEvent> loop_events() {
    std::vector<LoopEvent> events;
    while (auto event = channel_->loop_events.pop()) events.push_back(*event);
    return events;
  }
  std::vector<LoopEvent> loop_events_of(LoopEvent::Type type) {
    std::vector<LoopEvent> matching;
    for (const auto& event : loop_events()) {
      if (event.type == type) matching.push_back(event);
    }
    return matching;
  }

  DeviceState device_state() const { return channel_->device_state.load(); }

  control::DeviceModel model_ = test::torque_chain("legs", 3);
  RecordingDriver driver_;
  std::unique_ptr<DeviceChannel> channel_ = std::make_unique<DeviceChannel>();
  LoopSettings settings_;
  std::unique_ptr<ControlLoop> loop_;
  std::int64_t now_ns_ = 1000 * kMsNs;
  CommandMailbox mailbox_{*channel_};
  LoopState state_;
};

TEST_F(ControlLoopTest, OwnedJointsFollowTheirTargetsInLimitedStepsWhileUnownedJointsStayUndriven) {
  start(0, 1, ControlMode::kPosition, {0, 1});
  tick();
  EXPECT_TRUE(joint(0).owned);
  EXPECT_TRUE(joint(1).owned);
  EXPECT_FALSE(joint(2).owned);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kNone);  // owned, but nothing commanded yet

  send(0, 1, position_target(0, 1.0F));
  send(0, 1, position_target(1, -0.5F));
  const std::size_t first = driver_.frames.size();
  run_ms(200);
  double previous[2] = {0.0, 0.0};
  for (std::size_t f = first; f < driver_.frames.size(); ++f) {
    const auto& joints = driver_.frames[f].joints;
    for (std::size_t j = 0; j < 2; ++j) {
      ASSERT_EQ(joints[j].kind, JointCommandKind::kPosition) << "frame " << f;
      ASSERT_LE(std::fabs(joints[j].position_rad - previous[j]), 1.0 * kDt + 1e-12) << "frame " << f;
      previous[j] = joints[j].position_rad;
    }
    ASSERT_EQ(joints[2].kind, JointCommandKind::kNone) << "frame " << f;
  }
  EXPECT_GT(joint(0).position_rad, 0.1);
  EXPECT_LT(joint(1).position_rad, -0.1);
  EXPECT_DOUBLE_EQ(joint(0).kp, 50.0);  // the joint's default gains
  EXPECT_DOUBLE_EQ(joint(0).kd, 2.0);
}

TEST_F(ControlLoopTest, TargetReachesTheDriverOnTheTickAfterItIsPublished) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 0.5F));
  tick();
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);
  EXPECT_GT(joint(0).position_rad, 0.0);
}

TEST_F(ControlLoopTest, PositionTargetsWithoutGainsUseTheSessionsDefaultGains) {
  ControlEvent event = session_start(0, 1, ControlMode::kPosition, {0, 1});
  event.default_kp[0] = 70.0F;
  event.default_kd[1] = 4.0F;
  start(event);
  tick();
  send(0, 1, position_target(0, 0.2F));
  send(0, 1, position_target(1, 0.2F));
  tick();
  EXPECT_DOUBLE_EQ(joint(0).kp, 70.0);
  EXPECT_DOUBLE_EQ(joint(0).kd, 2.0);
  EXPECT_DOUBLE_EQ(joint(1).kp, 50.0);
  EXPECT_DOUBLE_EQ(joint(1).kd, 4.0);
}

TEST_F(ControlLoopTest, TorqueSessionCommandsPureTorque) {
  set_measured(2, 0.25);
  start(0, 1, ControlMode::kTorque, {2});
  tick();
  send(0, 1, torque_target(2, 1.5F));
  tick();
  EXPECT_EQ(joint(2).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(2).kp, 0.0);
  EXPECT_DOUBLE_EQ(joint(2).kd, 0.0);
  EXPECT_DOUBLE_EQ(joint(2).torque_nm, 1.5);
  EXPECT_DOUBLE_EQ(joint(2).position_rad, 0.25);
}

TEST_F(ControlLoopTest, MixedSessionCommandsImpedanceWithTheCommandsGainsAndTorque) {
  start(0, 1, ControlMode::kMixed, {1});
  tick();
  control::JointTargetUpdate update;
  update.joint = 1;
  update.fields = control::kHasPosition | control::kHasKp | control::kHasKd | control::kHasTorque;
  update.position = 0.0F;
  update.kp = 30.0F;
  update.kd = 1.5F;
  update.torque = 0.75F;
  send(0, 1, update);
  tick();
  EXPECT_EQ(joint(1).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(1).kp, 30.0);
  EXPECT_DOUBLE_EQ(joint(1).kd, 1.5);
  EXPECT_DOUBLE_EQ(joint(1).torque_nm, 0.75);
  EXPECT_DOUBLE_EQ(joint(1).position_rad, 0.0);
}

TEST_F(ControlLoopTest, SilentSessionTimesOutIntoItsFallbackAndIsReported) {
  ControlEvent event = session_start(0, 1, ControlMode::kPosition, {0}, Behavior::kDamping, 20 * kMsNs);
  event.default_kd[0] = 3.5F;
  start(event);
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(20);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);  // 20 ms of silence is not yet too much
  EXPECT_TRUE(loop_events_of(LoopEvent::Type::kSessionTimedOut).empty());

  tick();
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
  EXPECT_DOUBLE_EQ(joint(0).kd, 3.5);
  EXPECT_FALSE(joint(0).owned);
  const auto timeouts = loop_events_of(LoopEvent::Type::kSessionTimedOut);
  ASSERT_EQ(timeouts.size(), 1u);
  EXPECT_EQ(timeouts[0].slot, 0);
  EXPECT_EQ(timeouts[0].generation, 1u);
  EXPECT_EQ(timeouts[0].behavior, Behavior::kDamping);
  EXPECT_EQ(timeouts[0].silence_ns, 21 * kMsNs - 1000);  // the command came 1 µs after its tick
}

TEST_F(ControlLoopTest, KeepalivesKeepASessionAlive) {
  start(session_start(0, 1, ControlMode::kPosition, {0}, Behavior::kDamping, 20 * kMsNs));
  tick();
  send(0, 1, position_target(0, 0.5F));
  for (int i = 0; i < 10; ++i) {
    run_ms(15);
    keepalive(0, 1);
  }
  EXPECT_TRUE(loop_events_of(LoopEvent::Type::kSessionTimedOut).empty());
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);
  EXPECT_TRUE(joint(0).owned);
}

TEST_F(ControlLoopTest, SessionThatNeverCommandsTimesOutFromItsGrant) {
  start(session_start(0, 1, ControlMode::kPosition, {0}, Behavior::kKeep, 20 * kMsNs));
  run_ms(21);
  const auto timeouts = loop_events_of(LoopEvent::Type::kSessionTimedOut);
  ASSERT_EQ(timeouts.size(), 1u);
  EXPECT_EQ(timeouts[0].silence_ns, 21 * kMsNs);
  EXPECT_EQ(timeouts[0].behavior, Behavior::kKeep);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);  // KEEP: held where it is
  EXPECT_DOUBLE_EQ(joint(0).position_rad, 0.0);
}

TEST_F(ControlLoopTest, TimeoutDampingWithoutSessionGainsUsesTheJointsDefaultDamping) {
  start(session_start(0, 1, ControlMode::kPosition, {1}, Behavior::kDamping, 20 * kMsNs));
  tick();
  send(0, 1, position_target(1, 0.5F));
  run_ms(21);
  EXPECT_EQ(joint(1).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(1).kp, 0.0);
  EXPECT_DOUBLE_EQ(joint(1).kd, 2.0);
}

TEST_F(ControlLoopTest, ReleaseAppliesTheReleaseBehaviourAndFreesTheJoint) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(10);
  release(0, 1, Behavior::kZeroTorque);
  tick();
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
  EXPECT_DOUBLE_EQ(joint(0).kd, 0.0);
  EXPECT_DOUBLE_EQ(joint(0).torque_nm, 0.0);
  EXPECT_FALSE(joint(0).owned);
  const auto released = loop_events_of(LoopEvent::Type::kSessionReleased);
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].generation, 1u);
  EXPECT_EQ(released[0].behavior, Behavior::kZeroTorque);
}

TEST_F(ControlLoopTest, ReleaseNamingAnEarlierGenerationOfTheSlotIsIgnored) {
  start(0, 2, ControlMode::kPosition, {0});
  tick();
  send(0, 2, position_target(0, 1.0F));
  tick();
  release(0, 1, Behavior::kZeroTorque);
  tick();
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);
  EXPECT_TRUE(joint(0).owned);
  EXPECT_TRUE(loop_events_of(LoopEvent::Type::kSessionReleased).empty());
}

TEST_F(ControlLoopTest, EstopDampsActiveJointsAndLeavesIdleJointsUndriven) {
  start(0, 1, ControlMode::kPosition, {0, 1});
  tick();
  send(0, 1, position_target(0, 1.0F));  // joint 1 is owned but never commanded
  run_ms(10);
  channel_->estop.store(true);
  tick();
  EXPECT_TRUE(frame().estop);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
  EXPECT_DOUBLE_EQ(joint(0).kd, 2.0);
  EXPECT_EQ(joint(1).kind, JointCommandKind::kNone);
  EXPECT_EQ(joint(2).kind, JointCommandKind::kNone);
  EXPECT_EQ(device_state(), DeviceState::kEstop);
  EXPECT_EQ(loop_events_of(LoopEvent::Type::kEstopApplied).size(), 1u);
}

TEST_F(ControlLoopTest, TargetsAreNotAppliedWhileEstopped) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  tick();
  channel_->estop.store(true);
  tick();
  send(0, 1, position_target(0, -1.0F));
  run_ms(5);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
}

TEST_F(ControlLoopTest, EstopResetHoldsTrackingJointsWhereTheyAreMeasuredInsteadOfResumingTheTarget) {
  start(0, 1, ControlMode::kPosition, {0, 1});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(50);
  channel_->estop.store(true);
  tick();
  set_measured(0, 0.3);  // the damped joint sagged while e-stopped
  run_ms(5);
  channel_->estop.store(false);
  tick();
  EXPECT_FALSE(frame().estop);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);
  EXPECT_DOUBLE_EQ(joint(0).position_rad, 0.3);
  EXPECT_DOUBLE_EQ(joint(0).velocity_rad_s, 0.0);
  EXPECT_EQ(joint(1).kind, JointCommandKind::kNone);  // idle before, idle after
  EXPECT_EQ(device_state(), DeviceState::kRunning);
  EXPECT_EQ(loop_events_of(LoopEvent::Type::kEstopCleared).size(), 1u);
  run_ms(100);
  EXPECT_DOUBLE_EQ(joint(0).position_rad, 0.3);
}

TEST_F(ControlLoopTest, DriverFaultLatchesWithItsTextAndFreezesTheBlackBox) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(10);
  driver_.read_result = driver::IoResult::kFault;
  driver_.fault_to_report.set(42, "overcurrent on joint 0");
  tick();
  EXPECT_EQ(device_state(), DeviceState::kFault);
  const std::vector<LoopEvent> events = loop_events();
  const auto latched = std::find_if(events.begin(), events.end(),
                                    [](const LoopEvent& e) { return e.type == LoopEvent::Type::kFaultLatched; });
  ASSERT_NE(latched, events.end());
  EXPECT_EQ(latched->fault.code, 42);
  EXPECT_STREQ(latched->fault.text.data(), "overcurrent on joint 0");
  EXPECT_TRUE(std::any_of(events.begin(), events.end(),
                          [](const LoopEvent& e) { return e.type == LoopEvent::Type::kBlackBoxFrozen; }));
  EXPECT_TRUE(channel_->black_box_frozen.load());
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);  // damped: the safe behaviour

  const std::uint64_t recorded = channel_->black_box_next.load();
  driver_.read_result = driver::IoResult::kOk;  // the fault stays latched though the link recovers
  run_ms(10);
  EXPECT_EQ(device_state(), DeviceState::kFault);
  EXPECT_EQ(channel_->black_box_next.load(), recorded);
}

TEST_F(ControlLoopTest, LostLinkWithoutAFaultCodeLatchesTheLinkLostFault) {
  tick();
  driver_.read_result = driver::IoResult::kDisconnected;
  driver_.fault_to_report.set(0, "socket closed");
  tick();
  EXPECT_EQ(device_state(), DeviceState::kFault);
  const auto latched = loop_events_of(LoopEvent::Type::kFaultLatched);
  ASSERT_EQ(latched.size(), 1u);
  EXPECT_EQ(latched[0].fault.code, kFaultLinkLost);
  EXPECT_STREQ(latched[0].fault.text.data(), "socket closed");
}

TEST_F(ControlLoopTest, BlackBoxRecordsEveryTick) {
  run_ms(3);
  ASSERT_EQ(channel_->black_box_next.load(), 3u);
  const BlackBoxRecord& last = channel_->black_box[2];
  EXPECT_EQ(last.tick, 3u);
  EXPECT_EQ(last.time_ns, now_ns_);
  EXPECT_EQ(last.joint_count, 3);
}

TEST_F(ControlLoopTest, SilentFeedbackLatchesTheNoFeedbackFault) {
  tick();
  driver_.read_result = driver::IoResult::kNoNewData;
  run_ms(50);
  EXPECT_EQ(device_state(), DeviceState::kRunning);  // 50 ms is the limit, not beyond it
  tick();
  EXPECT_EQ(device_state(), DeviceState::kFault);
  const auto latched = loop_events_of(LoopEvent::Type::kFaultLatched);
  ASSERT_EQ(latched.size(), 1u);
  EXPECT_EQ(latched[0].fault.code, kFaultNoFeedback);
  EXPECT_THAT(latched[0].fault.text.data(), HasSubstr("no feedback from the driver for 51 ms"));
}

TEST_F(ControlLoopTest, NothingIsWrittenBeforeTheFirstFeedback) {
  driver_.read_result = driver::IoResult::kNoNewData;
  run_ms(5);
  EXPECT_TRUE(driver_.frames.empty());
  EXPECT_EQ(device_state(), DeviceState::kConnecting);
  driver_.read_result = driver::IoResult::kOk;
  tick();
  EXPECT_EQ(driver_.frames.size(), 1u);
  EXPECT_EQ(device_state(), DeviceState::kRunning);
}

TEST_F(ControlLoopTest, MaintenanceStopsDriverIoAndClearingItWithTheFaultHoldsJointsWhereMeasured) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(20);
  driver_.read_result = driver::IoResult::kFault;
  driver_.fault_to_report.set(7, "encoder error");
  tick();
  ASSERT_EQ(device_state(), DeviceState::kFault);

  channel_->maintenance_requested.store(true);
  tick();
  EXPECT_TRUE(channel_->maintenance_active.load());
  EXPECT_EQ(device_state(), DeviceState::kMaintenance);
  const int reads = driver_.reads;
  const std::size_t writes = driver_.frames.size();
  run_ms(10);
  EXPECT_EQ(driver_.reads, reads);
  EXPECT_EQ(driver_.frames.size(), writes);

  // The maintenance thread recovered the device; the joint now rests at 0.2 rad.
  driver_.read_result = driver::IoResult::kOk;
  set_measured(0, 0.2);
  channel_->maintenance_clears_fault.store(true);
  channel_->maintenance_requested.store(false);
  tick();
  EXPECT_FALSE(channel_->maintenance_active.load());
  EXPECT_EQ(device_state(), DeviceState::kRunning);
  const LoopState* state = channel_->state.take();
  ASSERT_NE(state, nullptr);
  EXPECT_EQ(state->fault.code, 0);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);
  EXPECT_DOUBLE_EQ(joint(0).position_rad, 0.2);
  EXPECT_DOUBLE_EQ(joint(0).velocity_rad_s, 0.0);
}

TEST_F(ControlLoopTest, TargetOfAnEndedSessionIsNotAppliedAndCountsAsStale) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  release(0, 1, Behavior::kZeroTorque);
  tick();
  send(0, 1, position_target(0, 1.0F));  // accepted just before the release, delivered after
  tick();
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
  EXPECT_EQ(channel_->dropped_stale.load(), 1u);
}

TEST_F(ControlLoopTest, TargetOfAReplacedSessionIsDroppedAndTheNewSessionsTargetIsApplied) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  release(0, 1, Behavior::kKeep);
  start(1, 2, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, -1.0F));  // the old session's late target
  tick();
  EXPECT_EQ(channel_->dropped_stale.load(), 1u);
  EXPECT_DOUBLE_EQ(joint(0).position_rad, 0.0);  // held, not moving toward -1
  send(1, 2, position_target(0, 1.0F));
  tick();
  EXPECT_GT(joint(0).position_rad, 0.0);
  EXPECT_EQ(channel_->dropped_stale.load(), 1u);
}

TEST_F(ControlLoopTest, TargetThatArrivesBeforeItsSessionStartIsAppliedOnceTheStartArrives) {
  // The service posts the start event before the client can command, but the loop may take the
  // command snapshot in the same tick after it drained the events: the target must wait, not be
  // discarded.
  tick();
  send(0, 1, position_target(0, 1.0F));
  tick();
  EXPECT_EQ(joint(0).kind, JointCommandKind::kNone);
  EXPECT_EQ(channel_->dropped_stale.load(), 0u);
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  EXPECT_EQ(joint(0).kind, JointCommandKind::kPosition);
  EXPECT_GT(joint(0).position_rad, 0.0);
  EXPECT_EQ(channel_->dropped_stale.load(), 0u);
}

TEST_F(ControlLoopTest, ShutdownEndsSessionsAppliesTheShutdownBehaviourAndFinishesAfterItsDuration) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(10);
  channel_->shutdown_requested.store(true);
  tick();
  const auto ended = loop_events_of(LoopEvent::Type::kSessionEndedByShutdown);
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].behavior, Behavior::kDamping);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
  EXPECT_DOUBLE_EQ(joint(0).kd, 2.0);
  EXPECT_EQ(joint(1).kind, JointCommandKind::kNone);
  EXPECT_FALSE(loop_->finished());

  run_ms(19);
  EXPECT_FALSE(loop_->finished());
  tick();
  EXPECT_TRUE(loop_->finished());
  EXPECT_EQ(device_state(), DeviceState::kStopped);
}

TEST_F(ControlLoopTest, StateIsPublishedEveryTickWithTheLatestFeedback) {
  set_measured(1, -0.4);
  run_ms(2);
  const LoopState* state = channel_->state.take();
  ASSERT_NE(state, nullptr);
  EXPECT_EQ(state->tick, 2u);
  EXPECT_EQ(state->time_ns, now_ns_);
  EXPECT_EQ(state->state, DeviceState::kRunning);
  EXPECT_EQ(state->feedback.joint_count, 3u);
  EXPECT_DOUBLE_EQ(state->feedback.joints[1].position_rad, -0.4);
  EXPECT_EQ(channel_->ticks.load(), 2u);
}

// --- the defects the randomized safety test found (tests/safety), one example each ---------

control::JointTargetUpdate mixed_target(std::uint8_t joint, float position, float kp, float kd, float torque) {
  control::JointTargetUpdate update;
  update.joint = joint;
  update.fields = control::kHasPosition | control::kHasKp | control::kHasKd | control::kHasTorque;
  update.position = position;
  update.kp = kp;
  update.kd = kd;
  update.torque = torque;
  return update;
}

TEST_F(ControlLoopTest, ATargetAcceptedBeforeAnEstopIsNeverResumedAfterItsReset) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.5F));
  run_ms(50);
  channel_->estop.store(true);
  send(0, 1, position_target(0, 1.5F));  // the client streams on: accepted as the e-stop lands
  tick();
  set_measured(0, 0.3);  // the damped joint sagged
  run_ms(500);
  channel_->estop.store(false);
  const std::size_t reset = driver_.frames.size();
  run_ms(100);
  for (std::size_t f = reset; f < driver_.frames.size(); ++f) {
    ASSERT_DOUBLE_EQ(driver_.frames[f].joints[0].position_rad, 0.3) << "frame " << f;
  }
  EXPECT_GE(channel_->dropped_stale.load(), 1U);
  send(0, 1, position_target(0, 0.5F));  // what the client sends after the reset moves the joint
  tick();
  EXPECT_GT(joint(0).position_rad, 0.3);
}

TEST_F(ControlLoopTest, ATorqueAcceptedBeforeAnEstopIsNotReappliedOnTheResetTick) {
  start(0, 1, ControlMode::kTorque, {2});
  tick();
  send(0, 1, torque_target(2, 4.5F));
  run_ms(10);
  channel_->estop.store(true);
  send(0, 1, torque_target(2, 4.5F));
  run_ms(20);
  channel_->estop.store(false);
  tick();
  EXPECT_DOUBLE_EQ(joint(2).torque_nm, 0.0);
  EXPECT_EQ(joint(2).kind, JointCommandKind::kPosition);  // held where it is measured
}

TEST_F(ControlLoopTest, AfterARecoverTheJointHoldsInsteadOfHeadingForTheOldTarget) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(20);
  driver_.read_result = driver::IoResult::kDisconnected;
  send(0, 1, position_target(0, 1.0F));
  tick();
  channel_->maintenance_requested.store(true);
  tick();
  driver_.read_result = driver::IoResult::kOk;
  set_measured(0, -0.2);
  channel_->maintenance_clears_fault.store(true);
  channel_->maintenance_requested.store(false);
  tick();
  run_ms(50);
  EXPECT_EQ(device_state(), DeviceState::kRunning);
  EXPECT_DOUBLE_EQ(joint(0).position_rad, -0.2);
}

TEST_F(ControlLoopTest, AJointMeasuredBeyondItsLimitComesBackInsideUnderTheLimitsWithoutAStep) {
  set_measured(0, 2.6);  // 0.6 rad above position_max (a narrowed limit, a sagged arm)
  start(0, 1, ControlMode::kMixed, {0});
  tick();
  send(0, 1, mixed_target(0, 1.9F, 40.0F, 2.0F, 0.0F));
  const std::size_t first = driver_.frames.size();
  for (int i = 0; i < 2000; ++i) {
    tick();
    follow_setpoint(0);
  }
  EXPECT_NEAR(driver_.frames[first].joints[0].position_rad, 2.6, 1e-4);  // starts where it is
  double previous = driver_.frames[first].joints[0].velocity_rad_s * kDt;
  for (const double step : setpoint_steps(0, first)) {
    ASSERT_LE(std::fabs(step), 1.0 * kDt + 1e-12);                    // velocity limit
    ASSERT_LE(std::fabs(step - previous), 10.0 * kDt * kDt + 1e-12);  // acceleration limit
    previous = step;
  }
  EXPECT_DOUBLE_EQ(joint(0).position_rad, static_cast<double>(1.9F));
}

// What Device::narrow_limits hands the loop: joint 0's position range narrowed to `low`..`high`.
void narrow_joint0(DeviceChannel& channel, const control::DeviceModel& model, double low, double high) {
  LimitSet& limits = channel.limits.write_buffer();
  for (std::size_t j = 0; j < model.joint_count(); ++j) limits.joints[j] = motion_limits(model.limits[j]);
  limits.joints[0].position_min = low;
  limits.joints[0].position_max = high;
  channel.limits.publish();
}

TEST_F(ControlLoopTest, LimitsNarrowedAtRunTimeHoldFromTheNextTickAndStopAStreamInsideThem) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.9F));
  run_ms(100);  // under way, at most 0.1 rad out
  ASSERT_LT(joint(0).position_rad, 0.2);
  narrow_joint0(*channel_, model_, -2.0, 0.5);
  const std::size_t first = driver_.frames.size() - 1;
  for (int i = 0; i < 3000; ++i) {
    send(0, 1, position_target(0, 1.9F));  // the client keeps asking for the old range
    tick();
    follow_setpoint(0);
  }
  double previous = driver_.frames[first].joints[0].velocity_rad_s * kDt;
  for (std::size_t f = first + 1; f < driver_.frames.size(); ++f) {
    const double position = driver_.frames[f].joints[0].position_rad;
    const double step = position - driver_.frames[f - 1].joints[0].position_rad;
    ASSERT_LE(position, 0.5) << "frame " << f;
    ASSERT_LE(std::fabs(step), 1.0 * kDt + 1e-12) << "frame " << f;
    ASSERT_LE(std::fabs(step - previous), 10.0 * kDt * kDt + 1e-12) << "frame " << f;
    previous = step;
  }
  EXPECT_DOUBLE_EQ(joint(0).position_rad, 0.5);
}

TEST_F(ControlLoopTest, AJointOutsideLimitsNarrowedAtRunTimeComesBackInsideUnderTheLimitsWithoutAStep) {
  start(session_start(0, 1, ControlMode::kPosition, {0}, Behavior::kKeep, 60'000 * kMsNs));
  tick();
  send(0, 1, position_target(0, 1.5F));
  for (int i = 0; i < 3000; ++i) {
    tick();
    follow_setpoint(0);
  }
  ASSERT_DOUBLE_EQ(joint(0).position_rad, static_cast<double>(1.5F));
  narrow_joint0(*channel_, model_, -2.0, 1.0);  // the joint now stands 0.5 rad beyond its maximum
  const std::size_t first = driver_.frames.size() - 1;
  for (int i = 0; i < 3000; ++i) {
    tick();
    follow_setpoint(0);
  }
  double previous = 0;
  for (const double step : setpoint_steps(0, first)) {
    ASSERT_LE(step, 1e-12);                                           // never further out
    ASSERT_LE(std::fabs(step), 1.0 * kDt + 1e-12);                    // velocity limit
    ASSERT_LE(std::fabs(step - previous), 10.0 * kDt * kDt + 1e-12);  // acceleration limit
    previous = step;
  }
  EXPECT_DOUBLE_EQ(joint(0).position_rad, 1.0);
}

TEST_F(ControlLoopTest, MixedSessionsKeepFallbackDropsTheClientsTorqueAndGains) {
  start(session_start(0, 1, ControlMode::kMixed, {1}, Behavior::kKeep, 20 * kMsNs));
  tick();
  send(0, 1, mixed_target(1, 0.2F, 80.0F, 6.0F, 4.9F));
  run_ms(25);  // timed out
  ASSERT_EQ(loop_events_of(LoopEvent::Type::kSessionTimedOut).size(), 1U);
  run_ms(5000);
  EXPECT_FALSE(joint(1).owned);
  EXPECT_DOUBLE_EQ(joint(1).torque_nm, 0.0);
  EXPECT_DOUBLE_EQ(joint(1).kp, 50.0);  // the joint's defaults (the session gave none)
  EXPECT_DOUBLE_EQ(joint(1).kd, 2.0);
}

TEST_F(ControlLoopTest, KeepOnAMovingJointBrakesToRestWithoutOvershootingAndComingBack) {
  start(session_start(0, 1, ControlMode::kPosition, {0}, Behavior::kKeep, 20 * kMsNs));
  tick();
  send(0, 1, position_target(0, 1.9F));
  run_ms(15);
  for (int i = 0; i < 300; ++i) {  // up to speed (1 rad/s) with fresh targets
    send(0, 1, position_target(0, 1.9F));
    tick();
  }
  ASSERT_NEAR(joint(0).velocity_rad_s, 1.0, 1e-9);
  const std::size_t first = driver_.frames.size() - 1;
  run_ms(400);  // silent: times out into KEEP
  const std::vector<double> steps = setpoint_steps(0, first);
  for (std::size_t i = 1; i < steps.size(); ++i) {
    ASSERT_GE(steps[i], -1e-12) << "step " << i << " turns back";
    ASSERT_LE(steps[i], steps[i - 1] + 1e-15) << "step " << i << " speeds up";
  }
  EXPECT_DOUBLE_EQ(joint(0).velocity_rad_s, 0.0);
}

TEST_F(ControlLoopTest, NonFiniteFeedbackNeverReachesTheDriverAndFaultsNamingTheJoint) {
  set_measured(1, 0.25);
  tick();
  driver_.feedback.joints[1].position_rad = std::nan("");
  start(0, 1, ControlMode::kPosition, {1});
  tick();
  send(0, 1, position_target(1, 1.0F));
  run_ms(49);  // 50 ms since the last finite reading: the feedback timeout, not beyond it
  for (const auto& frame : driver_.frames) {
    ASSERT_TRUE(std::isfinite(frame.joints[1].position_rad));
    ASSERT_TRUE(std::isfinite(frame.joints[1].velocity_rad_s));
  }
  EXPECT_NEAR(driver_.frames[2].joints[1].position_rad, 0.25, 1e-3);  // from the last finite reading
  EXPECT_EQ(device_state(), DeviceState::kRunning);
  tick();
  EXPECT_EQ(device_state(), DeviceState::kFault);
  const auto latched = loop_events_of(LoopEvent::Type::kFaultLatched);
  ASSERT_EQ(latched.size(), 1U);
  EXPECT_EQ(latched[0].fault.code, kFaultNonFiniteFeedback);
  EXPECT_THAT(latched[0].fault.text.data(), HasSubstr("joint 'j1' has reported no finite position"));
}

TEST_F(ControlLoopTest, ADeviceIsNotRunningUntilEveryJointHasAFiniteReading) {
  driver_.feedback.joints[0].velocity_rad_s = std::numeric_limits<double>::infinity();
  run_ms(5);
  EXPECT_EQ(device_state(), DeviceState::kConnecting);
  driver_.feedback.joints[0].velocity_rad_s = 0;
  tick();
  EXPECT_EQ(device_state(), DeviceState::kRunning);
}

TEST_F(ControlLoopTest, AnEstopDuringMaintenanceAbortsItAndReachesTheDriverOnTheTickItEnds) {
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(10);
  channel_->maintenance_requested.store(true);
  tick();
  ASSERT_TRUE(channel_->maintenance_active.load());
  run_ms(3);
  EXPECT_EQ(driver_.abort_requests, 0);
  channel_->estop.store(true);
  tick();
  EXPECT_EQ(driver_.abort_requests, 1);
  tick();
  EXPECT_EQ(driver_.abort_requests, 2);  // asked again every tick until the driver lets go
  const std::size_t written = driver_.frames.size();
  channel_->maintenance_requested.store(false);  // the maintenance thread gave up
  tick();
  ASSERT_EQ(driver_.frames.size(), written + 1);
  EXPECT_TRUE(frame().estop);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kImpedance);  // damped: the safe behaviour needs no position
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
}

TEST_F(ControlLoopTest, WithoutFreshFeedbackAnEstopFrameLeavesAHeldJointUndriven) {
  settings_.safe_behavior = Behavior::kKeep;  // a position-only arm holds on e-stop
  loop_ = std::make_unique<ControlLoop>(driver_, model_, *channel_, settings_);
  start(0, 1, ControlMode::kPosition, {0});
  tick();
  send(0, 1, position_target(0, 1.0F));
  run_ms(10);
  channel_->maintenance_requested.store(true);
  tick();
  channel_->estop.store(true);
  tick();
  channel_->maintenance_requested.store(false);
  driver_.read_result = driver::IoResult::kNoNewData;  // the reconnected device has not answered yet
  tick();
  EXPECT_TRUE(frame().estop);
  EXPECT_EQ(joint(0).kind, JointCommandKind::kNone);  // nothing measured since: nothing to hold
}

TEST_F(ControlLoopTest, MaintenanceIsDeclinedWhileAnEstopIsEngaged) {
  tick();
  channel_->estop.store(true);
  channel_->maintenance_requested.store(true);
  tick();
  EXPECT_FALSE(channel_->maintenance_active.load());
  EXPECT_TRUE(channel_->maintenance_declined.load());
  EXPECT_TRUE(frame().estop);
}

TEST_F(ControlLoopTest, TheEstopFrameGoesOutBeforeTheDeviceHasEverBeenMeasured) {
  driver_.read_result = driver::IoResult::kNoNewData;
  tick();
  EXPECT_TRUE(driver_.frames.empty());
  channel_->estop.store(true);
  tick();
  ASSERT_EQ(driver_.frames.size(), 1U);
  EXPECT_TRUE(frame().estop);
  EXPECT_GT(channel_->estop_reached_ns.load(), 0);
}

TEST_F(ControlLoopTest, AnEstopFrameTakenByADeviceInFaultHasReachedItAndOneBehindALostLinkHasNot) {
  tick();
  driver_.fault_to_report.set(42, "joint 3 over temperature");
  driver_.read_result = driver::IoResult::kFault;
  driver_.write_result = driver::IoResult::kFault;  // the device reports its fault, and takes the frame
  tick();
  ASSERT_EQ(device_state(), DeviceState::kFault);
  channel_->estop.store(true);
  tick();
  EXPECT_TRUE(frame().estop);
  EXPECT_GT(channel_->estop_reached_ns.load(), 0);

  channel_->estop.store(false);
  tick();
  EXPECT_EQ(channel_->estop_reached_ns.load(), 0);
  driver_.read_result = driver::IoResult::kDisconnected;
  driver_.write_result = driver::IoResult::kDisconnected;
  channel_->estop.store(true);
  run_ms(5);
  EXPECT_TRUE(frame().estop) << "robotd keeps sending the e-stop every tick";
  EXPECT_EQ(channel_->estop_reached_ns.load(), 0);
}

TEST_F(ControlLoopTest, AShutdownDuringMaintenanceAbortsItAndThenRunsTheShutdownStop) {
  tick();
  channel_->maintenance_requested.store(true);
  tick();
  channel_->shutdown_requested.store(true);
  run_ms(3);
  EXPECT_EQ(driver_.abort_requests, 3);
  EXPECT_FALSE(loop_->finished());
  channel_->maintenance_requested.store(false);
  run_ms(20);
  EXPECT_FALSE(loop_->finished());  // the stop lasts shutdown_duration from when it could begin
  tick();
  EXPECT_TRUE(loop_->finished());
}

TEST_F(ControlLoopTest, SessionsTimeOutOnTimeWhileMaintenanceHoldsTheDriver) {
  start(session_start(0, 1, ControlMode::kPosition, {0}, Behavior::kDamping, 20 * kMsNs));
  tick();
  channel_->maintenance_requested.store(true);
  run_ms(19);  // 20 ms since the grant
  EXPECT_TRUE(loop_events_of(LoopEvent::Type::kSessionTimedOut).empty());
  tick();
  EXPECT_EQ(loop_events_of(LoopEvent::Type::kSessionTimedOut).size(), 1U);
}

// --- closed loop ----------------------------------------------------------------------------

TEST_F(ControlLoopTest, EachTicksStateCarriesItsNumberAndDeadlineAndAnsweredTicksAreBooked) {
  start(0, 1, ControlMode::kTorque, {0, 1, 2});
  tick();
  for (int i = 0; i < 20; ++i) {
    const LoopState state = newest_state();
    ASSERT_TRUE(state.state_due);
    EXPECT_EQ(state.deadline_ns, now_ns_);  // tick() runs each tick at its deadline
    EXPECT_EQ(state.period_ns, kPeriodNs);
    answer(0, 1, torque_target(0, 0.5F), state.tick);
    tick();
    EXPECT_DOUBLE_EQ(joint(0).torque_nm, 0.5);  // the answer is applied on the next tick
  }
  const AnswerCounts answers = newest_state().answers[0];
  EXPECT_EQ(answers.generation, 1U);
  EXPECT_TRUE(answers.closed_loop);
  EXPECT_EQ(answers.to_answer, 20U);
  EXPECT_EQ(answers.in_time, 20U);
  EXPECT_FLOAT_EQ(answers.success_rate, 1.0F);
}

TEST_F(ControlLoopTest, AClosedLoopSessionBelowItsMinimumFallsBackWhenItAskedTo) {
  ControlEvent event = session_start(0, 1, ControlMode::kTorque, {0, 1, 2}, Behavior::kDamping);
  event.min_success_rate = 0.9F;
  event.on_low_success_rate = LowRateAction::kFallback;
  start(event);
  tick();
  // Every other tick answered: 50 %.
  for (int i = 0; i < 2 * static_cast<int>(kSuccessRateWindowTicks) + 4; ++i) {
    if (i % 2 == 0) answer(0, 1, torque_target(0, 0.5F), newest_state().tick);
    tick();
  }
  const auto ended = loop_events_of(LoopEvent::Type::kSessionRateTooLow);
  ASSERT_EQ(ended.size(), 1U);
  EXPECT_EQ(ended[0].generation, 1U);
  EXPECT_EQ(ended[0].behavior, Behavior::kDamping);
  EXPECT_NEAR(ended[0].success_rate, 0.5, 0.02);
  // The session's fallback: damping, not the torque it commanded.
  EXPECT_FALSE(joint(0).owned);
  EXPECT_DOUBLE_EQ(joint(0).kp, 0.0);
  EXPECT_DOUBLE_EQ(joint(0).torque_nm, 0.0);
  // Its next answer moves nothing: the session is over.
  answer(0, 1, torque_target(0, 0.7F), newest_state().tick);
  tick();
  EXPECT_DOUBLE_EQ(joint(0).torque_nm, 0.0);
}

TEST_F(ControlLoopTest, AClosedLoopSessionBelowItsMinimumThatOnlyWarnsKeepsItsMotors) {
  ControlEvent event = session_start(0, 1, ControlMode::kTorque, {0, 1, 2});
  event.min_success_rate = 0.9F;
  event.on_low_success_rate = LowRateAction::kWarn;
  start(event);
  tick();
  for (int i = 0; i < 2 * static_cast<int>(kSuccessRateWindowTicks) + 4; ++i) {
    if (i % 2 == 0) answer(0, 1, torque_target(0, 0.5F), newest_state().tick);
    tick();
  }
  const auto events = loop_events();
  EXPECT_EQ(std::count_if(events.begin(), events.end(),
                          [](const LoopEvent& e) { return e.type == LoopEvent::Type::kSuccessRateLow; }),
            1);
  EXPECT_TRUE(std::none_of(events.begin(), events.end(), [](const LoopEvent& e) { return ends_session(e.type); }));
  EXPECT_TRUE(newest_state().answers[0].rate_low);
  answer(0, 1, torque_target(0, 0.7F), newest_state().tick);
  tick();
  EXPECT_FLOAT_EQ(static_cast<float>(joint(0).torque_nm), 0.7F);
}

}  // namespace
}  // namespace robotd::device
