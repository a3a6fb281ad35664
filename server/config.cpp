#include "server/config.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <thread>
#include <vector>

#include "server/job_store.h"

namespace papernet::server {
namespace {

struct Setting {
  const char* flag;  // without the leading "--"
  const char* env;
  const char* help;
  std::function<void(ServerConfig&, const std::string&, const std::string&)> set;
};

std::size_t count(const std::string& where, const std::string& v, std::size_t min,
                  std::size_t max) {
  std::size_t out = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
  if (v.empty() || ec != std::errc() || end != v.data() + v.size() || out < min || out > max)
    throw ConfigError(where + ": '" + v + "' is not a whole number between " + std::to_string(min) +
                      " and " + std::to_string(max));
  return out;
}

double seconds(const std::string& where, const std::string& v) {
  double out = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
  if (v.empty() || ec != std::errc() || end != v.data() + v.size() || !std::isfinite(out) ||
      out < 0 || out > 86400)
    throw ConfigError(where + ": '" + v + "' is not a number of seconds between 0 and 86400");
  return out;
}

// "3600", "90m", "12h", "7d" -> seconds (at most ten years).
double duration(const std::string& where, const std::string& v) {
  double unit = 1;
  std::string digits = v;
  if (!v.empty() && std::string("smhd").find(v.back()) != std::string::npos) {
    unit = v.back() == 's' ? 1 : v.back() == 'm' ? 60 : v.back() == 'h' ? 3600 : 86400;
    digits.pop_back();
  }
  double out = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), out);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() ||
      !std::isfinite(out) || out < 0 || out * unit > 3650 * 86400.0)
    throw ConfigError(where + ": '" + v +
                      "' is not a duration (seconds, or a number with s, m, h or d; e.g. 7d)");
  return out * unit;
}

// "500M" -> bytes: a whole number, optionally with K, M, G or T (powers of 1024).
std::uint64_t byte_size(const std::string& where, const std::string& v) {
  std::uint64_t unit = 1;
  std::string digits = v;
  const std::string units = "KMGT";
  if (!v.empty() && units.find(v.back()) != std::string::npos) {
    unit = std::uint64_t{1} << (10 * (units.find(v.back()) + 1));
    digits.pop_back();
  }
  std::uint64_t out = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), out);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() ||
      out > (std::uint64_t{1} << 60) / unit)
    throw ConfigError(where + ": '" + v +
                      "' is not a size (bytes, or a number with K, M, G or T; e.g. 20G)");
  return out * unit;
}

bool yes_no(const std::string& where, const std::string& v) {
  if (v == "1" || v == "true" || v == "yes") return true;
  if (v == "0" || v == "false" || v == "no") return false;
  throw ConfigError(where + ": '" + v + "' is not true or false");
}

// "https://shop.example, http://localhost:5173" -> its origins, each scheme://host[:port].
std::vector<std::string> origins(const std::string& where, const std::string& v) {
  std::vector<std::string> out;
  std::size_t from = 0;
  while (from <= v.size()) {
    std::size_t to = v.find(',', from);
    if (to == std::string::npos) to = v.size();
    std::string o = v.substr(from, to - from);
    o.erase(0, o.find_first_not_of(" \t"));
    o.erase(o.find_last_not_of(" \t") + 1);
    from = to + 1;
    if (o.empty()) continue;
    if (o.back() == '/') o.pop_back();
    const auto scheme = o.find("://");
    const bool web = o.rfind("http://", 0) == 0 || o.rfind("https://", 0) == 0;
    if (o != "*" && (!web || o.size() == scheme + 3 ||
                     o.find_first_of("/?#* ", scheme + 3) != std::string::npos))
      throw ConfigError(where + ": '" + o +
                        "' is not an origin (scheme://host[:port], e.g. https://shop.example) "
                        "or *");
    out.push_back(o);
  }
  return out;
}

// "hooks.shop.example, 10.0.0.7, *.shop.example" -> lower-case host names and addresses.
std::vector<std::string> hosts(const std::string& where, const std::string& v) {
  std::vector<std::string> out;
  std::size_t from = 0;
  while (from <= v.size()) {
    std::size_t to = v.find(',', from);
    if (to == std::string::npos) to = v.size();
    std::string h = v.substr(from, to - from);
    from = to + 1;
    h.erase(0, h.find_first_not_of(" \t"));
    h.erase(h.find_last_not_of(" \t") + 1);
    if (h.empty()) continue;
    if (h.size() > 2 && h.front() == '[' && h.back() == ']') h = h.substr(1, h.size() - 2);
    for (char& c : h) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const std::size_t wild = h.starts_with("*.") ? 2 : 0;
    if (h.size() == wild ||
        h.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789.-:", wild) != std::string::npos)
      throw ConfigError(where + ": '" + h +
                        "' is not a host name, an address or *.domain (no scheme, no port)");
    out.push_back(h);
  }
  return out;
}

const std::vector<Setting>& settings() {
  static const std::vector<Setting> table = {
      {"host", "PAPERNET_HOST", "address to listen on (default 127.0.0.1)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.host = v; }},
      {"port", "PAPERNET_PORT", "TCP port, 0 = any free one (default 8080)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.port = static_cast<int>(count(w, v, 0, 65535));
       }},
      {"data", "PAPERNET_DATA", "directory of the SQLite job store (default ./var)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.data_dir = v; }},
      {"store", "PAPERNET_STORE",
       "job store: sqlite (the file papernet.sqlite under --data; default) or a "
       "postgres://user:password@host/database URL that several nodes share",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         if (v != "sqlite" && !is_postgres_url(v))
           throw ConfigError(w + ": '" + redact_store_url(v) +
                             "' is neither sqlite nor a postgres:// URL");
         c.store = v;
       }},
      {"lease", "PAPERNET_LEASE",
       "seconds a running job's lease lasts; when its node stops renewing it (a crash), "
       "another node runs the job after this long (default 30)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.lease = seconds(w, v);
         if (c.lease < 1) throw ConfigError(w + ": a lease lasts at least 1 second");
       }},
      {"max-attempts", "PAPERNET_MAX_ATTEMPTS",
       "times a job may be started before it fails with interrupted_too_often, when its node "
       "crashed or stopped each time (default 3)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.max_attempts = static_cast<int>(count(w, v, 1, 100));
       }},
      {"workers", "PAPERNET_WORKERS", "geometry worker threads (default: one per core)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.workers = count(w, v, 1, 256);
       }},
      {"http-threads", "PAPERNET_HTTP_THREADS",
       "threads serving HTTP connections, one per open connection, event streams apart "
       "(default 16)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.http_threads = count(w, v, 2, 1024);
       }},
      {"max-streams", "PAPERNET_MAX_STREAMS",
       "live progress streams (GET /v1/jobs/{id}/events) open at once, each on a thread of its "
       "own beside --http-threads; the next one is answered 429 too_many_streams with "
       "Retry-After (default 500)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.max_streams = count(w, v, 0, 10'000);
       }},
      {"queue-length", "PAPERNET_QUEUE_LENGTH", "queued jobs before 429 (default 64)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.queue_length = count(w, v, 1, 1'000'000);
       }},
      {"max-body-bytes", "PAPERNET_MAX_BODY_BYTES", "largest upload in bytes (default 64 MiB)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.max_body_bytes = count(w, v, 1024, std::size_t{4} << 30);
       }},
      {"max-faces", "PAPERNET_MAX_FACES", "most faces a mesh may have (default 1000000)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.max_faces = count(w, v, 4, 100'000'000);
       }},
      {"job-time-limit", "PAPERNET_JOB_TIME_LIMIT",
       "seconds a job may run when it names no time_limit (default 120)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.job_time_limit = seconds(w, v);
       }},
      {"max-job-time-limit", "PAPERNET_MAX_JOB_TIME_LIMIT",
       "largest time_limit a job may ask for (default 600)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.max_job_time_limit = seconds(w, v);
       }},
      {"shutdown-grace", "PAPERNET_SHUTDOWN_GRACE",
       "seconds running jobs get to finish on SIGTERM before they are re-queued (default 10)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.shutdown_grace = seconds(w, v);
       }},
      {"read-timeout", "PAPERNET_READ_TIMEOUT",
       "seconds one read from a client may wait for data (default 5)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.read_timeout = seconds(w, v);
       }},
      {"header-timeout", "PAPERNET_HEADER_TIMEOUT",
       "seconds a client has to send a request's line and headers (default 10)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.header_timeout = seconds(w, v);
       }},
      {"request-timeout", "PAPERNET_REQUEST_TIMEOUT",
       "seconds a client has to send a whole request, upload included (default 120)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.request_timeout = seconds(w, v);
       }},
      {"reuse-results", "PAPERNET_REUSE_RESULTS",
       "answer identical mesh + options from a stored result (default true)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.reuse_results = yes_no(w, v);
       }},
      {"access-log", "PAPERNET_ACCESS_LOG", "one log line per request (default true)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.access_log = yes_no(w, v);
       }},
      {"web-root", "PAPERNET_WEB_ROOT",
       "directory of the web demo served at / (the built clients/web bundle; default none)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.web_root = v; }},
      {"cors-origins", "PAPERNET_CORS_ORIGINS",
       "comma-separated origins whose pages may call the API from a browser, e.g. "
       "https://shop.example (CORS, preflight answered); * = any origin, only without "
       "--api-keys (default none: same-origin pages only)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.cors_origins = origins(w, v);
       }},
      {"api-keys", "PAPERNET_API_KEYS",
       "file of API keys, one a line: TENANT SHA256HEX [rate=N] [share=F] [name=LABEL] (the "
       "key's SHA-256 in hex; rate: requests a second; share: fraction of the queue); every "
       "/v1/jobs request then needs Authorization: Bearer KEY and sees its tenant's jobs only. "
       "Read again on SIGHUP and when the file changes (default none: the API is open)",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.api_keys = v; }},
      {"retention", "PAPERNET_RETENTION",
       "how long a finished job, its upload and its results are kept: seconds or a number "
       "with s, m, h or d; afterwards its files are removed and its id answers 410 "
       "job_expired; 0 = forever (default 7d)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.retention = duration(w, v);
       }},
      {"max-store", "PAPERNET_MAX_STORE",
       "most bytes of uploads and results the store keeps: past it, the finished jobs that "
       "finished first expire early (410 job_expired), before their retention; bytes, or a "
       "number with K, M, G or T; 0 = no bound (default 20G)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.max_store_bytes = byte_size(w, v);
       }},
      {"webhook-hosts", "PAPERNET_WEBHOOK_HOSTS",
       "comma-separated hosts a job's callback_url may name (hooks.shop.example, 10.0.0.7, "
       "*.shop.example); only listed hosts may resolve to loopback or private addresses "
       "(default none: any host whose addresses are all public)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.webhook_hosts = hosts(w, v);
       }},
      {"webhook-secret", "PAPERNET_WEBHOOK_SECRET",
       "key of the HMAC-SHA256 signature in each callback's X-Papernet-Signature header; "
       "without it callback_url is refused (default none); prefer the variable to the flag, "
       "which other users see in ps",
       [](ServerConfig& c, const std::string&, const std::string& v) { c.webhook_secret = v; }},
      {"webhook-timeout", "PAPERNET_WEBHOOK_TIMEOUT",
       "seconds a callback attempt may take to connect, and each to send and to receive "
       "(default 5)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.webhook_timeout = seconds(w, v);
         if (c.webhook_timeout <= 0 || c.webhook_timeout > 60)
           throw ConfigError(w + ": a callback timeout is more than 0 and at most 60 seconds");
       }},
      {"webhook-retry-for", "PAPERNET_WEBHOOK_RETRY_FOR",
       "how long a callback is retried (backoff 1, 2, 4 ... at most 300 s apart) after its "
       "first attempt: seconds or a number with s, m, h or d (default 1h)",
       [](ServerConfig& c, const std::string& w, const std::string& v) {
         c.webhook_retry_for = duration(w, v);
       }},
  };
  return table;
}

}  // namespace

std::optional<ServerConfig> parse_serve_config(
    int argc, char** argv, const std::function<const char*(const char*)>& getenv) {
  ServerConfig config;
  for (const Setting& s : settings())
    if (const char* v = getenv(s.env)) s.set(config, std::string("environment ") + s.env, v);
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") return std::nullopt;
    if (arg.rfind("--", 0) != 0) throw ConfigError("unexpected argument '" + arg + "'");
    std::string value;
    bool has_value = false;
    if (const auto eq = arg.find('='); eq != std::string::npos) {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
      has_value = true;
    }
    const Setting* found = nullptr;
    for (const Setting& s : settings())
      if (arg == std::string("--") + s.flag) found = &s;
    if (!found) throw ConfigError("unknown flag '" + arg + "' (see papernet serve --help)");
    if (!has_value) {
      if (i + 1 >= argc) throw ConfigError("flag '" + arg + "' needs a value");
      value = argv[++i];
    }
    found->set(config, "flag " + arg, value);
  }
  for (const std::string& o : config.cors_origins)
    if (o == "*" && !config.api_keys.empty())
      throw ConfigError(
          "--cors-origins '*' is refused with --api-keys: list the origins of the pages that "
          "may use the keys");
  if (config.workers == 0)
    config.workers = std::max<std::size_t>(1, std::thread::hardware_concurrency());
  if (config.read_timeout <= 0 || config.header_timeout <= 0 || config.request_timeout <= 0)
    throw ConfigError("read, header and request timeouts must be more than 0 seconds");
  if (config.job_time_limit <= 0 || config.job_time_limit > config.max_job_time_limit)
    throw ConfigError("job time limit must be more than 0 and at most the max job time limit");
  return config;
}

std::string serve_usage() {
  std::ostringstream out;
  out << "usage: papernet serve [--flag VALUE]...\n\n"
         "Runs the HTTP job service (API under /v1, OpenAPI at /v1/openapi.json).\n"
         "Each flag may also be set by its environment variable; flags win.\n\n";
  for (const Setting& s : settings())
    out << "  --" << s.flag << " (" << s.env << ")\n      " << s.help << "\n";
  return out.str();
}

}  // namespace papernet::server
