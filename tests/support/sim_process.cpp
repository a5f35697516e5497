#include "sim_process.hpp"

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <stdexcept>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <system_error>
#include <thread>
#include <unistd.h>

extern char** environ;  // NOLINT

namespace robotd::testing {
namespace {

constexpr auto kReadyTimeout = std::chrono::seconds(5);

std::string errno_text(int error) { return std::generic_category().message(error); }

std::string base_name(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

/// A connected unix stream socket to `path`, or -1 with `error` set.
int connect_to(const std::string& path, int& error) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.size() >= sizeof(address.sun_path)) {
    error = ENAMETOOLONG;
    return -1;
  }
  path.copy(address.sun_path, sizeof(address.sun_path) - 1);
  const int sock = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (sock < 0) {
    error = errno;
    return -1;
  }
  if (connect(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {  // NOLINT
    error = errno;
    close(sock);
    return -1;
  }
  return sock;
}

}  // namespace

std::string SimProcess::unique_path(const std::string& stem, const std::string& suffix) {
  static std::atomic<int> counter{0};
  return "/tmp/robotd-" + stem + "-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + suffix;
}

SimProcess::SimProcess(std::string program, const std::string& stem, const std::string& link_option,
                       std::string link_path, std::vector<std::string> extra_args)
    : program_(std::move(program)),
      link_path_(std::move(link_path)),
      control_path_(unique_path(stem + "-ctl")),
      arguments_{link_option, link_path_, "--control", control_path_, "--rt-priority", std::to_string(kSimRtPriority)} {
  arguments_.insert(arguments_.end(), extra_args.begin(), extra_args.end());
  start();
}

SimProcess::~SimProcess() {
  kill_hard();
  if (link_path_.starts_with('/')) unlink(link_path_.c_str());  // a path, not a port number
  unlink(control_path_.c_str());
}

void SimProcess::start() {
  child_ = std::make_unique<ChildProcess>(program_, arguments_);
  const auto line = child_->read_line(kReadyTimeout);
  if (!line || *line != "ready") {
    child_.reset();  // kills and reaps it
    throw std::runtime_error(base_name(program_) + " on " + link_path_ + " did not print \"ready\" within 5 s" +
                             (line ? " (printed \"" + *line + "\")" : " (see its stderr above)"));
  }
}

void SimProcess::kill_hard() {
  if (child_) child_->kill_hard();
  child_.reset();
}

std::optional<int> SimProcess::terminate(std::chrono::milliseconds timeout) {
  if (!child_) return std::nullopt;
  const pid_t pid = child_->pid();
  ::kill(pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    // WNOWAIT: look without reaping, so ChildProcess still owns (and reaps) its pid.
    siginfo_t info{};
    if (waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid) {
      const int status = info.si_code == CLD_EXITED ? info.si_status : 128 + info.si_status;
      child_.reset();
      return status;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return std::nullopt;
}

void SimProcess::restart() {
  kill_hard();
  start();
}

nlohmann::json SimProcess::control(const nlohmann::json& request, std::chrono::milliseconds timeout) const {
  int error = 0;
  const int sock = connect_to(control_path_, error);
  if (sock < 0) {
    throw std::runtime_error("cannot reach the simulator's control socket " + control_path_ + ": " + errno_text(error));
  }
  const std::string line = request.dump() + "\n";
  std::size_t written = 0;
  while (written < line.size()) {
    const ssize_t n = send(sock, line.data() + written, line.size() - written, MSG_NOSIGNAL);
    if (n <= 0) {
      const int send_error = errno;
      close(sock);
      throw std::runtime_error("sending to " + control_path_ + " failed: " + errno_text(send_error));
    }
    written += static_cast<std::size_t>(n);
  }
  std::string reply;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (reply.find('\n') == std::string::npos) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd fd{sock, POLLIN, 0};
    if (left.count() <= 0 || poll(&fd, 1, static_cast<int>(left.count())) <= 0) {
      close(sock);
      throw std::runtime_error("no reply from " + control_path_ + " within " + std::to_string(timeout.count()) +
                               " ms to " + request.dump());
    }
    std::array<char, 4096> chunk{};
    const ssize_t n = recv(sock, chunk.data(), chunk.size(), 0);
    if (n <= 0) {
      close(sock);
      throw std::runtime_error("the simulator closed the control connection before replying to " + request.dump());
    }
    reply.append(chunk.data(), static_cast<std::size_t>(n));
  }
  close(sock);
  nlohmann::json parsed = nlohmann::json::parse(reply.substr(0, reply.find('\n')), nullptr, false);
  if (parsed.is_discarded()) throw std::runtime_error("the simulator's reply is not JSON: " + reply);
  return parsed;
}

int run_to_exit(const std::string& program, const std::vector<std::string>& arguments) {
  std::vector<std::string> args{program};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace robotd::testing
