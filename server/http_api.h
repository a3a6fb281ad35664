#pragma once

#include <atomic>

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
/// `service`, `config` and `metrics` must outlive `http`.
void install_routes(httplib::Server& http, JobService& service, const ServerConfig& config,
                    HttpMetrics& metrics);

}  // namespace papernet::server
