#include "server/api_keys.h"

#include <openssl/evp.h>
#include <sys/stat.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/ascii.h"

namespace papernet::server {
namespace {

bool is_hex64(const std::string& s) {
  if (s.size() != 64) return false;
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

double number(const std::string& where, const std::string& name, const std::string& v, double max) {
  double out = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
  if (v.empty() || ec != std::errc() || end != v.data() + v.size() || !std::isfinite(out) ||
      out < 0 || out > max)
    throw ApiKeyFileError(where + ": " + name + "='" + v + "' is not a number between 0 and " +
                          std::to_string(max));
  return out;
}

}  // namespace

std::string sha256_hex(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256 failed (OpenSSL)");
  static const char* hex = "0123456789abcdef";
  std::string out;
  out.reserve(2 * length);
  for (unsigned int i = 0; i < length; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 15];
  }
  return out;
}

std::string sha256_hex_of_parts(const std::vector<std::string_view>& parts) {
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  bool ok = ctx && EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) == 1;
  for (std::string_view part : parts) {
    const std::string length = std::to_string(part.size()) + ":";
    ok = ok && EVP_DigestUpdate(ctx.get(), length.data(), length.size()) == 1 &&
         EVP_DigestUpdate(ctx.get(), part.data(), part.size()) == 1;
  }
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (!ok || EVP_DigestFinal_ex(ctx.get(), digest, &size) != 1)
    throw std::runtime_error("SHA-256 failed (OpenSSL)");
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < size; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 15];
  }
  return out;
}

std::map<std::string, ApiKey> parse_api_keys(const std::string& text, const std::string& path) {
  std::map<std::string, ApiKey> keys;
  std::istringstream in(text);
  std::string line;
  int number_of_line = 0;
  while (std::getline(in, line)) {
    ++number_of_line;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string tenant, digest, word;
    if (!(words >> tenant)) continue;
    const std::string where = path + ":" + std::to_string(number_of_line);
    if (!(words >> digest))
      throw ApiKeyFileError(where + ": expected TENANT SHA256HEX [name=value ...]");
    if (tenant.size() > 64)
      throw ApiKeyFileError(where + ": a tenant name is at most 64 characters");
    digest = ascii_lower(digest);
    if (!is_hex64(digest))
      throw ApiKeyFileError(where + ": '" + digest.substr(0, 80) +
                            "' is not a SHA-256 in hex (64 hex digits; sha256sum prints it)");
    ApiKey key;
    key.tenant = tenant;
    while (words >> word) {
      const auto eq = word.find('=');
      if (eq == std::string::npos)
        throw ApiKeyFileError(where + ": '" + word + "' is not name=value");
      const std::string name = word.substr(0, eq), value = word.substr(eq + 1);
      if (name == "name")
        key.name = value;
      else if (name == "rate")
        key.rate = number(where, name, value, 1e6);
      else if (name == "share")
        key.share = number(where, name, value, 1);
      else
        throw ApiKeyFileError(where + ": unknown setting '" + name + "' (name, rate, share)");
    }
    if (!keys.emplace(digest, key).second)
      throw ApiKeyFileError(where + ": the same key is listed twice");
  }
  if (keys.empty())
    throw ApiKeyFileError(path + ": no keys (an empty file would lock every caller out)");
  return keys;
}

ApiKeyRing::ApiKeyRing(std::string path, Logger log)
    : path_(std::move(path)), log_(std::move(log)) {
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw ApiKeyFileError(path_ + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0) {
    mtime_ = st.st_mtim;
    size_ = st.st_size;
  }
  keys_ = std::make_shared<const std::map<std::string, ApiKey>>(parse_api_keys(text.str(), path_));
  checked_ = std::time(nullptr);
}

bool ApiKeyRing::reload() {
  struct stat st {};
  const bool stated = ::stat(path_.c_str(), &st) == 0;
  std::ifstream in(path_, std::ios::binary);
  std::stringstream text;
  if (in) text << in.rdbuf();
  std::lock_guard lock(mutex_);
  if (stated) {
    mtime_ = st.st_mtim;
    size_ = st.st_size;
  }
  try {
    if (!in) throw ApiKeyFileError(path_ + ": cannot be read");
    keys_ =
        std::make_shared<const std::map<std::string, ApiKey>>(parse_api_keys(text.str(), path_));
  } catch (const ApiKeyFileError& e) {
    log_(std::string("api keys: not reloaded, keeping the ") + std::to_string(keys_->size()) +
         " keys read before: " + e.what());
    return false;
  }
  log_("api keys: " + std::to_string(keys_->size()) + " keys read from " + path_);
  return true;
}

void ApiKeyRing::reload_if_changed() {
  {
    std::lock_guard lock(mutex_);
    const std::time_t now = std::time(nullptr);
    if (now == checked_) return;
    checked_ = now;
    struct stat st {};
    if (::stat(path_.c_str(), &st) != 0) return;  // gone for a moment (an editor's rename)
    if (st.st_mtim.tv_sec == mtime_.tv_sec && st.st_mtim.tv_nsec == mtime_.tv_nsec &&
        st.st_size == size_)
      return;
  }
  reload();
}

std::optional<ApiKey> ApiKeyRing::find(const std::string& secret) {
  reload_if_changed();
  const std::string digest = sha256_hex(secret);
  std::shared_ptr<const std::map<std::string, ApiKey>> keys;
  {
    std::lock_guard lock(mutex_);
    keys = keys_;
  }
  const auto it = keys->find(digest);
  if (it == keys->end()) return std::nullopt;
  return it->second;
}

std::size_t ApiKeyRing::size() {
  std::lock_guard lock(mutex_);
  return keys_->size();
}

int RateLimiter::take(const std::string& key, double rate, Clock::time_point now) {
  if (rate <= 0) return 0;
  std::lock_guard lock(mutex_);
  auto [it, fresh] = buckets_.try_emplace(key, Bucket{std::max(1.0, rate), now});
  Bucket& b = it->second;
  if (!fresh && now > b.at) {
    const double seconds = std::chrono::duration<double>(now - b.at).count();
    b.tokens = std::min(std::max(1.0, rate), b.tokens + seconds * rate);
    b.at = now;
  }
  if (b.tokens >= 1) {
    b.tokens -= 1;
    return 0;
  }
  return static_cast<int>(std::ceil((1 - b.tokens) / rate));
}

}  // namespace papernet::server
