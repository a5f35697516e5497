#include "exit_status.hpp"

#include <iostream>

namespace robotctl {
namespace {

std::string where_robotctl_looked(const robotd::ClientOptions& options) {
  std::string text = "DDS domain " + std::to_string(options.domain_id);
  if (!options.cyclonedds_xml.empty()) return text + " (custom Cyclone DDS configuration)";
  text += options.network_interface.empty() ? " (interface chosen by Cyclone DDS"
                                            : " (interface " + options.network_interface;
  if (options.multicast) text += ", multicast";
  if (options.security.enabled()) text += ", DDS Security as " + options.security.identity_certificate;
  return text + ")";
}

}  // namespace

int report_failure(const robotd::Error& error, const robotd::ClientOptions& options) {
  if (error.code == robotd::ErrorCode::kNotAvailable) {
    const std::string trust = options.security.enabled() ? ", and does it trust this identity's CA?" : "?";
    return report_failure("no robotd answers on " + where_robotctl_looked(options) + " — is robotd running" + trust +
                          " (start it with: robotd --config config/robotd.json)");
  }
  return report_failure(error.message);
}

int report_failure(const std::string& message) {
  std::cerr << "robotctl: " << message << std::endl;
  return kExitFailure;
}

int report_usage_error(const std::string& message) {
  std::cerr << "robotctl: " << message << "\nRun with --help for more information." << std::endl;
  return kExitUsage;
}

}  // namespace robotctl
