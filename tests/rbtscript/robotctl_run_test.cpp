// robotctl run, the real binary, on robotd's simulated arm: what it prints and how it exits on a
// syntax error, a dry run with and without problems, a looping program and Ctrl-C mid-move.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <sys/types.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

#include "pose_tolerances.hpp"
#include "robotd_fixture.hpp"
#include "robotd_process.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kStillRad = 1e-3;  // a held arm's joints wander less than this

class RobotctlRunTest : public RobotdTest {
 protected:
  void SetUp() override { start_robotd(); }
  void TearDown() override {
    for (const std::string& path : programs_) std::filesystem::remove(path);
    RobotdTest::TearDown();
  }

  /// `text` in a file of its own; its path.
  std::string program(const std::string& name, const std::string& text) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("robotd-rbt-" + std::to_string(getpid()) + "-" + name + ".rbt"))
            .string();
    std::ofstream(path) << text;
    programs_.push_back(path);
    return path;
  }

  /// robotctl run `path` on the arm with `extra` arguments; stdout and stderr read as one.
  std::unique_ptr<ChildProcess> robotctl_run(const std::string& path, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> command{
        "-c", "exec \"$@\" 2>&1", "sh", ROBOTCTL_BINARY, "--domain", std::to_string(domain_.id()), "run",
        path, "--device",         "arm"};
    command.insert(command.end(), extra.begin(), extra.end());
    return std::make_unique<ChildProcess>("/bin/sh", command);
  }

  /// Everything `child` prints until it exits, and its exit status.
  static std::pair<std::string, std::optional<int>> finish(ChildProcess& child) {
    std::string text;
    while (auto line = child.read_line(30s)) text += *line + "\n";
    return {text, child.wait_exit(10s)};
  }

  std::vector<double> joints() { return joint_state("arm").position; }

  static void expect_same_joints(const std::vector<double>& after, const std::vector<double>& before,
                                 const std::string& when) {
    ASSERT_EQ(after.size(), before.size());
    for (std::size_t j = 0; j < before.size(); ++j)
      EXPECT_NEAR(after[j], before[j], kStillRad) << when << ", joint " << j + 1;
  }

  std::vector<std::string> programs_;
};

TEST_F(RobotctlRunTest, SyntaxErrorExits2NamingLineAndColumn) {
  const auto child = robotctl_run(program("syntax", "Begin()\n  MoveJ(1)\nEnd()\n"));
  const auto [output, status] = finish(*child);
  EXPECT_EQ(status, 2) << output;
  EXPECT_NE(output.find("line 2, column 3"), std::string::npos) << output;
  EXPECT_NE(output.find("found 'MoveJ'"), std::string::npos) << output;
}

TEST_F(RobotctlRunTest, DryRunListsProblemsAndExits1WithTheArmUnmoved) {
  const std::vector<double> before = joints();
  const auto child = robotctl_run(program("problems",
                                          "MoveJoint(10,0,0,0,0,0)\n"
                                          "MoveJoint(400,0,0,0,0,0)\n"
                                          "Output(1,HIGH)\n"),
                                  {"--dry-run"});
  const auto [output, status] = finish(*child);
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("line 2, column 1: MoveJoint(400,0,0,0,0,0)"), std::string::npos) << output;
  EXPECT_NE(output.find("line 3, column 1: Output(1,HIGH)"), std::string::npos) << output;
  EXPECT_NE(output.find("2 problem(s) for device 'arm'; nothing was sent to it"), std::string::npos) << output;
  expect_same_joints(joints(), before, "after the dry run");
}

TEST_F(RobotctlRunTest, CleanDryRunPrintsThePlanAndExits0WithTheArmUnmoved) {
  const std::vector<double> before = joints();
  const auto child = robotctl_run(
      program("clean", "MoveJoint(10,0,0,0,0,0,t=1)\nDelay(0.5)\nMoveJoint(0,0,0,0,0,0,t=1)\n"), {"--dry-run"});
  const auto [output, status] = finish(*child);
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("2 move(s) planned on 'arm', 2.50 s per pass; no problems"), std::string::npos) << output;
  expect_same_joints(joints(), before, "after the dry run");
}

TEST_F(RobotctlRunTest, TwoLoopsShowEachStatementAsItStarts) {
  const auto child =
      robotctl_run(program("loops", "Begin()\nMoveJoint(5,0,0,0,0,0,t=0.3)\nMoveJoint(0,0,0,0,0,0,t=0.3)\nLoop()\n"),
                   {"--loops", "2"});
  const auto [output, status] = finish(*child);
  EXPECT_EQ(status, 0) << output;
  for (const int pass : {1, 2}) {
    for (const char* line : {"line 1] Begin()", "line 2] MoveJoint(5,0,0,0,0,0,t=0.3)",
                             "line 3] MoveJoint(0,0,0,0,0,0,t=0.3)", "line 4] Loop()"}) {
      const std::string shown = "[pass " + std::to_string(pass) + ", " + line;
      EXPECT_NE(output.find(shown), std::string::npos) << "no '" << shown << "' in:\n" << output;
    }
  }
  EXPECT_NE(output.find("program ended after 2 pass(es), 8 statement(s)"), std::string::npos) << output;
}

TEST_F(RobotctlRunTest, CtrlCMidMoveExits130WithTheArmHeldWhereItStopped) {
  const auto child = robotctl_run(program("long", "MoveJoint(60,0,0,0,0,0,t=3)\n"));
  ASSERT_TRUE(wait_for_joints([](const JointState& s) { return s.position[0] > 10 * kDeg; }, 10s))
      << "the move did not start";
  child->send_signal(SIGINT);
  const auto [output, status] = finish(*child);
  EXPECT_EQ(status, 130) << output;
  EXPECT_NE(output.find("program stopped; the arm holds where it was"), std::string::npos) << output;
  const std::vector<double> stopped = joints();
  EXPECT_LT(stopped[0], 59 * kDeg) << "the move ran to its end";
  std::this_thread::sleep_for(300ms);
  expect_same_joints(joints(), stopped, "300 ms after the stop");
}

}  // namespace
}  // namespace robotd::testing
