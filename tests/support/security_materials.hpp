// What scripts/make-dds-security makes (a CA, and per participant an identity and its signed
// permissions), in a fresh temporary directory removed with this object. Each instance is its
// own CA: two of them are two deployments that do not trust each other.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "robotd/dds_security.hpp"

namespace robotd::testing {

class SecurityMaterials {
 public:
  /// Runs the script for the participants robotd, operator and viewer (their roles' names);
  /// throws when it fails.
  SecurityMaterials();
  SecurityMaterials(const SecurityMaterials&) = delete;
  SecurityMaterials& operator=(const SecurityMaterials&) = delete;
  ~SecurityMaterials();

  /// The files of participant `name`.
  DdsSecurityFiles files(const std::string& name) const;
  /// The same files as robotd's config object "dds.security".
  nlohmann::json config(const std::string& name) const;
  /// How long the script took, in seconds.
  double seconds_to_make() const { return seconds_to_make_; }

 private:
  std::string directory_;
  double seconds_to_make_ = 0;
};

}  // namespace robotd::testing
