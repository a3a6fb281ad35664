#include "server/http_api.h"

#include <httplib.h>

#include <chrono>
#include <regex>
#include <thread>

#include "api/openapi.h"
#include "server/job_json.h"
#include "server/problem.h"
#include "server/upload.h"

namespace papernet::server {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Set when a request starts routing; the access logger runs on the same thread afterwards.
thread_local Clock::time_point request_start;

void send_problem(httplib::Response& res, const Problem& p, const std::string& instance) {
  res.status = p.status;
  res.set_content(problem_json(p, instance).dump(), "application/problem+json");
  if (p.retry_after) res.set_header("Retry-After", std::to_string(*p.retry_after));
}

void send_json(httplib::Response& res, int status, const json& doc) {
  res.status = status;
  res.set_content(doc.dump(), "application/json");
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

JobView find_job(JobService& service, const httplib::Request& req) {
  const std::string id = job_id_of(req);
  auto view = service.view(id);
  if (!view) throw ApiError("job_not_found", "no job " + id);
  return *view;
}

struct Api {
  Api(JobService& s, const ServerConfig& c, HttpMetrics& m) : service(s), config(c), metrics(m) {}
  JobService& service;
  const ServerConfig& config;
  HttpMetrics& metrics;
  std::atomic<int> streams{0};

  void submit(const httplib::Request& req, httplib::Response& res) {
    OptionsLimits limits;
    limits.max_time_limit = config.max_job_time_limit;
    limits.max_target_faces = config.max_faces;
    ParsedUpload upload = parse_upload(upload_request_of(req), limits);
    const JobRecord job = service.submit(std::move(upload.input), std::move(upload.options));
    auto view = service.view(job.id);
    res.set_header("Location", "/v1/jobs/" + job.id);
    send_json(res, 202,
              job_to_json(view ? *view : JobView{job, {}, 0, false, nullptr, {}}, now_seconds()));
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
    for (const JobRecord& r : service.list(limit, cursor)) {
      if (auto view = service.view(r.id)) jobs.push_back(job_to_json(*view, now_seconds()));
      last = r.seq;
      ++n;
    }
    json doc = {{"jobs", jobs}, {"next", nullptr}};
    if (n == limit && last > 1)
      doc["next"] = "/v1/jobs?limit=" + std::to_string(limit) + "&cursor=" + std::to_string(last);
    send_json(res, 200, doc);
  }

  void result(const httplib::Request& req, httplib::Response& res) {
    const JobView view = find_job(service, req);
    const std::string name = req.matches[2];
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
      res.set_content(std::move(file->data), file->content_type);
      return;
    }
    if (view.intermediate) {
      auto it = view.intermediate->files.find(name);
      if (it != view.intermediate->files.end()) {
        res.set_header("X-Papernet-Level",
                       "intermediate; faces=" + std::to_string(view.intermediate->faces) +
                           "; input-faces=" + std::to_string(view.intermediate->input_faces));
        res.set_content(it->second.data, it->second.content_type);
        return;
      }
    }
    Problem p = make_problem("result_not_ready", "job " + r.id + " is " + status_name(r.status) +
                                                     " and has no overlap-free intermediate " +
                                                     name + " yet");
    p.retry_after = 1;
    send_problem(res, p, req.path);
  }

  void events(const httplib::Request& req, httplib::Response& res) {
    const std::string id = find_job(service, req).record.id;
    if (streams.fetch_add(1) >= static_cast<int>(config.http_threads / 2)) {
      streams.fetch_sub(1);
      Problem p = make_problem("too_many_streams", "too many open event streams; poll instead");
      p.retry_after = 5;
      throw ApiError(p);
    }
    res.set_header("Cache-Control", "no-store");
    auto last_version = std::make_shared<std::uint64_t>(0);
    auto last_doc = std::make_shared<std::string>();
    auto sequence = std::make_shared<int>(0);
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, id, last_version, last_doc, sequence](std::size_t, httplib::DataSink& sink) {
          *last_version = service.wait_for_change(*last_version, std::chrono::seconds(1));
          auto view = service.view(id);
          const bool final = !view || is_final(view->record.status);
          std::string doc = view ? job_to_json(*view, now_seconds()).dump() : "null";
          if (doc != *last_doc || final) {
            const std::string event = std::string("id: ") + std::to_string(++*sequence) +
                                      "\nevent: " + (final ? "done" : "progress") +
                                      "\ndata: " + doc + "\n\n";
            if (!sink.write(event.data(), event.size())) return false;
            *last_doc = std::move(doc);
          }
          if (final || !service.accepting()) {
            sink.done();
            return true;
          }
          // At most ten events a second, however often the unfolder reports.
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
          return sink.is_writable();
        },
        [this](bool) { streams.fetch_sub(1); });
  }
};

std::string job_id_in_path(const std::string& path) {
  static const std::regex pattern("^/v1/jobs/([0-9a-f]{32})");
  std::smatch m;
  return std::regex_search(path, m, pattern) ? m[1].str() : std::string();
}

}  // namespace

void install_routes(httplib::Server& http, JobService& service, const ServerConfig& config,
                    HttpMetrics& metrics) {
  auto api = std::make_shared<Api>(service, config, metrics);
  const std::string job = "/v1/jobs/([^/]+)";

  http.set_payload_max_length(config.max_body_bytes);
  http.set_pre_routing_handler([](const httplib::Request&, httplib::Response&) {
    request_start = Clock::now();
    return httplib::Server::HandlerResponse::Unhandled;
  });
  // Answers httplib produced itself (unknown route, body over the limit, unparsable request)
  // get a problem document too.
  http.set_error_handler(httplib::Server::HandlerWithResponse([&config](const httplib::Request& req,
                                                                        httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    Problem p;
    if (res.status == 413)
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
    metrics.count(res.status, seconds);
    if (!config.access_log) return;
    std::string id = job_id_in_path(req.path);
    if (id.empty()) id = job_id_in_path(res.get_header_value("Location"));
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1fms", seconds * 1000);
    log_line("access " + req.method + " " + req.path + " " + std::to_string(res.status) + " " + ms +
             (id.empty() ? "" : " job=" + id));
  });

  http.Get("/healthz", guarded([](const httplib::Request&, httplib::Response& res) {
             send_json(res, 200, {{"status", "ok"}});
           }));
  http.Get("/readyz", guarded([&service](const httplib::Request&, httplib::Response& res) {
             if (!service.accepting())
               throw ApiError("shutting_down", "the server is shutting down");
             send_json(res, 200, {{"status", "ready"}});
           }));
  http.Get("/metrics",
           guarded([&service, &metrics](const httplib::Request&, httplib::Response& res) {
             res.set_content(render_metrics(service.stats(), metrics),
                             "text/plain; version=0.0.4; charset=utf-8");
           }));
  http.Get("/v1/openapi.json", guarded([](const httplib::Request&, httplib::Response& res) {
             res.set_content(std::string(openapi_document()), "application/json");
           }));
  http.Post("/v1/jobs", guarded([api](const httplib::Request& req, httplib::Response& res) {
              api->submit(req, res);
            }));
  http.Get("/v1/jobs", guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->list(req, res);
           }));
  http.Get(job, guarded([&service](const httplib::Request& req, httplib::Response& res) {
             send_json(res, 200, job_to_json(find_job(service, req), now_seconds()));
           }));
  http.Delete(job, guarded([&service](const httplib::Request& req, httplib::Response& res) {
                send_json(res, 202, job_to_json(service.cancel(job_id_of(req)), now_seconds()));
              }));
  http.Get(job + "/events", guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->events(req, res);
           }));
  http.Get(job + "/(net\\.json|net\\.svg|net\\.pdf|mesh\\.glb)",
           guarded([api](const httplib::Request& req, httplib::Response& res) {
             api->result(req, res);
           }));
}

}  // namespace papernet::server
