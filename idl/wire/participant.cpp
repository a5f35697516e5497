#include "wire/participant.hpp"

#include <map>
#include <mutex>
#include <utility>

#include "wire/dds_security.hpp"

namespace robotd::wire {
namespace {

struct DomainUse {
  dds_entity_t domain = 0;
  int participants = 0;
  DdsSecurityFiles security;  // the identity the domain was created with, shared by all its participants
};

std::string identity_of(const DdsSecurityFiles& security) {
  return security.enabled() ? "DDS Security as '" + security.identity_certificate + "'" : "no DDS Security";
}

std::mutex& domains_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<int, DomainUse>& domains() {
  static std::map<int, DomainUse> uses;
  return uses;
}

void release_domain(int domain_id) {
  const std::lock_guard lock(domains_mutex());
  auto it = domains().find(domain_id);
  if (it == domains().end()) return;
  if (--it->second.participants == 0) {
    dds_delete(it->second.domain);
    domains().erase(it);
  }
}

}  // namespace

std::string dds_error(const char* what, dds_return_t code) {
  return std::string("failed to ") + what + ": " + dds_strretcode(code);
}

Error dds_failure(const char* what, std::string_view topic, dds_return_t code) {
  const std::string action = std::string(what) + " for " + std::string(topic);
  if (code == DDS_RETCODE_NOT_ALLOWED_BY_SECURITY) {
    return make_error(ErrorCode::kNotPermitted, "failed to " + action +
                                                    ": not allowed by DDS Security (this participant's permissions "
                                                    "document does not grant it)");
  }
  return make_error(ErrorCode::kTransport, dds_error(action.c_str(), code));
}

Result<Participant> Participant::create(const DdsSettings& settings) {
  if (settings.domain_id < 0 || settings.domain_id > 230) {
    return make_error(ErrorCode::kInvalidArgument,
                      "DDS domain id " + std::to_string(settings.domain_id) + " is out of range (expected 0..230)");
  }
  const bool secure = settings.security.enabled();
  if (secure) {
    if (!settings.cyclonedds_xml.empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        "DDS Security files and a verbatim Cyclone DDS XML cannot be combined: put a <Security> "
                        "section into the XML, or drop the XML");
    }
    if (const auto problems = find_security_file_problems(settings.security); !problems.empty()) {
      return make_error(ErrorCode::kInvalidArgument,
                        "DDS Security is misconfigured (it needs all six files): " + describe(problems));
    }
  }
  const auto domain_id = static_cast<dds_domainid_t>(settings.domain_id);
  {
    const std::lock_guard lock(domains_mutex());
    auto& use = domains()[settings.domain_id];
    if (use.participants == 0) {
      const std::string xml = to_cyclone_xml(settings);
      const dds_entity_t domain = dds_create_domain(domain_id, xml.c_str());
      if (domain < 0) {
        domains().erase(settings.domain_id);
        return make_error(ErrorCode::kTransport, dds_error("create the DDS domain", domain) +
                                                     " (check the dds settings: interface '" +
                                                     settings.network_interface + "')");
      }
      use.domain = domain;
      use.security = settings.security;
    } else if (use.security != settings.security) {
      return make_error(ErrorCode::kInvalidArgument,
                        "this process is on DDS domain " + std::to_string(settings.domain_id) + " with " +
                            identity_of(use.security) +
                            ", and Cyclone DDS applies DDS Security to the whole "
                            "domain: a participant with " +
                            identity_of(settings.security) + " needs a process of its own");
    }
    ++use.participants;
  }
  const dds_entity_t participant = dds_create_participant(domain_id, nullptr, nullptr);
  if (participant < 0) {
    release_domain(settings.domain_id);
    if (secure) {
      return make_error(ErrorCode::kNotPermitted,
                        dds_error("create a DDS participant with DDS Security", participant) +
                            " (Cyclone DDS logged why. Usual causes: the identity certificate is not signed by "
                            "identity_ca or has expired; the permissions do not name its subject or this domain; "
                            "governance or permissions are not signed by permissions_ca)");
    }
    return make_error(ErrorCode::kTransport, dds_error("create a DDS participant", participant));
  }
  return Participant(participant, settings.domain_id);
}

Participant::Participant(Participant&& other) noexcept
    : handle_(std::exchange(other.handle_, 0)), domain_id_(other.domain_id_) {}

Participant& Participant::operator=(Participant&& other) noexcept {
  if (this != &other) {
    reset();
    handle_ = std::exchange(other.handle_, 0);
    domain_id_ = other.domain_id_;
  }
  return *this;
}

Participant::~Participant() { reset(); }

void Participant::reset() {
  if (handle_ > 0) {
    dds_delete(handle_);
    release_domain(domain_id_);
    handle_ = 0;
  }
}

}  // namespace robotd::wire
