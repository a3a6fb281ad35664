#include "server/problem.h"

#include <new>
#include <string_view>

#include "core/errors.h"
#include "core/mesh/validate.h"
#include "engine/pipeline.h"
#include "server/store_records.h"

namespace papernet::server {
namespace {

struct ProblemType {
  std::string_view code;
  int status;
  std::string_view title;
};

// Every code the API can answer with. Clients may rely on the codes; add, never rename.
constexpr ProblemType kProblemTypes[] = {
    {"unknown_option", 400, "Unknown option"},
    {"invalid_option_value", 400, "Invalid option value"},
    {"option_out_of_range", 400, "Option out of range"},
    {"conflicting_options", 400, "Conflicting options"},
    {"malformed_options", 400, "Malformed options"},
    {"malformed_request", 400, "Malformed request"},
    {"missing_mesh", 400, "No mesh in the request"},
    {"missing_api_key", 401, "API key required"},
    {"invalid_api_key", 401, "API key not accepted"},
    {"origin_not_allowed", 403, "Origin not allowed"},
    {"not_found", 404, "No such resource"},
    {"job_not_found", 404, "No such job"},
    {"method_not_allowed", 405, "Method not allowed"},
    {"request_timeout", 408, "Request timeout"},
    {"result_not_ready", 409, "Result not ready"},
    {"job_finished", 409, "Job already finished"},
    {"idempotency_key_in_use", 409, "Idempotency-Key in use"},
    {"job_cancelled", 410, "Job was cancelled"},
    {"job_expired", 410, "Job expired"},
    {"length_required", 411, "Content-Length required"},
    {"payload_too_large", 413, "Upload too large"},
    {"too_many_faces", 413, "Mesh has too many faces"},
    {"image_too_large", 413, "Texture image has too many pixels"},
    {"uri_too_long", 414, "Request URI too long"},
    {"unsupported_format", 415, "Unsupported mesh format"},
    {"idempotency_key_reused", 422, "Idempotency-Key used for another request"},
    {"callback_url_refused", 422, "Callback URL refused"},
    {"unreadable_mesh", 422, "Mesh cannot be read"},
    {"invalid_mesh", 422, "Mesh cannot be unfolded"},
    {"unfold_failed", 422, "No overlap-free net found"},
    {"face_too_large", 422, "A face is larger than a sheet"},
    {"print_too_large", 422, "Print larger than a kit holds"},
    {"time_limit_exceeded", 422, "Job ran out of time"},
    {"interrupted_too_often", 422, "Job interrupted too often"},
    {"queue_full", 429, "Queue full"},
    {"too_many_streams", 429, "Too many event streams"},
    {"rate_limited", 429, "Too many requests for this API key"},
    {"request_head_too_large", 431, "Request line or headers too large"},
    {"internal_error", 500, "Internal error"},
    {"store_failed", 500, "Job store failed"},
    {"shutting_down", 503, "Server shutting down"},
    {"store_unavailable", 503, "Job store unavailable"},
};

// The validator's findings as the problem's extension members.
Problem invalid_mesh(const ValidationReport& report) {
  nlohmann::json reasons = nlohmann::json::array();
  for (const MeshProblem& p : report.problems)
    if (p.blocking)
      reasons.push_back({{"code", p.code}, {"message", p.message}, {"elements", p.elements}});
  return make_problem("invalid_mesh", report.reason(),
                      {{"reasons", reasons},
                       {"mesh",
                        {{"vertices", report.vertices},
                         {"faces", report.faces},
                         {"components", report.components},
                         {"genus", report.genus},
                         {"boundary_loops", report.boundary_loops}}}});
}

const ProblemType* lookup(std::string_view code) {
  for (const ProblemType& t : kProblemTypes)
    if (t.code == code) return &t;
  return nullptr;
}

}  // namespace

Problem make_problem(const std::string& code, std::string detail, nlohmann::json extra) {
  const ProblemType* type = lookup(code);
  if (!type) return make_problem("internal_error", "unknown problem code '" + code + "'");
  Problem p;
  p.status = type->status;
  p.code = std::string(type->code);
  p.title = std::string(type->title);
  p.detail = std::move(detail);
  p.extra = extra.is_object() ? std::move(extra) : nlohmann::json::object();
  if (p.status == 429 || p.status == 503) p.retry_after = 5;
  return p;
}

Problem problem_from_exception(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const ApiError& e) {
    return e.problem();
  } catch (const InvalidOptionException& e) {
    nlohmann::json extra = nlohmann::json::object();
    if (!e.option().empty()) extra["option"] = e.option();
    return make_problem(e.code(), e.what(), extra);
  } catch (const LimitExceededException& e) {
    const auto limit = e.limit();
    return make_problem(limit == LimitExceededException::Limit::Bytes    ? "payload_too_large"
                        : limit == LimitExceededException::Limit::Pixels ? "image_too_large"
                                                                         : "too_many_faces",
                        e.what());
  } catch (const InvalidMeshException& e) {
    return invalid_mesh(e.report());
  } catch (const InvalidInputException& e) {
    return make_problem("invalid_mesh", e.what());
  } catch (const IOException& e) {
    return make_problem("unreadable_mesh", e.what());
  } catch (const CancelledException&) {
    return make_problem("job_cancelled", "the job was cancelled");
  } catch (const TopologyException& e) {
    return make_problem("unfold_failed", e.what());
  } catch (const StoreUnavailable& e) {
    return make_problem("store_unavailable", e.what());
  } catch (const StoreError& e) {
    return make_problem("store_failed", e.what());
  } catch (const std::bad_alloc&) {
    return make_problem("too_many_faces", "the mesh needs more memory than this server gives");
  } catch (const std::exception& e) {
    return make_problem("internal_error", e.what());
  } catch (...) {
    return make_problem("internal_error", "unknown error");
  }
}

nlohmann::json problem_json(const Problem& p, const std::string& instance) {
  nlohmann::json doc = p.extra;
  doc["type"] = "urn:papernet:problem:" + p.code;
  doc["title"] = p.title;
  doc["status"] = p.status;
  doc["code"] = p.code;
  doc["detail"] = p.detail;
  if (!instance.empty()) doc["instance"] = instance;
  return doc;
}

Problem problem_from_json(const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("code"))
    return make_problem("internal_error", "stored error is unreadable");
  nlohmann::json extra = doc;
  for (const char* key : {"type", "title", "status", "code", "detail", "instance"})
    extra.erase(key);
  return make_problem(doc["code"].get<std::string>(), doc.value("detail", ""), extra);
}

}  // namespace papernet::server
