// The job options parsers (api/options) with the service's limits: the input as the JSON
// `options` part of an upload, and as a query string (`strategy=QQ&seed=3`, not URL-decoded:
// httplib decodes before we see it). Accepted options must survive their canonical JSON.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "api/options.h"
#include "server/config.h"

namespace {

papernet::OptionsLimits service_limits() {
  const papernet::server::ServerConfig config;  // as server/http_api.cpp fills them
  papernet::OptionsLimits limits;
  limits.max_time_limit = config.max_job_time_limit;
  limits.max_target_faces = config.max_faces;
  return limits;
}

void round_trip(const papernet::JobOptions& options, const papernet::OptionsLimits& limits) {
  const nlohmann::json canonical = papernet::options_to_json(options);
  if (papernet::options_to_json(papernet::parse_options_json(canonical.dump(), limits)) !=
      canonical)
    std::abort();
}

std::multimap<std::string, std::string> query_params(std::string_view text) {
  std::multimap<std::string, std::string> params;
  while (!text.empty()) {
    const std::string_view pair = text.substr(0, text.find('&'));
    text.remove_prefix(std::min(text.size(), pair.size() + 1));
    const std::size_t eq = pair.find('=');
    params.emplace(std::string(pair.substr(0, eq)),
                   eq == std::string_view::npos ? std::string() : std::string(pair.substr(eq + 1)));
  }
  return params;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const papernet::OptionsLimits limits = service_limits();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    round_trip(papernet::parse_options_json(text, limits), limits);
  } catch (const papernet::InvalidOptionException& e) {
    if (e.code().empty() || std::string_view(e.what()).empty()) std::abort();
  }
  try {
    round_trip(papernet::parse_options_query(query_params(text), limits), limits);
  } catch (const papernet::InvalidOptionException& e) {
    if (e.code().empty() || std::string_view(e.what()).empty()) std::abort();
  }
  return 0;
}
