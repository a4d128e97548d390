#pragma once
/// @file Self-signed certificates made at test time (OpenSSL), for HTTPS tests on loopback.

#include <filesystem>
#include <string>

#include "fake_llm_server.hpp"

namespace lang2manip::test {

/// Writes `name`.crt and `name`.key (EC P-256, valid from an hour ago for a day) into
/// `directory`; `subjectAltNames` as in OpenSSL config, e.g. "IP:127.0.0.1,DNS:localhost".
FakeTlsFiles writeSelfSignedCertificate(const std::filesystem::path& directory,
                                        const std::string& name,
                                        const std::string& subjectAltNames);

}  // namespace lang2manip::test
