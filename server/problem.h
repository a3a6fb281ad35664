#pragma once

#include <exception>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

namespace papernet::server {

/// An RFC 9457 problem: what the client is told when something is not right. `code` is stable;
/// status and title follow from it (one table in problem.cpp is the only place that says so).
struct Problem {
  int status = 500;
  std::string code;
  std::string title;
  std::string detail;
  nlohmann::json extra = nlohmann::json::object();  ///< extension members (option, reasons...)
  std::optional<int> retry_after;                   ///< seconds, for 429 and 503
};

/// The problem for a known code. An unknown code is a programming error and becomes
/// internal_error (so the table stays the single source of truth).
Problem make_problem(const std::string& code, std::string detail,
                     nlohmann::json extra = nlohmann::json::object());

/// Thrown by request handling and by runners to answer with a specific problem.
class ApiError : public std::runtime_error {
 public:
  explicit ApiError(Problem problem)
      : std::runtime_error(problem.detail), problem_(std::move(problem)) {}
  ApiError(const std::string& code, std::string detail,
           nlohmann::json extra = nlohmann::json::object())
      : ApiError(make_problem(code, std::move(detail), std::move(extra))) {}
  const Problem& problem() const { return problem_; }

 private:
  Problem problem_;
};

/// THE mapping from anything thrown (ApiError, the core and engine exceptions, the rest)
/// to the problem a client sees.
Problem problem_from_exception(std::exception_ptr error);

/// application/problem+json body; `instance` is the request path.
nlohmann::json problem_json(const Problem& problem, const std::string& instance = "");
/// Reads a problem back from its JSON (a failed job's stored error).
Problem problem_from_json(const nlohmann::json& doc);

}  // namespace papernet::server
