#include "server/http_api.h"

#include <httplib.h>

#include <chrono>
#include <mutex>
#include <optional>
#include <regex>
#include <thread>

#include "api/openapi.h"
#include "core/io/json_text.h"
#include "server/api_keys.h"
#include "server/event_streams.h"
#include "server/http_server.h"
#include "server/internal/methods_cors.h"
#include "server/job_json.h"
#include "server/problem.h"
#include "server/store_records.h"
#include "server/upload.h"
#include "server/webhooks.h"

namespace papernet::server {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Set when a request starts routing; the handlers and the access logger run on the same
// thread afterwards.
thread_local Clock::time_point request_start;
// The problem code of the answer being sent ("" for none), for /metrics.
thread_local std::string request_problem;
// The tenant of the request's API key ("" without keys): it owns what it submits and sees
// nothing else.
thread_local std::string request_tenant;
thread_local double request_queue_share = 1;  // the key's share= (1 without keys)

// The longest Authorization header looked at: keys are short; a longer header is refused
// before it is hashed.
constexpr std::size_t kMaxAuthorization = 256;

void send_problem(httplib::Response& res, const Problem& p, const std::string& instance) {
  res.status = p.status;
  request_problem = p.code;
  // The path is the client's: echo no more of it than a job's result path needs.
  res.set_content(json_text(problem_json(p, instance.substr(0, 128))), "application/problem+json");
  if (p.retry_after) res.set_header("Retry-After", std::to_string(*p.retry_after));
}

void send_json(httplib::Response& res, int status, const json& doc) {
  res.status = status;
  res.set_content(json_text(doc), "application/json");
}

// Ends a chunked response. cpp-httplib writes the last chunk from a function-local static that
// it initialises on first use, behind a guard inside the (uninstrumented) library: ThreadSanitizer
// would report every later end, on other threads, as racing with that first one. The first end
// is therefore made under a mutex that every end passes, which TSan sees.
void end_chunked(httplib::DataSink& sink) {
  static std::mutex first_mutex;
  static bool first_done = false;
  {
    std::lock_guard lock(first_mutex);
    if (!first_done) {
      sink.done();
      first_done = true;
      return;
    }
  }
  sink.done();
}

// Every handler runs inside this: whatever it throws becomes a problem, mapped in problem.cpp.
template <class Handler>
httplib::Server::Handler guarded(Handler handler) {
  return [handler](const httplib::Request& req, httplib::Response& res) {
    try {
      handler(req, res);
    } catch (...) {
      send_problem(res, problem_from_exception(std::current_exception()), req.path);
    }
  };
}

std::string job_id_of(const httplib::Request& req) {
  const std::string id = req.matches.size() > 1 ? std::string(req.matches[1]) : std::string();
  if (!valid_job_id(id)) throw ApiError("job_not_found", "no job '" + id.substr(0, 64) + "'");
  return id;
}

// Another tenant's job is answered exactly like one that does not exist.
JobView find_job(JobService& service, const httplib::Request& req) {
  const std::string id = job_id_of(req);
  auto view = service.view(id, &request_tenant);
  if (!view) throw ApiError("job_not_found", "no job " + id);
  if (view->record.expired)
    throw ApiError("job_expired", "job " + id +
                                      " finished longer ago than this server keeps jobs "
                                      "(--retention); its upload and results were removed");
  return *view;
}

// Who is asking, with keys configured: sets request_tenant, or returns the problem to answer.
std::optional<Problem> authenticate(ApiKeyRing& keys, RateLimiter& limiter,
                                    const httplib::Request& req) {
  const std::string header = req.get_header_value("Authorization");
  if (header.empty())
    return make_problem("missing_api_key",
                        "this server needs an API key: send Authorization: Bearer <key>");
  if (header.size() > kMaxAuthorization)
    return make_problem("invalid_api_key", "the Authorization header is longer than " +
                                               std::to_string(kMaxAuthorization) +
                                               " bytes; no papernet key is that long");
  std::string scheme = header.substr(0, 7);
  for (char& c : scheme) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string secret = header.size() > 7 ? header.substr(7) : std::string();
  if (scheme != "bearer " || secret.empty() || secret.find_first_of(" \t") != std::string::npos)
    return make_problem("invalid_api_key",
                        "the Authorization header is not of the form Bearer <key>");
  const std::optional<ApiKey> key = keys.find(secret);
  if (!key) return make_problem("invalid_api_key", "the API key is unknown or was revoked");
  request_tenant = key->tenant;
  request_queue_share = key->share;
  if (const int wait = limiter.take(sha256_hex(secret), key->rate); wait > 0) {
    Problem p = make_problem("rate_limited", "this API key may make " + std::to_string(key->rate) +
                                                 " requests a second; retry later");
    p.retry_after = wait;
    return p;
  }
  return std::nullopt;
}

// Reads the upload's body through `reader`, never more than `max_bytes` of it (after any
// Content-Encoding is undone): a chunked, length-less or compressed body is refused with 413 as
// soon as it passes the limit, before it is all in memory.
UploadRequest upload_of(const httplib::Request& req, const httplib::ContentReader& reader,
                        std::size_t max_bytes) {
  UploadRequest up;
  up.content_type = req.get_header_value("Content-Type");
  up.query = {req.params.begin(), req.params.end()};
  up.multipart = req.is_multipart_form_data();
  std::size_t total = 0;
  bool too_large = false, too_many_parts = false;
  auto take = [&](std::string& into, const char* data, std::size_t n) {
    total += n;
    if (total > max_bytes) {
      too_large = true;
      return false;
    }
    into.append(data, n);
    return true;
  };
  bool ok = false;
  if (up.multipart) {
    ok = reader(
        [&](const httplib::MultipartFormData& part) {
          if (up.parts.size() >= 64) {
            too_many_parts = true;
            return false;
          }
          up.parts.push_back({part.name, part.filename, part.content_type, {}});
          return true;
        },
        [&](const char* data, std::size_t n) {
          return !up.parts.empty() && take(up.parts.back().content, data, n);
        });
  } else {
    ok = reader([&](const char* data, std::size_t n) { return take(up.body, data, n); });
  }
  if (ok) return up;
  close_connection_after_response();
  const RequestReadState state = request_read_state();
  if (too_large || state.body_too_large)
    throw ApiError("payload_too_large", "the upload is larger than this server's limit of " +
                                            std::to_string(max_bytes) + " bytes");
  if (state.timed_out)
    throw ApiError("request_timeout",
                   "the upload did not arrive in time (read timeout or "
                   "request deadline passed)");
  if (too_many_parts) throw ApiError("malformed_request", "more than 64 form parts");
  throw ApiError("malformed_request",
                 "the request body could not be read: truncated, a bad chunked or multipart "
                 "framing, or a Content-Encoding that does not decode");
}

// A body on a route that takes none (everything but POST /v1/jobs) is refused before it is
// read: httplib would buffer a chunked or compressed one without bound.
bool refuse_unexpected_body(const httplib::Request& req) {
  if (req.method == "POST" && req.path == "/v1/jobs") return false;
  if (req.has_header("Transfer-Encoding") || req.has_header("Content-Encoding")) return true;
  return req.get_header_value<std::uint64_t>("Content-Length") > (std::uint64_t{64} << 10);
}

// How long an Idempotency-Key stands for its first request.
constexpr double kIdempotencyWindow = 24 * 3600;

bool valid_idempotency_key(const std::string& key) {
  if (key.empty() || key.size() > 255) return false;
  for (char c : key)
    if (c < 0x21 || c > 0x7e) return false;
  return true;
}

// "The same body": the same mesh, files and options, however they were framed (a multipart
// boundary or the order of query parameters does not count).
std::string request_hash(const ParsedUpload& upload) {
  const std::string format = format_name(upload.input.format);
  const std::string options = json_text(options_to_json(upload.options));
  std::vector<std::string_view> parts = {format, options, upload.input.mesh};
  for (const auto& [name, data] : upload.input.external_files) {
    parts.push_back(name);
    parts.push_back(data);
  }
  return sha256_hex_of_parts(parts);
}

struct Api {
  Api(JobService& s, const ServerConfig& c, HttpMetrics& m)
      : service(s), config(c), metrics(m), streams(s, c.max_streams) {}
  JobService& service;
  const ServerConfig& config;
  HttpMetrics& metrics;
  EventStreams streams;

  void submit(const httplib::Request& req, httplib::Response& res,
              const httplib::ContentReader& reader) {
    OptionsLimits limits;
    limits.max_time_limit = config.max_job_time_limit;
    limits.max_target_faces = config.max_faces;
    const bool idempotent = req.has_header("Idempotency-Key");
    const std::string key = req.get_header_value("Idempotency-Key");
    if (idempotent && !valid_idempotency_key(key))
      throw ApiError("malformed_request",
                     "an Idempotency-Key is 1 to 255 visible ASCII characters (a UUID will do)");
    ParsedUpload upload = parse_upload(upload_of(req, reader, config.max_body_bytes), limits);
    // Refused here, before a job exists, so that the caller learns of it (422 naming the
    // option); the sender checks the host again at every attempt.
    if (upload.options.callback_url)
      callback_addresses(parse_callback_url(*upload.options.callback_url),
                         webhook_settings(config));
    std::string id;
    if (idempotent) {
      const std::string hash = request_hash(upload);
      const double now = now_seconds();
      id = new_job_id();
      const IdempotencyRecord stored = service.remember_idempotency(
          request_tenant, key, {hash, id, now}, now - kIdempotencyWindow);
      if (stored.job_id != id) {  // a retry: the first request's job
        if (stored.request_hash != hash)
          throw ApiError("idempotency_key_reused",
                         "this Idempotency-Key was used in the last 24 hours for another request "
                         "(another mesh or options); use a new key for a new request");
        auto first = service.view(stored.job_id);
        if (!first || first->record.tenant != request_tenant) {
          Problem p = make_problem("idempotency_key_in_use",
                                   "the first request with this Idempotency-Key is still being "
                                   "stored; retry in a moment");
          p.retry_after = 1;
          throw ApiError(p);
        }
        res.set_header("Location", "/v1/jobs/" + stored.job_id);
        res.set_header("Idempotent-Replayed", "true");
        send_json(res, 200, job_to_json(*first, now_seconds()));
        return;
      }
    }
    JobRecord job;
    try {
      job = service.submit(std::move(upload.input), std::move(upload.options),
                           {request_tenant, id, request_queue_share});
    } catch (...) {
      if (idempotent) service.forget_idempotency(request_tenant, key, id);
      throw;
    }
    // The job as accepted: queued (with its place) or answered from a stored result. A worker
    // may have claimed it already; the next poll shows that.
    JobView accepted{job, {}, 0, false, std::nullopt, job.result_files, std::nullopt};
    if (auto view = service.view(job.id); view && view->record.status == job.status)
      accepted = *view;
    res.set_header("Location", "/v1/jobs/" + job.id);
    send_json(res, 202, job_to_json(accepted, now_seconds()));
  }

  void list(const httplib::Request& req, httplib::Response& res) {
    std::size_t limit = 20;
    std::int64_t cursor = 0;
    try {
      if (req.has_param("limit")) limit = std::stoul(req.get_param_value("limit"));
      if (req.has_param("cursor")) cursor = std::stoll(req.get_param_value("cursor"));
    } catch (const std::exception&) {
      throw ApiError("malformed_request", "limit and cursor must be whole numbers");
    }
    if (limit < 1 || limit > 100 || cursor < 0)
      throw ApiError("malformed_request", "limit must be 1..100 and cursor not negative");
    json jobs = json::array();
    std::int64_t last = 0;
    std::size_t n = 0;
    for (const JobRecord& r : service.list(request_tenant, limit, cursor)) {
      if (auto view = service.view(r.id)) jobs.push_back(job_to_json(*view, now_seconds()));
      last = r.seq;
      ++n;
    }
    json doc = {{"jobs", jobs}, {"next", nullptr}};
    if (n == limit && last > 1)
      doc["next"] = "/v1/jobs?limit=" + std::to_string(limit) + "&cursor=" + std::to_string(last);
    send_json(res, 200, doc);
  }

  // A result file: `name`, else the one the path names (net.json, ...).
  void result(const httplib::Request& req, httplib::Response& res, std::string name = {}) {
    const JobView view = find_job(service, req);
    if (name.empty()) name = req.matches[2];
    const JobRecord& r = view.record;
    if (r.status == JobStatus::Failed) {
      send_problem(res, problem_from_json(r.error), req.path);
      return;
    }
    if (r.status == JobStatus::Cancelled)
      throw ApiError("job_cancelled", "job " + r.id + " was cancelled; it has no result");
    if (is_final(r.status)) {
      auto file = service.artifact(r.result_job, name);
      if (!file) throw ApiError("not_found", "job " + r.id + " has no " + name);
      res.set_header("X-Papernet-Level", r.result_kind + "; faces=" + std::to_string(r.faces) +
                                             "; input-faces=" + std::to_string(r.input_faces));
      res.set_header("Content-Disposition",
                     content_disposition(r.options, name, file->content_type));
      res.set_content(std::move(file->data), file->content_type);
      return;
    }
    if (auto file = service.intermediate(r.id, name)) {
      res.set_header("X-Papernet-Level", "intermediate; faces=" + std::to_string(file->faces) +
                                             "; input-faces=" + std::to_string(file->input_faces));
      res.set_header("Content-Disposition",
                     content_disposition(r.options, name, file->file.content_type));
      res.set_content(std::move(file->file.data), file->file.content_type);
      return;
    }
    Problem p = make_problem("result_not_ready", "job " + r.id + " is " + status_name(r.status) +
                                                     " and has no overlap-free intermediate " +
                                                     name + " yet");
    p.retry_after = 1;
    send_problem(res, p, req.path);
  }

  void events(const httplib::Request& req, httplib::Response& res) {
    const std::string id = find_job(service, req).record.id;
    if (!service.accepting())
      throw ApiError("shutting_down", "the server is shutting down; try again");
    std::shared_ptr<EventStreams::Watch> watch = streams.open(id);
    if (!watch) {
      Problem p = make_problem("too_many_streams", "the server has its most event streams open (" +
                                                       std::to_string(streams.max_streams()) +
                                                       "); poll GET /v1/jobs/" + id +
                                                       " instead, or retry later");
      p.retry_after = 5;
      throw ApiError(p);
    }
    ++metrics.open_streams;
    res.set_header("Cache-Control", "no-store");
    auto seen = std::make_shared<std::uint64_t>(0);
    auto sequence = std::make_shared<int>(0);
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, watch, seen, sequence](std::size_t, httplib::DataSink& sink) {
          const EventStreams::State state = streams.next(*watch, *seen, std::chrono::seconds(1));
          if (state.generation != 0 && state.generation != *seen) {
            const std::string event = std::string("id: ") + std::to_string(++*sequence) +
                                      "\nevent: " + (state.final ? "done" : "progress") +
                                      "\ndata: " + state.doc + "\n\n";
            if (!sink.write(event.data(), event.size())) return false;
            *seen = state.generation;
          }
          if (state.final || state.closing) {
            end_chunked(sink);
            return true;
          }
          return !client_closed();
        },
        [this](bool) { --metrics.open_streams; });
  }
};

std::string job_id_in_path(const std::string& path) {
  static const std::regex pattern("^/v1/jobs/([0-9a-f]{32})");
  std::smatch m;
  return std::regex_search(path, m, pattern) ? m[1].str() : std::string();
}

}  // namespace

void install_routes(httplib::Server& http, JobService& service, const ServerConfig& config,
                    HttpMetrics& metrics, ApiKeyRing* keys) {
  auto api = std::make_shared<Api>(service, config, metrics);
  auto limiter = std::make_shared<RateLimiter>();
  const std::string job = "/v1/jobs/([^/]+)";

  http.set_payload_max_length(config.max_body_bytes);
  // A declared length over the limit is refused before the body is read (and before a client
  // that asked "Expect: 100-continue" sends it).
  auto declared_too_large = [&config](const httplib::Request& req) {
    return req.get_header_value<std::uint64_t>("Content-Length") > config.max_body_bytes;
  };
  http.set_expect_100_continue_handler(
      [declared_too_large](const httplib::Request& req, httplib::Response& res) {
        if (!declared_too_large(req)) return 100;
        close_connection_after_response();
        res.status = 413;  // the error handler below writes the problem
        return 413;
      });
  http.set_pre_routing_handler([&config, declared_too_large, keys, limiter](
                                   const httplib::Request& req, httplib::Response& res) {
    request_start = Clock::now();
    request_problem.clear();
    request_tenant.clear();
    request_queue_share = 1;
    Problem p;
    const std::string allowed = allowed_methods(req.path);
    if (!allowed.empty()) {
      const std::optional<std::string> origin =
          req.has_header("Origin") ? std::optional(req.get_header_value("Origin")) : std::nullopt;
      const CorsAnswer cors = answer_cors(config, allowed, req.method, origin,
                                          req.has_header("Access-Control-Request-Method"));
      for (const auto& [name, value] : cors.headers) res.set_header(name, value);
      if (cors.refused) send_problem(res, *cors.refused, req.path);
      if (cors.preflight) {
        if (!cors.refused) res.status = 204;
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    if (keys && !allowed.empty() && req.path.rfind("/v1/jobs", 0) == 0)
      if (std::optional<Problem> refused = authenticate(*keys, *limiter, req)) {
        if (refused->status == 401) res.set_header("WWW-Authenticate", "Bearer realm=\"papernet\"");
        if (req.has_header("Content-Length") || req.has_header("Transfer-Encoding"))
          close_connection_after_response();
        send_problem(res, *refused, req.path);
        return httplib::Server::HandlerResponse::Handled;
      }
    if (!allowed.empty() && !method_allowed(allowed, req.method)) {
      res.set_header("Allow", allowed);
      p = make_problem("method_not_allowed", req.method + " is not allowed on " +
                                                 req.path.substr(0, 128) + " (allowed: " + allowed +
                                                 ")");
      // A body we do not read must not be taken for the next request.
      if (req.has_header("Content-Length") || req.has_header("Transfer-Encoding"))
        close_connection_after_response();
      send_problem(res, p, req.path);
      return httplib::Server::HandlerResponse::Handled;
    }
    if (req.method == "POST" && !req.has_header("Content-Length") &&
        !req.has_header("Transfer-Encoding"))
      p = make_problem("length_required",
                       "a POST needs a Content-Length (or a chunked Transfer-Encoding); a "
                       "body that ends only when the connection closes is not read");
    else if (declared_too_large(req))
      p = make_problem("payload_too_large", "the upload declares " +
                                                req.get_header_value("Content-Length") +
                                                " bytes, more than this server's limit of " +
                                                std::to_string(config.max_body_bytes));
    else if (refuse_unexpected_body(req))
      p = make_problem("payload_too_large", req.method + " " + req.path +
                                                " takes no request body (chunked, encoded or "
                                                "over 64 KiB bodies are refused)");
    else
      return httplib::Server::HandlerResponse::Unhandled;
    close_connection_after_response();
    send_problem(res, p, req.path);
    return httplib::Server::HandlerResponse::Handled;
  });
  // Answers httplib produced itself (unknown route, body over the limit, unparsable request)
  // get a problem document too.
  http.set_error_handler(httplib::Server::HandlerWithResponse([&config](const httplib::Request& req,
                                                                        httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    Problem p;
    // httplib answers 400 when a read fails; the guarded stream knows why.
    const RequestReadState state = request_read_state();
    if (state.timed_out) res.status = 408;
    if (state.body_too_large) res.status = 413;
    if (state.head_too_large || state.header_line_too_long) res.status = 431;
    if (res.status == 408)
      p = make_problem("request_timeout",
                       "the request did not arrive in time (read timeout or "
                       "request deadline passed)");
    else if (res.status == 414)
      p = make_problem("uri_too_long", "the request URI is longer than this server accepts");
    else if (res.status == 431 && state.header_line_too_long)
      p = make_problem("request_head_too_large",
                       "a header line is longer than " +
                           std::to_string(CPPHTTPLIB_HEADER_MAX_LENGTH) +
                           " bytes (an Authorization header carries a key of at most " +
                           std::to_string(kMaxAuthorization) + " bytes)");
    else if (res.status == 431)
      p = make_problem("request_head_too_large",
                       "the request line or headers are longer than this server accepts");
    else if (res.status == 413)
      p = make_problem("payload_too_large", "the upload is larger than this server's limit of " +
                                                std::to_string(config.max_body_bytes) + " bytes");
    else if (res.status == 404)
      p = make_problem("not_found", "no resource at " + req.path);
    else if (res.status == 405)
      p = make_problem("method_not_allowed", req.method + " is not allowed on " + req.path);
    else if (res.status >= 500)
      p = make_problem("internal_error", "the server failed to answer");
    else
      p = make_problem("malformed_request", "the request could not be parsed");
    const int status = res.status;
    send_problem(res, p, req.path);
    res.status = status;
    return httplib::Server::HandlerResponse::Handled;
  }));
  http.set_exception_handler(
      [](const httplib::Request& req, httplib::Response& res, std::exception_ptr ep) {
        send_problem(res, problem_from_exception(ep), req.path);
      });
  http.set_logger([&config, &metrics](const httplib::Request& req, const httplib::Response& res) {
    const double seconds = std::chrono::duration<double>(Clock::now() - request_start).count();
    metrics.count(route_of(req.method, req.path), res.status, request_problem, seconds);
    if (!config.access_log) return;
    std::string id = job_id_in_path(req.path);
    if (id.empty()) id = job_id_in_path(res.get_header_value("Location"));
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1fms", seconds * 1000);
    std::string line = "access " + req.method + " " + req.path + " " + std::to_string(res.status);
    line += std::string(" ") + ms;
    if (!id.empty()) line += " job=" + id;
    if (!request_tenant.empty()) line += " tenant=" + request_tenant;
    log_line(line);
  });

  http.Get("/healthz", guarded([](const httplib::Request&, httplib::Response& res) {
             send_json(res, 200, {{"status", "ok"}});
           }));
  // Ready: accepting jobs, and the store answers (a shared database may be down).
  http.Get("/readyz", guarded([&service](const httplib::Request&, httplib::Response& res) {
             if (!service.accepting())
               throw ApiError("shutting_down", "the server is shutting down");
             service.check_store();
             send_json(res, 200, {{"status", "ready"}, {"node", service.node()}});
           }));
  http.Get("/metrics",
           guarded([&service, &metrics](const httplib::Request&, httplib::Response& res) {
             res.set_content(render_metrics(service.stats(), metrics),
                             "text/plain; version=0.0.4; charset=utf-8");
           }));
  http.Get("/v1/openapi.json", guarded([](const httplib::Request&, httplib::Response& res) {
             res.set_content(std::string(openapi_document()), "application/json");
           }));
  http.Post("/v1/jobs", [api](const httplib::Request& req, httplib::Response& res,
                              const httplib::ContentReader& reader) {
    try {
      api->submit(req, res, reader);
    } catch (...) {
      send_problem(res, problem_from_exception(std::current_exception()), req.path);
    }
  });
  http.Get("/v1/jobs", guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->list(req, res);
           }));
  http.Get(job, guarded([&service](const httplib::Request& req, httplib::Response& res) {
             send_json(res, 200, job_to_json(find_job(service, req), now_seconds()));
           }));
  http.Delete(job, guarded([&service](const httplib::Request& req, httplib::Response& res) {
                const std::string id = find_job(service, req).record.id;
                send_json(res, 202, job_to_json(service.cancel(id), now_seconds()));
              }));
  http.Get(job + "/events", guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->events(req, res);
           }));
  http.Get(job + "/(net\\.json|net\\.svg|net\\.pdf|mesh\\.glb)",
           guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->result(req, res);
           }));
  http.Get(job + "/textures/([0-9]{1,6})",
           guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->result(req, res, texture_file_name(std::stoul(req.matches[2].str())));
           }));
  http.Get(job + "/pages/([0-9]{1,6})",
           guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->result(req, res, page_file_name(std::stoul(req.matches[2].str())));
           }));
}

}  // namespace papernet::server
