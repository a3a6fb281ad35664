// Callbacks (webhooks): which hosts a callback_url may name, and the threads that deliver them.
// docs/security.md "Webhooks" is the contract: the signature, the SSRF rules, the retries.
#include "server/webhooks.h"

#include <arpa/inet.h>
#include <httplib.h>
#include <netdb.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>

#include "server/job.h"

namespace papernet::server {
namespace {

[[noreturn]] void refuse(const std::string& why, bool transient = false) {
  throw CallbackRefused("option 'callback_url': " + why, transient);
}

bool listed(const std::string& host, const std::vector<std::string>& hosts) {
  for (const std::string& entry : hosts) {
    if (entry == host) return true;
    // "*.shop.example": any name under shop.example, not shop.example itself.
    if (entry.size() > 2 && entry.starts_with("*.") && host.size() > entry.size() - 1 &&
        host.ends_with(entry.substr(1)))
      return true;
  }
  return false;
}

bool internal_v4(std::uint32_t a) {
  auto in = [&](std::uint32_t net, int bits) {
    return bits == 0 || (a >> (32 - bits)) == (net >> (32 - bits));
  };
  return in(0x00000000, 8) ||   // 0.0.0.0/8 "this network"
         in(0x0A000000, 8) ||   // 10/8
         in(0x64400000, 10) ||  // 100.64/10 shared (carrier-grade NAT)
         in(0x7F000000, 8) ||   // loopback
         in(0xA9FE0000, 16) ||  // link-local (cloud metadata lives at 169.254.169.254)
         in(0xAC100000, 12) ||  // 172.16/12
         in(0xC0000000, 24) ||  // 192.0.0/24 protocol assignments
         in(0xC0A80000, 16) ||  // 192.168/16
         in(0xC6120000, 15) ||  // 198.18/15 benchmarking
         in(0xE0000000, 4) ||   // multicast
         in(0xF0000000, 4);     // reserved and broadcast
}

std::string hex(const unsigned char* bytes, unsigned length) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < length; ++i) {
    out += digits[bytes[i] >> 4];
    out += digits[bytes[i] & 15];
  }
  return out;
}

}  // namespace

WebhookSettings webhook_settings(const ServerConfig& config) {
  WebhookSettings s;
  s.hosts = config.webhook_hosts;
  s.secret = config.webhook_secret;
  s.timeout = config.webhook_timeout;
  s.retry_for = config.webhook_retry_for;
  return s;
}

std::string webhook_signature(const std::string& secret, std::int64_t t, const std::string& body) {
  std::string signed_text = std::to_string(t);
  signed_text += '.';
  signed_text += body;
  unsigned char mac[EVP_MAX_MD_SIZE];
  unsigned length = 0;
  if (!HMAC(EVP_sha256(), secret.data(), static_cast<int>(secret.size()),
            reinterpret_cast<const unsigned char*>(signed_text.data()), signed_text.size(), mac,
            &length))
    throw std::runtime_error("HMAC-SHA256 failed");
  std::string header = "t=" + std::to_string(t);
  header += ",v1=";
  header += hex(mac, length);
  return header;
}

bool is_internal_address(const std::string& address) {
  in_addr v4{};
  if (inet_pton(AF_INET, address.c_str(), &v4) == 1) return internal_v4(ntohl(v4.s_addr));
  in6_addr v6{};
  if (inet_pton(AF_INET6, address.c_str(), &v6) != 1) return true;  // not an address: refuse
  const unsigned char* b = v6.s6_addr;
  static const unsigned char zero[16] = {};
  if (std::memcmp(b, zero, 15) == 0 && (b[15] == 0 || b[15] == 1)) return true;  // :: and ::1
  // IPv4-mapped (::ffff:a.b.c.d) and NAT64 (64:ff9b::a.b.c.d): the IPv4 address decides.
  static const unsigned char mapped[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff};
  static const unsigned char nat64[12] = {0, 0x64, 0xff, 0x9b, 0, 0, 0, 0, 0, 0, 0, 0};
  if (std::memcmp(b, mapped, 12) == 0 || std::memcmp(b, nat64, 12) == 0) {
    const std::uint32_t a = (std::uint32_t{b[12]} << 24) | (std::uint32_t{b[13]} << 16) |
                            (std::uint32_t{b[14]} << 8) | b[15];
    return internal_v4(a);
  }
  return (b[0] & 0xfe) == 0xfc ||                    // fc00::/7 unique local
         (b[0] == 0xfe && (b[1] & 0xc0) == 0x80) ||  // fe80::/10 link-local
         (b[0] == 0xfe && (b[1] & 0xc0) == 0xc0) ||  // fec0::/10 site-local (deprecated)
         b[0] == 0xff;                               // multicast
}

std::vector<std::string> callback_addresses(const CallbackUrl& url,
                                            const WebhookSettings& settings) {
  if (settings.secret.empty())
    refuse("this server sends no callbacks (it has no --webhook-secret to sign them with)");
  const bool is_listed = listed(url.host, settings.hosts);
  if (!settings.hosts.empty() && !is_listed)
    refuse("host '" + url.host + "' is not one the server's --webhook-hosts allows");
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (getaddrinfo(url.host.c_str(), nullptr, &hints, &found) != 0 || !found)
    refuse("host '" + url.host + "' does not resolve", true);
  std::unique_ptr<addrinfo, void (*)(addrinfo*)> owned(found, freeaddrinfo);
  std::vector<std::string> out;
  for (const addrinfo* a = found; a; a = a->ai_next) {
    char text[INET6_ADDRSTRLEN] = "";
    const void* raw =
        a->ai_family == AF_INET
            ? static_cast<const void*>(&reinterpret_cast<const sockaddr_in*>(a->ai_addr)->sin_addr)
            : static_cast<const void*>(
                  &reinterpret_cast<const sockaddr_in6*>(a->ai_addr)->sin6_addr);
    if (!inet_ntop(a->ai_family, raw, text, sizeof text)) continue;
    // One internal address is enough to refuse: which one a connection gets is not ours to
    // choose (DNS rebinding answers public first, internal next).
    if (!is_listed && is_internal_address(text))
      refuse("host '" + url.host + "' resolves to " + text +
             ", a loopback, private or reserved address; only hosts in the server's "
             "--webhook-hosts may");
    if (std::find(out.begin(), out.end(), text) == out.end()) out.push_back(text);
  }
  if (out.empty()) refuse("host '" + url.host + "' does not resolve", true);
  return out;
}

WebhookSender::WebhookSender(JobStore& store, WebhookSettings settings, std::string node,
                             std::function<std::string(const std::string&)> status_json, Logger log)
    : store_(store),
      settings_(std::move(settings)),
      node_(std::move(node)),
      status_json_(std::move(status_json)),
      log_(std::move(log)) {}

WebhookSender::~WebhookSender() { stop(); }

void WebhookSender::start() {
  for (std::size_t i = 0; i < std::max<std::size_t>(1, settings_.threads); ++i)
    threads_.emplace_back([this] { run(); });
}

void WebhookSender::stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
  threads_.clear();
}

void WebhookSender::run() {
  // An attempt takes at most a connect, a send and a receive timeout; the lease outlasts that,
  // so no other node (or thread) attempts the same delivery meanwhile.
  const double lease = 3 * settings_.timeout + 10;
  bool store_failing = false;  // logged once a failure, not twice a second
  std::unique_lock lock(mutex_);
  while (!stop_) {
    lock.unlock();
    std::optional<WebhookDelivery> due;
    try {
      due = store_.claim_webhook(node_, now_seconds(), lease);
      store_failing = false;
    } catch (const std::exception& e) {
      if (!store_failing) log_(std::string("webhooks: cannot read the store: ") + e.what());
      store_failing = true;
    }
    if (due) attempt(std::move(*due));
    lock.lock();
    // The store is polled: a job may end on any node, and a retry falls due by the clock.
    if (!due) cv_.wait_for(lock, std::chrono::milliseconds(500), [&] { return stop_; });
  }
}

void WebhookSender::attempt(WebhookDelivery d) {
  nlohmann::json entry = {{"at", now_seconds()}};
  bool delivered = false, hopeless = false;
  try {
    const CallbackUrl url = parse_callback_url(d.url);
    // Checked again at every attempt: what a name resolves to may have changed since submit.
    const std::vector<std::string> addresses = callback_addresses(url, settings_);
    const std::string body = status_json_(d.job_id);
    if (body.empty()) {
      entry["error"] = "the job is gone";
      hopeless = true;
    } else {
      httplib::Client client(url.host, url.port);
      // Connect to the address checked above, not to whatever a second lookup returns.
      client.set_hostname_addr_map({{url.host, addresses.front()}});
      const auto timeout = std::chrono::milliseconds(static_cast<long>(settings_.timeout * 1000));
      client.set_connection_timeout(timeout);
      client.set_read_timeout(timeout);
      client.set_write_timeout(timeout);
      client.set_follow_location(false);  // a redirect could lead anywhere, internal included
      client.set_keep_alive(false);
      const auto t = static_cast<std::int64_t>(std::floor(now_seconds()));
      const httplib::Headers headers = {
          {"X-Papernet-Signature", webhook_signature(settings_.secret, t, body)},
          {"X-Papernet-Job", d.job_id},
          {"User-Agent", "papernet-webhook/1"}};
      auto res = client.Post(url.target.c_str(), headers, body, "application/json");
      if (!res) {
        entry["error"] = httplib::to_string(res.error());
      } else {
        entry["status"] = res->status;
        delivered = res->status >= 200 && res->status < 300;
        if (res->status >= 300 && res->status < 400) entry["error"] = "redirect not followed";
      }
    }
  } catch (const CallbackRefused& e) {
    entry["error"] = e.what();
    hopeless = !e.transient();  // refused by the rules: the same again would be refused again
  } catch (const InvalidOptionException& e) {
    entry["error"] = e.what();  // a stored URL that no longer parses
    hopeless = true;
  } catch (const std::exception& e) {
    entry["error"] = e.what();
  }
  d.attempts.push_back(entry);
  const std::size_t n = d.attempts.size();
  const double now = now_seconds();
  const double first = d.attempts.front().value("at", now);
  const double delay =
      std::min(300.0, std::ldexp(1.0, static_cast<int>(std::min<std::size_t>(n, 20)) - 1));
  std::string what;
  if (entry.contains("status")) {
    what = "HTTP ";
    what += std::to_string(entry["status"].get<int>());
    if (entry.contains("error")) {
      what += " (";
      what += entry["error"].get<std::string>();
      what += ")";
    }
  } else {
    what = entry["error"].get<std::string>();
  }
  if (delivered) {
    d.state = "delivered";
  } else if (hopeless || now + delay - first > settings_.retry_for) {
    d.state = "failed";
    what += "; gave up";
  } else {
    d.next_at = now + delay;
    what += "; next in ";
    what += std::to_string(static_cast<int>(delay));
    what += " s";
  }
  std::string line = "webhook job " + d.job_id;
  line += " attempt ";
  line += std::to_string(n);
  line += ": ";
  line += what;
  log_(line);
  try {
    if (!store_.update_webhook(d, node_))
      log_("webhook job " + d.job_id + ": claim lost (another node attempts it)");
  } catch (const std::exception& e) {
    log_("webhook job " + d.job_id + ": attempt not stored: " + e.what());
  }
}

}  // namespace papernet::server
