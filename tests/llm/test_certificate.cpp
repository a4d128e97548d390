#include "test_certificate.hpp"

#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <functional>
#include <memory>
#include <stdexcept>

namespace lang2manip::test {

namespace {

template <typename T, void (*Free)(T*)>
struct OpenSslDeleter {
  void operator()(T* pointer) const { Free(pointer); }
};
using KeyPointer = std::unique_ptr<EVP_PKEY, OpenSslDeleter<EVP_PKEY, EVP_PKEY_free>>;
using CertificatePointer = std::unique_ptr<X509, OpenSslDeleter<X509, X509_free>>;
using ExtensionPointer =
    std::unique_ptr<X509_EXTENSION, OpenSslDeleter<X509_EXTENSION, X509_EXTENSION_free>>;

void require(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(std::string("test certificate: ") + what + " failed");
}

void writePem(const std::filesystem::path& path, const std::function<int(BIO*)>& write) {
  BIO* bio = BIO_new_file(path.c_str(), "w");
  require(bio != nullptr, "opening the PEM file");
  const int written = write(bio);
  BIO_free(bio);
  require(written == 1, "writing the PEM file");
}

}  // namespace

FakeTlsFiles writeSelfSignedCertificate(const std::filesystem::path& directory,
                                        const std::string& name,
                                        const std::string& subjectAltNames) {
  KeyPointer key(EVP_PKEY_Q_keygen(nullptr, nullptr, "EC", "P-256"));
  require(key != nullptr, "key generation");
  CertificatePointer certificate(X509_new());
  require(X509_set_version(certificate.get(), 2) == 1, "version");
  ASN1_INTEGER_set(X509_get_serialNumber(certificate.get()), 1);
  X509_gmtime_adj(X509_getm_notBefore(certificate.get()), -3600);
  X509_gmtime_adj(X509_getm_notAfter(certificate.get()), 24 * 3600);
  require(X509_set_pubkey(certificate.get(), key.get()) == 1, "public key");
  X509_NAME* subject = X509_get_subject_name(certificate.get());
  const std::string commonName = "lang2manip test " + name;
  X509_NAME_add_entry_by_txt(subject, "CN", MBSTRING_ASC,
                             reinterpret_cast<const unsigned char*>(commonName.c_str()), -1, -1, 0);
  require(X509_set_issuer_name(certificate.get(), subject) == 1, "issuer");
  X509V3_CTX context;
  X509V3_set_ctx(&context, certificate.get(), certificate.get(), nullptr, nullptr, 0);
  ExtensionPointer alternativeNames(
      X509V3_EXT_conf_nid(nullptr, &context, NID_subject_alt_name, subjectAltNames.c_str()));
  require(alternativeNames != nullptr, "subjectAltName");
  require(X509_add_ext(certificate.get(), alternativeNames.get(), -1) == 1, "adding subjectAltName");
  require(X509_sign(certificate.get(), key.get(), EVP_sha256()) > 0, "signing");

  FakeTlsFiles files{(directory / (name + ".crt")).string(), (directory / (name + ".key")).string()};
  writePem(files.certificateFile,
           [&](BIO* bio) { return PEM_write_bio_X509(bio, certificate.get()); });
  writePem(files.privateKeyFile, [&](BIO* bio) {
    return PEM_write_bio_PrivateKey(bio, key.get(), nullptr, nullptr, 0, nullptr, nullptr);
  });
  return files;
}

}  // namespace lang2manip::test
