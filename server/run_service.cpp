// The HTTP job service as a program: wires config, keys, store, workers and routes; handles
// SIGINT/SIGTERM by draining (no new jobs, running ones get a grace period), persisting and
// stopping, and SIGHUP by reading the API keys again.
#include "server/run_service.h"

#include <httplib.h>
#include <signal.h>

#include <iostream>
#include <thread>

#include "core/io/json_text.h"
#include "server/api_keys.h"
#include "server/http_api.h"
#include "server/http_server.h"
#include "server/job_json.h"
#include "server/job_service.h"
#include "server/job_store.h"
#include "server/metrics.h"
#include "server/pipeline_runner.h"
#include "server/static_files.h"
#include "server/webhooks.h"

namespace papernet::server {

int run_service(const ServerConfig& config) {
  // Signals go to one thread that waits for them; every other thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  signal(SIGPIPE, SIG_IGN);

  std::unique_ptr<ApiKeyRing> keys;
  if (!config.api_keys.empty()) {
    try {
      keys = std::make_unique<ApiKeyRing>(config.api_keys,
                                          [](const std::string& line) { log_line(line); });
    } catch (const std::exception& e) {
      std::cerr << "papernet serve: --api-keys " << e.what() << "\n";
      return 2;
    }
  }

  // Every worker and HTTP thread may use a database connection at once, and the lease keeper,
  // the two webhook threads and the reader of the event streams (a stream's own thread reads
  // the job once, when it opens, as a status poll does).
  std::unique_ptr<JobStore> store;
  try {
    store = open_job_store(config.store, config.data_dir, config.workers + config.http_threads + 4);
  } catch (const std::exception& e) {
    std::cerr << "papernet serve: " << e.what() << "\n";
    return 1;
  }

  ServiceSettings settings;
  settings.workers = config.workers;
  settings.queue_length = config.queue_length;
  settings.options_limits.max_time_limit = config.max_job_time_limit;
  settings.options_limits.max_target_faces = config.max_faces;
  settings.default_time_limit = config.job_time_limit;
  settings.reuse_results = config.reuse_results;
  settings.max_attempts = config.max_attempts;
  settings.lease_seconds = config.lease;
  settings.retention_seconds = config.retention;
  settings.max_store_bytes = config.max_store_bytes;
  JobService service(
      *store,
      make_pipeline_runner({config.max_body_bytes, config.max_faces, config.job_time_limit}),
      settings, [](const std::string& line) { log_line(line); });

  // Callbacks of finished jobs, from threads of their own: a receiver that never answers holds
  // one of them, never an HTTP thread.
  WebhookSender webhooks(
      *store, webhook_settings(config), service.node(),
      [&service](const std::string& id) {
        const std::optional<JobView> view = service.view(id);
        if (!view) return std::string();
        nlohmann::json doc = job_to_json(*view, now_seconds());
        doc.erase("callback");  // the delivery's own state changes with every attempt
        return json_text(doc);
      },
      [](const std::string& line) { log_line(line); });

  HttpMetrics metrics;
  HttpLimits http_limits;
  http_limits.max_body_bytes = config.max_body_bytes + (64 << 10);  // multipart/chunk framing
  http_limits.read_timeout = config.read_timeout;
  http_limits.header_timeout = config.header_timeout;
  http_limits.request_timeout = config.request_timeout;
  http_limits.keep_alive_timeout = config.read_timeout;
  // Each event stream holds a thread of its own, beside the http_threads the other requests
  // have (docs/reliability.md).
  GuardedHttpServer http(http_limits, config.http_threads, config.max_streams);
  http.set_tcp_nodelay(true);  // small JSON answers must not wait for delayed ACKs
  install_routes(http, service, config, metrics, keys.get());
  const std::string& web_root = config.web_root;
  try {
    mount_web_root(http, web_root);
  } catch (const std::invalid_argument& e) {
    std::cerr << "papernet serve: " << e.what() << "\n";
    return 2;
  }

  int port = config.port;
  if (port == 0) {
    port = http.bind_to_any_port(config.host);
  } else if (!http.bind_to_port(config.host, port)) {
    port = -1;
  }
  if (port <= 0 || !http.set_listen_backlog(1024)) {
    std::cerr << "papernet serve: cannot listen on " << config.host << ":" << config.port << "\n";
    return 1;
  }
  service.start();
  webhooks.start();

  std::thread signal_thread([&] {
    int sig = 0;
    for (;;) {
      sig = 0;
      sigwait(&signals, &sig);
      if (sig != SIGHUP) break;
      if (keys)
        keys->reload();
      else
        log_line("SIGHUP: no --api-keys file to read");
    }
    if (sig == 0) return;
    log_line(std::string("received ") + (sig == SIGINT ? "SIGINT" : "SIGTERM") +
             ": no new jobs; running ones get " +
             std::to_string(static_cast<int>(config.shutdown_grace)) + " s");
    service.shutdown(std::chrono::milliseconds(static_cast<long>(config.shutdown_grace * 1000)));
    webhooks.stop();
    http.stop();
  });

  const std::string where =
      store->kind() == "sqlite" ? "data " + config.data_dir : redact_store_url(config.store);
  log_line("papernet listening on http://" + config.host + ":" + std::to_string(port) + " (" +
           where + ", " + std::to_string(config.workers) + " workers, queue " +
           std::to_string(config.queue_length) + ")" +
           (web_root.empty() ? "" : "; web demo from " + web_root));
  if (keys)
    log_line("api keys: " + std::to_string(keys->size()) + " keys from " + config.api_keys +
             "; /v1/jobs needs Authorization: Bearer <key>");
  else
    log_line("no --api-keys: the API is open to anyone who can reach " + config.host + ":" +
             std::to_string(port) + " (every caller sees every job)");
  std::cout << "papernet listening on http://" << config.host << ":" << port << std::endl;
  const bool ok = http.listen_after_bind();
  if (!ok || http.is_running()) {
    // listen failed by itself: wake the signal thread so it shuts the service down.
    pthread_kill(signal_thread.native_handle(), SIGTERM);
  }
  signal_thread.join();
  log_line("papernet stopped; unfinished jobs stay queued for the next start (or another node)");
  return 0;
}

}  // namespace papernet::server
