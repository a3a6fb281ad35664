#pragma once

#include <chrono>
#include <cstddef>
#include <ctime>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace papernet::server {

/// One key of the key file: the tenant it speaks for and that tenant's settings.
struct ApiKey {
  std::string tenant;
  std::string name;  ///< a label for logs (name=...), "" = none
  double rate = 0;   ///< requests per second the key may make (rate=...), 0 = no limit
  double share = 1;  ///< fraction of the queue the tenant's queued jobs may fill (share=...)
};

/// The key file is unreadable or has a bad line; the message names the file and the line.
class ApiKeyFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The lowercase hex SHA-256 of `bytes` (OpenSSL's libcrypto).
std::string sha256_hex(const std::string& bytes);
/// The SHA-256 of `parts`, each preceded by its length: different lists, different digests.
std::string sha256_hex_of_parts(const std::vector<std::string_view>& parts);

/// Keys by the hex SHA-256 of the secret. The file has one key a line,
/// `TENANT SHA256HEX [name=value ...]` (names: name, rate, share); `#` starts a comment.
/// \throw ApiKeyFileError
std::map<std::string, ApiKey> parse_api_keys(const std::string& text, const std::string& path);

/// The keys of `--api-keys FILE`, read again on reload() (SIGHUP) and when the file's
/// modification time or size changes (looked at no more than once a second). A file that
/// turns bad keeps the keys read last; the error goes to the log. Thread-safe.
class ApiKeyRing {
 public:
  using Logger = std::function<void(const std::string&)>;
  /// Reads `path`. \throw ApiKeyFileError
  ApiKeyRing(std::string path, Logger log);

  /// The key whose SHA-256 is that of `secret`, if any.
  std::optional<ApiKey> find(const std::string& secret);
  /// Reads the file again; false (and the old keys kept) when it is bad.
  bool reload();
  std::size_t size();

 private:
  void reload_if_changed();
  std::string path_;
  Logger log_;
  std::mutex mutex_;
  std::shared_ptr<const std::map<std::string, ApiKey>> keys_;
  std::timespec mtime_{};
  long long size_ = -1;
  std::time_t checked_ = 0;
};

/// Requests a second per key (ApiKey::rate): each key a bucket of max(1, rate) requests, refilled
/// at `rate` a second. Thread-safe.
class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  /// 0 when a request by `key` (at `now`) may go, and it is counted; else the whole seconds to wait
  /// for the next one. A rate of 0 or less: no limit.
  int take(const std::string& key, double rate, Clock::time_point now = Clock::now());

 private:
  struct Bucket {
    double tokens;
    Clock::time_point at;
  };
  std::mutex mutex_;
  std::map<std::string, Bucket> buckets_;
};

}  // namespace papernet::server
