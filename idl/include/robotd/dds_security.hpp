// The files of one DDS Security identity, for Cyclone DDS's built-in authentication, access
// control and cryptography plugins. scripts/make-dds-security writes one directory of them per
// participant, each file named after its field (identity_ca.pem, ..., permissions.p7s).
#pragma once

#include <string>

namespace robotd {

struct DdsSecurityFiles {
  std::string identity_ca;           // PEM certificate of the CA that signs every participant's identity
  std::string identity_certificate;  // PEM certificate of this participant, signed by identity_ca
  std::string private_key;           // PEM private key of identity_certificate (unencrypted)
  std::string permissions_ca;        // PEM certificate of the CA that signs governance and permissions
  std::string governance;            // the domain's rules: an S/MIME document signed by permissions_ca
  std::string permissions;           // what this identity may publish and subscribe: S/MIME, signed likewise

  /// DDS Security is on as soon as one file is named; then all six are needed.
  bool enabled() const {
    return !identity_ca.empty() || !identity_certificate.empty() || !private_key.empty() || !permissions_ca.empty() ||
           !governance.empty() || !permissions.empty();
  }
  bool operator==(const DdsSecurityFiles&) const = default;
};

}  // namespace robotd
