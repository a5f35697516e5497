// A DDS participant on a domain created with robotd's settings. Several participants in one
// process may share a domain (tests run a client and a daemon side by side); the domain is
// created on first use and deleted with its last participant.
#pragma once

#include <string>
#include <string_view>

#include <dds/dds.h>

#include "robotd/result.hpp"
#include "wire/dds_settings.hpp"

namespace robotd::wire {

class Participant {
 public:
  static Result<Participant> create(const DdsSettings& settings);

  Participant(Participant&& other) noexcept;
  Participant& operator=(Participant&& other) noexcept;
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;
  ~Participant();

  dds_entity_t handle() const { return handle_; }
  int domain_id() const { return domain_id_; }

 private:
  Participant(dds_entity_t handle, int domain_id) : handle_(handle), domain_id_(domain_id) {}
  void reset();

  dds_entity_t handle_ = 0;
  int domain_id_ = 0;
};

/// "failed to X: <Cyclone's reason>" for a negative Cyclone return code.
std::string dds_error(const char* what, dds_return_t code);

/// The Error for a negative Cyclone return code from creating an entity for `topic`:
/// kNotPermitted when DDS Security's access control refused it, kTransport otherwise.
Error dds_failure(const char* what, std::string_view topic, dds_return_t code);

}  // namespace robotd::wire
