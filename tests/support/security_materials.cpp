#include "security_materials.hpp"

#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#ifndef ROBOTD_MAKE_DDS_SECURITY
#error "ROBOTD_MAKE_DDS_SECURITY must point at scripts/make-dds-security"
#endif

namespace robotd::testing {
namespace {

// Runs `program directory` with its output discarded; its exit status.
int run_script(const std::string& program, const std::string& directory) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    dup2(null, STDOUT_FILENO);
    execl(program.c_str(), program.c_str(), directory.c_str(), nullptr);  // NOLINT(cppcoreguidelines-pro-type-vararg)
    _exit(127);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

SecurityMaterials::SecurityMaterials() {
  std::string pattern = "/tmp/robotd-test-security-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  directory_ = pattern;
  const auto start = std::chrono::steady_clock::now();
  const int status = run_script(ROBOTD_MAKE_DDS_SECURITY, directory_);
  seconds_to_make_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (status != 0) {
    std::filesystem::remove_all(directory_);
    throw std::runtime_error(std::string(ROBOTD_MAKE_DDS_SECURITY) + " failed with status " + std::to_string(status));
  }
}

SecurityMaterials::~SecurityMaterials() {
  std::error_code ignored;
  std::filesystem::remove_all(directory_, ignored);
}

DdsSecurityFiles SecurityMaterials::files(const std::string& name) const {
  const std::string dir = directory_ + "/" + name + "/";
  return DdsSecurityFiles{.identity_ca = dir + "identity_ca.pem",
                          .identity_certificate = dir + "identity_certificate.pem",
                          .private_key = dir + "private_key.pem",
                          .permissions_ca = dir + "permissions_ca.pem",
                          .governance = dir + "governance.p7s",
                          .permissions = dir + "permissions.p7s"};
}

nlohmann::json SecurityMaterials::config(const std::string& name) const {
  const DdsSecurityFiles f = files(name);
  return {{"identity_ca", f.identity_ca}, {"identity_certificate", f.identity_certificate},
          {"private_key", f.private_key}, {"permissions_ca", f.permissions_ca},
          {"governance", f.governance},   {"permissions", f.permissions}};
}

}  // namespace robotd::testing
