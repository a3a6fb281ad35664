#pragma once

#include <atomic>

#include "server/api_keys.h"
#include "server/config.h"
#include "server/job_service.h"
#include "server/metrics.h"

namespace httplib {
class Server;
}

namespace papernet::server {

/// Installs every route of the HTTP API (README.md "HTTP service", api/openapi.json) on `http`,
/// plus the error handler that turns any failure into application/problem+json and the access log.
/// Handlers only parse, enqueue and look up: geometry runs on the service's workers.
/// With `keys` (nullptr = an open API), every /v1/jobs request needs `Authorization: Bearer KEY`
/// and sees, lists and cancels its tenant's jobs only. `service`, `config`, `metrics` and `keys`
/// must outlive `http`.
void install_routes(httplib::Server& http, JobService& service, const ServerConfig& config,
                    HttpMetrics& metrics, ApiKeyRing* keys = nullptr);

}  // namespace papernet::server
