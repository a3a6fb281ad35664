#pragma once

#include <httplib.h>

#include <atomic>
#include <cstddef>
#include <memory>

namespace papernet::server {

/// How much and how slowly a client may send one request. cpp-httplib (0.11) bounds neither the
/// request line and headers nor chunked or length-less bodies, and its read timeout restarts with
/// every byte; these limits close those gaps.
struct HttpLimits {
  std::size_t max_head_bytes = 64 << 10;  ///< request line and headers together
  std::size_t max_body_bytes = 64 << 20;  ///< body bytes as sent (chunk framing included)
  double read_timeout = 5;                ///< seconds one read may wait for data
  double header_timeout = 10;             ///< seconds from the first byte to the end of the headers
  double request_timeout = 120;           ///< seconds from the first byte to the end of the body
  double keep_alive_timeout = 5;          ///< seconds an idle connection is kept open
  double linger = 2;  ///< seconds spent discarding a body we did not read before closing
  /// While connections wait for a free thread, a connection that sends nothing for this long
  /// between requests or in the middle of its headers gives its thread up (is closed).
  double busy_idle_timeout = 1;
};

/// What went wrong while reading the current request on this thread, if anything.
struct RequestReadState {
  bool head_too_large = false;
  /// A header line passed cpp-httplib's limit (CPPHTTPLIB_HEADER_MAX_LENGTH), which it answers
  /// with a bare 400.
  bool header_line_too_long = false;
  bool body_too_large = false;
  bool timed_out = false;
};

/// An httplib::Server whose connections are read through a stream that enforces HttpLimits:
/// over a limit or a deadline, the read fails, the answer says why (see request_read_state) and
/// the connection is closed.
class GuardedHttpServer : public httplib::Server {
 public:
  /// `threads` serve connections, one each; while all are busy, up to `extra_threads` more are
  /// started (and end again after 10 s without work); further connections wait for a free
  /// thread. A server whose handlers hold a connection long (event streams, at most N at once)
  /// gets N extra threads, so that they never take the `threads` other requests need.
  GuardedHttpServer(const HttpLimits& limits, std::size_t threads, std::size_t extra_threads = 0);
  const HttpLimits& limits() const { return limits_; }
  /// Call after binding: cpp-httplib listens with a backlog of 5, so a burst of connections
  /// overflows it and the kernel resets them. \return false when listen() fails.
  bool set_listen_backlog(int backlog);

 private:
  bool process_and_close_socket(socket_t sock) override;
  HttpLimits limits_;
  std::shared_ptr<std::atomic<int>> waiting_;  // accepted connections without a thread
};

/// The read state of the request being handled on this thread (all false outside a request).
RequestReadState request_read_state();

/// Whether the client of the connection being served on this thread has closed it (or reset
/// it), without waiting: a long response (an event stream) ends early then.
bool client_closed();

/// Called by a handler that answers without reading the whole body: the connection is closed
/// after the response (what is left of the body is discarded for at most HttpLimits::linger).
void close_connection_after_response();

}  // namespace papernet::server
