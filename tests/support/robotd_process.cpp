#include "robotd_process.hpp"

#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <poll.h>
#include <signal.h>
#include <sstream>
#include <stdexcept>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#ifndef ROBOTD_BINARY
#error "ROBOTD_BINARY must point at the robotd executable under test"
#endif

extern char** environ;  // NOLINT

namespace robotd::testing {
namespace {

/// In a child just forked from `parent`: the kernel SIGKILLs it when the test process ends, however
/// it ends. A test that aborts, or that CTest kills on a timeout, would otherwise leave its robotd
/// running on the test's DDS domain, for the next test that takes that domain id to talk to.
/// (The signal follows the forking thread: tests start their processes from the test's thread.)
void end_with_parent(pid_t parent) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(127);  // the parent was already gone
}

std::string temp_path(const std::string& stem) {
  std::string pattern = "/tmp/robotd-test-" + stem + "-XXXXXX";
  const int fd = mkstemp(pattern.data());
  if (fd < 0) throw std::runtime_error("mkstemp failed");
  close(fd);
  return pattern;
}

std::vector<char*> c_strings(std::vector<std::string>& strings) {
  std::vector<char*> out;
  out.reserve(strings.size() + 1);
  for (auto& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

}  // namespace

nlohmann::json sim_arm_params(double joint2_load_nm) {
  nlohmann::json joints = nlohmann::json::array();
  for (int j = 1; j <= 6; ++j) {
    nlohmann::json joint = {{"name", "joint" + std::to_string(j)}};
    if (j == 2) joint["external_torque_nm"] = joint2_load_nm;
    joints.push_back(joint);
  }
  return {{"model", "test arm"},
          {"joint_defaults",
           {{"position_min_rad", -2.5},
            {"position_max_rad", 2.5},
            {"velocity_max_rad_s", 2.0},
            {"acceleration_max_rad_s2", 10.0},
            {"effort_max_nm", 40.0},
            {"kp_max", 500.0},
            {"kd_max", 50.0},
            {"default_kp", 300.0},
            {"default_kd", 10.0},
            {"inertia_kg_m2", 0.05},
            {"damping_nm_s_rad", 0.3}}},
          {"joints", joints}};
}

nlohmann::json sim_arm_config(int domain, const nlohmann::json& params, const nlohmann::json& device_overrides) {
  nlohmann::json device = {{"name", "arm"},
                           {"driver", "sim"},
                           {"rate_hz", 1000},
                           {"realtime", "prefer"},
                           {"params", params.is_null() ? sim_arm_params() : params}};
  device.update(device_overrides);
  return {{"daemon", {{"log_level", "info"}, {"status_rate_hz", 20}, {"session_status_period_ms", 200}}},
          {"dds", {{"domain_id", domain}, {"interface", "127.0.0.1"}, {"multicast", false}, {"peers", {"127.0.0.1"}}}},
          {"devices", {device}}};
}

ClientOptions client_options(int domain, const std::string& node_name) {
  ClientOptions options;
  options.domain_id = domain;
  options.node_name = node_name;
  options.service_timeout = std::chrono::milliseconds(3000);
  return options;
}

RobotdProcess::RobotdProcess(const nlohmann::json& config, std::vector<std::string> environment)
    : config_path_(temp_path("config")), log_path_(temp_path("log")) {
  std::ofstream(config_path_) << config.dump(2);
  std::vector<std::string> arguments{ROBOTD_BINARY, "--config", config_path_};
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) env.emplace_back(*e);
  env.insert(env.end(), environment.begin(), environment.end());
  auto argv = c_strings(arguments);
  auto envp = c_strings(env);
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    end_with_parent(parent);
    const int log_fd = open(log_path_.c_str(), O_WRONLY | O_TRUNC);
    dup2(log_fd, STDOUT_FILENO);
    dup2(log_fd, STDERR_FILENO);
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
}

RobotdProcess::~RobotdProcess() {
  if (!exit_status()) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  std::remove(config_path_.c_str());
  std::remove(log_path_.c_str());
}

bool RobotdProcess::wait_ready(Client& client, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (exit_status()) return false;
    auto devices = client.list_devices();
    if (devices) {
      bool running = !devices.value().empty();
      for (const auto& device : devices.value()) running = running && device.state == DeviceState::kRunning;
      if (running) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

std::optional<int> RobotdProcess::exit_status() {
  if (status_) return status_;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) {
    status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  return status_;
}

std::optional<int> RobotdProcess::wait_for_exit(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!exit_status() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return exit_status();
}

std::optional<int> RobotdProcess::terminate(std::chrono::milliseconds timeout) {
  if (!exit_status()) ::kill(pid_, SIGTERM);
  return wait_for_exit(timeout);
}

std::string RobotdProcess::log() const {
  std::ifstream file(log_path_);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

ChildProcess::ChildProcess(const std::string& program, const std::vector<std::string>& arguments) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  std::vector<std::string> args{program};
  args.insert(args.end(), arguments.begin(), arguments.end());
  auto argv = c_strings(args);
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    end_with_parent(parent);
    dup2(fds[1], STDOUT_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(fds[1]);
  stdout_fd_ = fds[0];
}

ChildProcess::~ChildProcess() {
  kill_hard();
  if (stdout_fd_ >= 0) close(stdout_fd_);
}

std::optional<std::string> ChildProcess::read_line(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (const auto newline = buffer_.find('\n'); newline != std::string::npos) {
      std::string line = buffer_.substr(0, newline);
      buffer_.erase(0, newline + 1);
      return line;
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return std::nullopt;
    pollfd fd{stdout_fd_, POLLIN, 0};
    if (poll(&fd, 1, static_cast<int>(left.count())) <= 0) return std::nullopt;
    char chunk[256];
    const ssize_t n = ::read(stdout_fd_, chunk, sizeof(chunk));
    if (n <= 0) return std::nullopt;
    buffer_.append(chunk, static_cast<std::size_t>(n));
  }
}

void ChildProcess::send_signal(int signal_number) const {
  if (pid_ > 0) ::kill(pid_, signal_number);
}

std::optional<int> ChildProcess::wait_exit(std::chrono::milliseconds timeout) {
  if (pid_ <= 0) return std::nullopt;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (waitpid(pid_, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  pid_ = -1;
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
}

void ChildProcess::kill_hard() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
}

}  // namespace robotd::testing
