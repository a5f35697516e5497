#include "wire/participant.hpp"

#include <map>
#include <mutex>
#include <utility>

namespace robotd::wire {
namespace {

struct DomainUse {
  dds_entity_t domain = 0;
  int participants = 0;
};

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

Result<Participant> Participant::create(const DdsSettings& settings) {
  if (settings.domain_id < 0 || settings.domain_id > 230) {
    return make_error(ErrorCode::kInvalidArgument,
                      "DDS domain id " + std::to_string(settings.domain_id) + " is out of range (expected 0..230)");
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
    }
    ++use.participants;
  }
  const dds_entity_t participant = dds_create_participant(domain_id, nullptr, nullptr);
  if (participant < 0) {
    release_domain(settings.domain_id);
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
