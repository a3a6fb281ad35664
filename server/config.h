#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace papernet::server {

/// Every setting and limit of `papernet serve`, in one place. Filled from PAPERNET_* environment
/// variables, then command-line flags (flags win).
struct ServerConfig {
  std::string host = "127.0.0.1";
  int port = 8080;  ///< 0 picks a free port (printed on start)
  std::string data_dir = "./var";
  /// "sqlite" (the file papernet.sqlite under data_dir) or a postgres:// URL that several
  /// nodes share (docs/scaling.md).
  std::string store = "sqlite";
  double lease = 30;              ///< seconds a running job's lease lasts without renewal
  int max_attempts = 3;           ///< claims of one job before it fails with interrupted_too_often
  std::size_t workers = 0;        ///< geometry threads; 0 = one per core
  std::size_t http_threads = 16;  ///< threads serving connections (event streams apart)
  /// Live progress streams (GET /v1/jobs/{id}/events) open at once; the next one is answered
  /// 429 too_many_streams. Each holds a thread of its own, beside the http_threads.
  std::size_t max_streams = 500;
  std::size_t queue_length = 64;  ///< queued jobs before POST answers 429
  std::size_t max_body_bytes = std::size_t{64} << 20;
  std::size_t max_faces = 1'000'000;
  double job_time_limit = 120;      ///< seconds, when a job does not ask for one
  double max_job_time_limit = 600;  ///< the most a job may ask for
  double shutdown_grace = 10;       ///< seconds running jobs get to finish on SIGTERM
  double read_timeout = 5;          ///< seconds one read from a client may wait
  double header_timeout = 10;       ///< seconds a client has to send a request's line and headers
  double request_timeout = 120;     ///< seconds a client has to send a whole request (the upload)
  bool reuse_results = true;        ///< answer identical mesh + options from a stored result
  bool access_log = true;
  std::string web_root;  ///< directory of the web demo served at / ("" = none)
  /// Origins whose pages may call the API from a browser (CORS), e.g. https://shop.example;
  /// "*" = any (only without API keys).
  std::vector<std::string> cors_origins;
  /// File of API keys (server/api_keys.h); "" = none: the API is open to whoever reaches it.
  std::string api_keys;
  double retention = 7 * 86400;  ///< seconds a finished job and its files are kept (0 = forever)
  /// Bytes of uploads and results the store keeps at most (0 = no bound): past it, finished jobs
  /// expire early, those that finished first first.
  std::uint64_t max_store_bytes = std::uint64_t{20} << 30;
  /// Hosts a job's callback_url may name (server/webhooks.h); empty = any public host.
  std::vector<std::string> webhook_hosts;
  std::string webhook_secret;       ///< signs callbacks; "" = callback_url refused
  double webhook_timeout = 5;       ///< seconds to connect, send and receive, per attempt
  double webhook_retry_for = 3600;  ///< seconds after a callback's first attempt to keep trying
};

class ConfigError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Reads the environment through `getenv` (injectable for tests) and then the flags
/// (argv[0] is the command name). Returns nullopt when --help was asked for.
/// \throw ConfigError naming the bad flag or variable.
std::optional<ServerConfig> parse_serve_config(
    int argc, char** argv,
    const std::function<const char*(const char*)>& getenv = [](const char* n) {
      return std::getenv(n);
    });

/// The --help text: every flag with its variable and default.
std::string serve_usage();

}  // namespace papernet::server
