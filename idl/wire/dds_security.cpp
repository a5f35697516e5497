#include "wire/dds_security.hpp"

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <system_error>

namespace robotd::wire {
namespace {

constexpr std::string_view kCertificate = "-----BEGIN CERTIFICATE-----";
constexpr std::string_view kSignedDocument = "pkcs7-signature";  // openssl smime -sign's multipart/signed
// Certificates and signed documents are a few kB; anything far larger is not one of them.
constexpr std::size_t kLargestFile = 1U << 20U;

std::optional<std::string> problem_with(const std::string& path, const SecurityFileField& field) {
  const std::string expected = "expected " + std::string(field.expected);
  if (path.empty()) return "not set; " + expected;
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) return "no such file '" + path + "'; " + expected;
  if (!std::filesystem::is_regular_file(status)) return "'" + path + "' is not a file; " + expected;
  errno = 0;
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    return "cannot read '" + path + "' (" + std::generic_category().message(errno) + "); " + expected;
  }
  std::string text;
  text.resize(kLargestFile);
  file.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(file.gcount()));
  if (text.find(field.marker) == std::string::npos) {
    return "'" + path + "' is not " + std::string(field.expected) + " (it has no \"" + std::string(field.marker) +
           "\")";
  }
  return std::nullopt;
}

}  // namespace

const std::array<SecurityFileField, 6> kSecurityFileFields{{
    {"identity_ca", &DdsSecurityFiles::identity_ca, "the identity CA's certificate (PEM)", kCertificate},
    {"identity_certificate", &DdsSecurityFiles::identity_certificate,
     "this participant's identity certificate (PEM), signed by the identity CA", kCertificate},
    {"private_key", &DdsSecurityFiles::private_key, "the identity certificate's private key (PEM)", "PRIVATE KEY-----"},
    {"permissions_ca", &DdsSecurityFiles::permissions_ca, "the permissions CA's certificate (PEM)", kCertificate},
    {"governance", &DdsSecurityFiles::governance,
     "the governance document signed by the permissions CA (S/MIME, governance.p7s)", kSignedDocument},
    {"permissions", &DdsSecurityFiles::permissions,
     "this participant's permissions document signed by the permissions CA (S/MIME, permissions.p7s)", kSignedDocument},
}};

std::vector<SecurityFileProblem> find_security_file_problems(const DdsSecurityFiles& files) {
  std::vector<SecurityFileProblem> problems;
  for (const auto& field : kSecurityFileFields) {
    if (auto problem = problem_with(files.*field.path, field)) problems.push_back({field.name, std::move(*problem)});
  }
  return problems;
}

std::string describe(const std::vector<SecurityFileProblem>& problems) {
  std::string text;
  for (const auto& problem : problems) {
    text += (text.empty() ? "" : "; ") + std::string(problem.field) + ": " + problem.message;
  }
  return text;
}

}  // namespace robotd::wire
