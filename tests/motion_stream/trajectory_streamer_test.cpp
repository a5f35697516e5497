// The trajectory streamer through a real robotd and the simulated arm: it follows a trajectory to
// its end, holds the arm on the stop flag, and ends with a clear error on an e-stop. Functional
// only: nothing here depends on how fast the host is.
#include "robotd/motion/trajectory_streamer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "robotd_fixture.hpp"

namespace robotd::motion {
namespace {

using namespace std::chrono_literals;
using robotd::testing::RobotdTest;

constexpr double kDt = 0.01;

// A rest-to-rest quintic move of every joint from `start` by `delta` over `duration_s`.
SampledTrajectory quintic(const std::vector<double>& start, const std::vector<double>& delta, double duration_s) {
  SampledTrajectory trajectory{kDt, {}, {}};
  const auto steps = static_cast<std::size_t>(std::lround(duration_s / kDt));
  for (std::size_t k = 0; k <= steps; ++k) {
    const double tau = static_cast<double>(k) / static_cast<double>(steps);
    const double s = tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
    const double ds = 30 * tau * tau * (1 - tau) * (1 - tau) / duration_s;
    std::vector<double> positions;
    std::vector<double> velocities;
    for (std::size_t j = 0; j < start.size(); ++j) {
      positions.push_back(start[j] + delta[j] * s);
      velocities.push_back(delta[j] * ds);
    }
    trajectory.positions.push_back(std::move(positions));
    trajectory.velocities.push_back(std::move(velocities));
  }
  return trajectory;
}

class TrajectoryStreamerTest : public RobotdTest {
 protected:
  void SetUp() override {
    start_robotd();
    session_.emplace(acquire_device("arm"));
    auto streamer = TrajectoryStreamer::create(client(), *session_);
    ASSERT_TRUE(streamer) << streamer.error().message;
    streamer_.emplace(std::move(streamer.value()));
    start_ = joint_state().position;
  }
  void TearDown() override {
    streamer_.reset();
    session_.reset();
    RobotdTest::TearDown();
  }
  // The arm's positions after it has had `settle` to come to rest.
  std::vector<double> settled(std::chrono::milliseconds settle = 300ms) {
    std::this_thread::sleep_for(settle);
    return joint_state().position;
  }

  std::optional<Session> session_;
  std::optional<TrajectoryStreamer> streamer_;
  std::vector<double> start_;
  std::atomic<bool> stop_{false};
};

TEST_F(TrajectoryStreamerTest, FollowsATrajectoryToItsEndAndArrives) {
  const std::vector<double> delta{0.4, 0, -0.3, 0, 0.2, 0};
  std::vector<double> fractions;
  const auto report = streamer_->stream(quintic(start_, delta, 1.0), stop_,
                                        {.on_progress = [&](double f) { fractions.push_back(f); },
                                         .arrival = Arrival{.tolerance_rad = 0.01, .timeout = 5000ms}});
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report.value().end, StreamEnd::kCompleted);
  EXPECT_EQ(report.value().fraction_done, 1.0);
  EXPECT_GE(report.value().commands_sent, 1001U);  // the device's 1 ms period over 1 s, and the end
  EXPECT_NE(report.value().summary.find("arrived within 0.010 rad"), std::string::npos) << report.value().summary;
  ASSERT_FALSE(fractions.empty());
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);
  const std::vector<double> end = joint_state().position;
  for (std::size_t j = 0; j < delta.size(); ++j) EXPECT_NEAR(end[j], start_[j] + delta[j], 0.02) << "joint " << j;
}

TEST_F(TrajectoryStreamerTest, SpeedOnlyTrackingFollowsTheSpeedCurve) {
  const std::vector<double> delta{0.5, 0, 0, 0, 0, 0};
  const auto report = streamer_->stream(quintic(start_, delta, 1.0), stop_, {.tracking = Tracking::kSpeedOnly});
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report.value().end, StreamEnd::kCompleted);
  // No position correction: the arm goes the speed curve's way, most of its distance, and not past it.
  const double moved = settled()[0] - start_[0];
  EXPECT_GT(moved, 0.25);
  EXPECT_LT(moved, 0.55);
}

TEST_F(TrajectoryStreamerTest, TheStopFlagHoldsTheArmWhereItIsAndKeepsTheSession) {
  const std::vector<double> delta{1.0, 0, 0, 0, 0, 0};
  const auto report = streamer_->stream(quintic(start_, delta, 2.0), stop_, {.on_progress = [&](double f) {
                                          if (f >= 0.3) stop_ = true;
                                        }});
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report.value().end, StreamEnd::kStopped);
  EXPECT_GE(report.value().fraction_done, 0.3);
  EXPECT_LT(report.value().fraction_done, 0.5);
  EXPECT_EQ(report.value().summary.rfind("stopped at ", 0), 0U) << report.value().summary;
  EXPECT_NE(report.value().summary.find("holding at the measured position"), std::string::npos);
  const double held = settled()[0];
  EXPECT_LT(held - start_[0], 0.7) << "the arm went on towards the trajectory's end";
  EXPECT_NEAR(settled()[0], held, 0.005) << "the arm did not stay where it was held";
  EXPECT_TRUE(session_->info(2s)) << "the session ended";
}

TEST_F(TrajectoryStreamerTest, AnEstopMidTrajectoryEndsItWithAClearErrorAndTheArmStaysStill) {
  const std::vector<double> delta{1.0, 0, 0, 0, 0, 0};
  bool engaged = false;
  const auto report = streamer_->stream(quintic(start_, delta, 2.0), stop_, {.on_progress = [&](double f) {
                                          if (f >= 0.3 && !engaged) engaged = static_cast<bool>(client().estop("arm"));
                                        }});
  ASSERT_TRUE(engaged);
  ASSERT_FALSE(report) << report.value().summary;
  EXPECT_EQ(report.error().code, ErrorCode::kRefused);
  EXPECT_NE(report.error().message.find("ESTOP"), std::string::npos) << report.error().message;
  EXPECT_NE(report.error().message.find("the trajectory stopped at"), std::string::npos) << report.error().message;
  const double after = settled()[0];
  EXPECT_LT(after - start_[0], 0.7);
  EXPECT_NEAR(settled()[0], after, 0.005) << "the arm moved after the e-stop";
}

TEST_F(TrajectoryStreamerTest, ATrajectoryThatStartsAwayFromTheArmIsRefusedBeforeAnythingIsSent) {
  std::vector<double> elsewhere = start_;
  elsewhere[1] += 0.5;
  const auto report = streamer_->stream(quintic(elsewhere, std::vector<double>(6, 0.0), 0.1), stop_);
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(report.error().message.find("the trajectory starts 0.500 rad from where motor 1 of 'arm' is"),
            std::string::npos)
      << report.error().message;
}

TEST_F(TrajectoryStreamerTest, ATorqueSessionCannotStreamATrajectory) {
  session_.reset();
  Session torque = acquire_device("arm", {}, ControlMode::kTorque);
  const auto streamer = TrajectoryStreamer::create(client(), torque);
  ASSERT_FALSE(streamer);
  EXPECT_NE(streamer.error().message.find("is in TORQUE mode: a trajectory streams through a POSITION session"),
            std::string::npos)
      << streamer.error().message;
}

}  // namespace
}  // namespace robotd::motion
