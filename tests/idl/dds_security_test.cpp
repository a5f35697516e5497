// DDS Security files are checked before Cyclone DDS sees them: each problem names the field,
// the file and what the field expects, and a participant is not created with any of them, nor
// beside a participant of the same process and domain with another identity.
#include "wire/dds_security.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "wire/participant.hpp"
#include "wire_test_support.hpp"

namespace robotd::wire {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::SizeIs;

// Six files that look like what each field expects (the check reads markers, not cryptography).
class SecurityFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = "/tmp/robotd-test-security-files-XXXXXX";
    directory_ = mkdtemp(pattern.data());
    files_.identity_ca = write("identity_ca.pem", "-----BEGIN CERTIFICATE-----\n");
    files_.identity_certificate = write("identity_certificate.pem", "-----BEGIN CERTIFICATE-----\n");
    files_.private_key = write("private_key.pem", "-----BEGIN PRIVATE KEY-----\n");
    files_.permissions_ca = write("permissions_ca.pem", "-----BEGIN CERTIFICATE-----\n");
    files_.governance = write("governance.p7s", "Content-Type: application/x-pkcs7-signature\n");
    files_.permissions = write("permissions.p7s", "Content-Type: application/x-pkcs7-signature\n");
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  std::string write(const std::string& name, const std::string& text) {
    std::string path = directory_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }

  std::string directory_;
  DdsSecurityFiles files_;
};

TEST_F(SecurityFilesTest, FilesOfTheRightKindPass) { EXPECT_THAT(find_security_file_problems(files_), IsEmpty()); }

TEST_F(SecurityFilesTest, EveryUnsetFieldIsNamed) {
  DdsSecurityFiles only_one;
  only_one.identity_ca = files_.identity_ca;
  const auto problems = find_security_file_problems(only_one);
  ASSERT_THAT(problems, SizeIs(5));
  EXPECT_EQ(problems[0].field, "identity_certificate");
  EXPECT_THAT(problems[0].message, HasSubstr("not set; expected this participant's identity certificate (PEM)"));
  EXPECT_EQ(problems[4].field, "permissions");
}

TEST_F(SecurityFilesTest, MissingFileIsNamedWithWhatWasExpected) {
  files_.private_key = directory_ + "/nowhere.pem";
  const auto problems = find_security_file_problems(files_);
  ASSERT_THAT(problems, SizeIs(1));
  EXPECT_EQ(problems[0].field, "private_key");
  EXPECT_EQ(problems[0].message,
            "no such file '" + files_.private_key + "'; expected the identity certificate's private key (PEM)");
}

TEST_F(SecurityFilesTest, DirectoryIsNotAFile) {
  files_.governance = directory_;
  const auto problems = find_security_file_problems(files_);
  ASSERT_THAT(problems, SizeIs(1));
  EXPECT_THAT(problems[0].message, HasSubstr("'" + directory_ + "' is not a file"));
}

TEST_F(SecurityFilesTest, FileOfTheWrongKindIsNamed) {
  files_.identity_certificate = files_.private_key;  // an easy slip: the key where the certificate goes
  files_.permissions = write("permissions.xml", "<dds><permissions/></dds>\n");  // not signed
  const auto problems = find_security_file_problems(files_);
  ASSERT_THAT(problems, SizeIs(2));
  EXPECT_EQ(problems[0].field, "identity_certificate");
  EXPECT_THAT(problems[0].message, HasSubstr("is not this participant's identity certificate (PEM)"));
  EXPECT_EQ(problems[1].field, "permissions");
  EXPECT_THAT(problems[1].message, HasSubstr("is not this participant's permissions document signed by the "
                                             "permissions CA"));
  EXPECT_THAT(describe(problems), HasSubstr("identity_certificate: '" + files_.private_key + "' is not"));
}

TEST_F(SecurityFilesTest, ParticipantIsNotCreatedWithMisconfiguredSecurity) {
  const testing::PrivateDomain domain;
  DdsSettings settings = domain.settings();
  settings.security = files_;
  settings.security.governance.clear();
  const auto participant = Participant::create(settings);
  ASSERT_FALSE(participant);
  EXPECT_EQ(participant.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(participant.error().message,
              HasSubstr("DDS Security is misconfigured (it needs all six files): governance: not set"));
}

TEST_F(SecurityFilesTest, ParticipantsOfOneProcessAndDomainShareOneIdentity) {
  const testing::PrivateDomain domain;
  const auto unsecured = Participant::create(domain.settings());
  ASSERT_TRUE(unsecured) << unsecured.error().message;
  DdsSettings settings = domain.settings();
  settings.security = files_;
  const auto secured = Participant::create(settings);
  ASSERT_FALSE(secured);
  EXPECT_EQ(secured.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(secured.error().message, HasSubstr("with no DDS Security, and Cyclone DDS applies DDS Security to the "
                                                 "whole domain"));
  EXPECT_THAT(secured.error().message, HasSubstr("needs a process of its own"));
}

TEST_F(SecurityFilesTest, SecurityAndAVerbatimCycloneXmlDoNotMix) {
  const testing::PrivateDomain domain;
  DdsSettings settings = domain.settings();
  settings.security = files_;
  settings.cyclonedds_xml = "<CycloneDDS/>";
  const auto participant = Participant::create(settings);
  ASSERT_FALSE(participant);
  EXPECT_THAT(participant.error().message, HasSubstr("cannot be combined"));
}

}  // namespace
}  // namespace robotd::wire
