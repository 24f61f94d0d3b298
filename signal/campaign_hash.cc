#include "signal/campaign_hash.h"

#include <openssl/evp.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <memory>

#include "signal/input_error.h"

namespace beamid::signal {
namespace {

// One SHA-256 computation (OpenSSL's EVP interface, the library's
// recommended one), freed however it ends.
class Sha256 {
 public:
  Sha256() : context_(EVP_MD_CTX_new(), &EVP_MD_CTX_free) {
    if (!context_ || EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) != 1)
      throw std::runtime_error("OpenSSL: cannot start a SHA-256 digest");
  }
  void Update(const void* data, std::size_t size) {
    if (size > 0 && EVP_DigestUpdate(context_.get(), data, size) != 1)
      throw std::runtime_error("OpenSSL: SHA-256 update failed");
  }
  // The length as 8 little-endian bytes, whatever the machine's order.
  void UpdateLength(std::uint64_t length) {
    std::array<unsigned char, 8> bytes{};
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(length >> (8 * i));
    Update(bytes.data(), bytes.size());
  }
  std::string HexDigest() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int size = 0;
    if (EVP_DigestFinal_ex(context_.get(), digest.data(), &size) != 1)
      throw std::runtime_error("OpenSSL: SHA-256 final failed");
    static constexpr char kHex[] = "0123456789abcdef";
    std::string hex;
    for (unsigned int i = 0; i < size; ++i) {
      hex += kHex[digest[i] >> 4];
      hex += kHex[digest[i] & 0xf];
    }
    return hex;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> context_;
};

// Feeds the file's bytes to every digest given, and its length first to
// `framed` when given; checks that it had the length it had when opened.
void HashFile(const std::filesystem::path& file, Sha256* framed, Sha256* own) {
  std::ifstream in(file, std::ios::binary);
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (!in || error)
    throw InputError(file.string(), "", "cannot be read to compute the campaign's content hash",
                     "check that the file exists and can be read");
  if (framed != nullptr) framed->UpdateLength(size);
  std::array<char, 1 << 16> buffer{};
  std::uintmax_t read = 0;
  while (in) {
    in.read(buffer.data(), buffer.size());
    const auto count = static_cast<std::size_t>(in.gcount());
    if (framed != nullptr) framed->Update(buffer.data(), count);
    if (own != nullptr) own->Update(buffer.data(), count);
    read += count;
  }
  if (in.bad() || read != size)
    throw InputError(file.string(), "", "changed or could not be read while its content hash was computed",
                     "let the acquisition finish writing the campaign, then run beamid again");
}

}  // namespace

CampaignHash HashCampaign(const std::filesystem::path& folder, const std::vector<std::string>& step_files) {
  Sha256 campaign;
  const auto hash_named = [&](const std::string& name, Sha256* own) {
    campaign.UpdateLength(name.size());
    campaign.Update(name.data(), name.size());
    HashFile(folder / name, &campaign, own);
  };
  hash_named("campaign.json", nullptr);
  CampaignHash hash;
  for (const auto& file : step_files) {
    Sha256 own;
    hash_named(file, &own);
    hash.step_sha256.push_back(own.HexDigest());
  }
  hash.sha256 = campaign.HexDigest();
  return hash;
}

std::string FileSha256(const std::filesystem::path& file) {
  Sha256 own;
  HashFile(file, nullptr, &own);
  return own.HexDigest();
}

}  // namespace beamid::signal
