// DDS Security's six files, checked before Cyclone DDS sees them: its own errors name no
// file. to_cyclone_xml() (wire/dds_settings.hpp) turns them into the domain's <Security>.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "robotd/dds_security.hpp"

namespace robotd::wire {

/// A field of DdsSecurityFiles: its name (robotd's config key under "dds.security", and
/// ROBOTD_DDS_SECURITY_<NAME> in the environment) and what its file must be.
struct SecurityFileField {
  std::string_view name;
  std::string DdsSecurityFiles::*path;
  std::string_view expected;  // for messages: "the identity CA's certificate (PEM)"
  std::string_view marker;    // text every such file contains
};
extern const std::array<SecurityFileField, 6> kSecurityFileFields;

struct SecurityFileProblem {
  std::string_view field;  // a SecurityFileField name
  std::string message;     // what is wrong, and what was expected
};

/// Every field that is unset, names a file that cannot be read, or a file that is not what the
/// field expects. Empty when the files are fit to try.
std::vector<SecurityFileProblem> find_security_file_problems(const DdsSecurityFiles& files);

/// "identity_ca: ...; private_key: ..." — the problems in one line.
std::string describe(const std::vector<SecurityFileProblem>& problems);

}  // namespace robotd::wire
