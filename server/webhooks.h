#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "api/callback_url.h"
#include "server/config.h"
#include "server/job_store.h"

namespace papernet::server {

/// Where callbacks may go and how they are sent (docs/security.md "Webhooks").
struct WebhookSettings {
  /// Hosts callbacks may name ("hooks.shop.example", "10.0.0.7", "*.shop.example"). Empty: any
  /// host whose addresses are all public. A listed host may resolve to loopback or a private
  /// range; an unlisted one never.
  std::vector<std::string> hosts;
  std::string secret;       ///< HMAC-SHA256 key of X-Papernet-Signature; "" = callbacks refused
  double timeout = 5;       ///< seconds to connect, and each of send and receive, per attempt
  double retry_for = 3600;  ///< seconds after the first attempt that no new attempt starts
  std::size_t threads = 2;  ///< delivery threads: a receiver that hangs holds one of them
};

/// A callback_url the rules refuse (422 callback_url_refused naming callback_url). `transient`:
/// the host did not resolve, which a later attempt may see otherwise.
class CallbackRefused : public InvalidOptionException {
 public:
  CallbackRefused(const std::string& message, bool transient)
      : InvalidOptionException("callback_url_refused", "callback_url", message),
        transient_(transient) {}
  bool transient() const { return transient_; }

 private:
  bool transient_;
};

/// The webhook part of the service's configuration.
WebhookSettings webhook_settings(const ServerConfig& config);

/// "t=<t>,v1=<hex HMAC-SHA256(secret, "<t>.<body>")>", the X-Papernet-Signature header.
std::string webhook_signature(const std::string& secret, std::int64_t t, const std::string& body);

/// An IPv4 or IPv6 address (text) in loopback, private, link-local, shared (100.64/10),
/// unspecified, multicast or reserved space: somewhere a callback must not reach unlisted.
bool is_internal_address(const std::string& address);

/// The addresses a callback to `url` may connect to: `url`'s host resolved, every address
/// checked against `settings`. \throw CallbackRefused saying why: callbacks are off, the host is
/// not listed, does not resolve, or resolves to an internal address without being listed.
std::vector<std::string> callback_addresses(const CallbackUrl& url,
                                            const WebhookSettings& settings);

/// Sends the callbacks of finished jobs from threads of its own: claims due deliveries from
/// the store (so a restart, or another node, resumes them), POSTs the job's final status,
/// records each attempt and retries with exponential backoff (1, 2, 4 ... at most 300 s
/// apart) until `retry_for` has passed since the first attempt.
class WebhookSender {
 public:
  using Logger = std::function<void(const std::string&)>;
  /// `status_json` renders a finished job's status document (the callback's body).
  WebhookSender(JobStore& store, WebhookSettings settings, std::string node,
                std::function<std::string(const std::string& job_id)> status_json, Logger log);
  ~WebhookSender();
  WebhookSender(const WebhookSender&) = delete;
  WebhookSender& operator=(const WebhookSender&) = delete;

  void start();
  /// Lets attempts under way end (each within its timeouts) and stops. Idempotent.
  void stop();

 private:
  void run();
  void attempt(WebhookDelivery delivery);

  JobStore& store_;
  WebhookSettings settings_;
  std::string node_;
  std::function<std::string(const std::string&)> status_json_;
  Logger log_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace papernet::server
