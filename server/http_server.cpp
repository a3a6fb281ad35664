#include "server/http_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <list>
#include <mutex>
#include <system_error>
#include <thread>

namespace papernet::server {
namespace {

using Clock = std::chrono::steady_clock;

int millis(double seconds) {
  return static_cast<int>(std::clamp(std::ceil(seconds * 1000), 0.0, 86'400'000.0));
}

// The socket as httplib reads it, with a byte budget and deadlines per request. One stream
// serves a whole keep-alive connection, so bytes read ahead belong to the next request.
class GuardedStream : public httplib::Stream {
 public:
  GuardedStream(socket_t sock, const HttpLimits& limits, const std::atomic<int>& waiting)
      : sock_(sock), limits_(limits), waiting_(waiting) {}

  // A new request starts: fresh budget and deadlines.
  void begin_request() {
    state_ = {};
    head_done_ = false;
    head_bytes_ = body_bytes_ = 0;
    tail_ = 0;
    line_bytes_ = 0;
    head_lines_ = 0;
    start_ = Clock::now();
  }
  const RequestReadState& state() const { return state_; }
  bool buffered() const { return begin_ < end_; }

  bool is_readable() const override { return buffered() || wait(POLLIN, read_wait()) > 0; }
  bool is_writable() const override { return wait(POLLOUT, limits_.read_timeout) > 0; }

  ssize_t read(char* ptr, std::size_t size) override {
    if (size == 0) return 0;
    if (head_done_) {
      if (body_bytes_ >= limits_.max_body_bytes) {
        state_.body_too_large = true;
        return -1;
      }
      size = std::min(size, limits_.max_body_bytes - body_bytes_);
    } else {
      if (head_bytes_ >= limits_.max_head_bytes) {
        state_.head_too_large = true;
        return -1;
      }
      size = std::min(size, limits_.max_head_bytes - head_bytes_);
    }
    if (Clock::now() > deadline()) {
      state_.timed_out = true;
      return -1;
    }
    if (!buffered() && !fill()) return closed_ ? 0 : -1;
    const std::size_t n = std::min(size, end_ - begin_);
    std::copy(buffer_ + begin_, buffer_ + begin_ + n, ptr);
    begin_ += n;
    if (head_done_) {
      body_bytes_ += n;
    } else {
      head_bytes_ += n;
      // httplib reads the head byte by byte; it ends with an empty line ("\n\r\n").
      for (std::size_t i = 0; i < n && !head_done_; ++i) {
        tail_ = ((tail_ << 8) | static_cast<unsigned char>(ptr[i])) & 0xffffff;
        head_done_ = tail_ == 0x0a0d0a;
        if (ptr[i] == '\n') {
          line_bytes_ = 0;
          ++head_lines_;
        } else if (++line_bytes_ >= CPPHTTPLIB_HEADER_MAX_LENGTH && head_lines_ > 0) {
          state_.header_line_too_long = true;  // the request line has its own 414
        }
      }
    }
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, std::size_t size) override {
    if (!is_writable()) return -1;
    return ::send(sock_, ptr, size, MSG_NOSIGNAL);
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    address(::getpeername, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    address(::getsockname, ip, port);
  }
  socket_t socket() const override { return sock_; }

  // The client closed or reset the connection (a client of a long response sends nothing).
  bool peer_closed() const {
    if (buffered()) return false;
    pollfd p{sock_, POLLIN | POLLRDHUP, 0};
    if (::poll(&p, 1, 0) <= 0) return false;
    if (p.revents & (POLLRDHUP | POLLHUP | POLLERR | POLLNVAL)) return true;
    char byte = 0;
    return ::recv(sock_, &byte, 1, MSG_PEEK | MSG_DONTWAIT) == 0;
  }

  // Waits for the next request on an idle connection; false when it is closed, idle too long or
  // the server stops.
  template <class Running>
  bool wait_for_request(Running running) {
    if (buffered()) return true;
    return wait_for_data(limits_.keep_alive_timeout, true, running) > 0;
  }

  // Discards what the client still sends (a body we refused) for a short while, so that closing
  // does not reset the connection before the client has read our answer.
  void linger() {
    ::shutdown(sock_, SHUT_WR);
    const auto end = Clock::now() + std::chrono::milliseconds(millis(limits_.linger));
    std::size_t total = 0;
    while (Clock::now() < end && total < limits_.max_body_bytes) {
      if (wait(POLLIN, 0.2) <= 0) continue;
      const ssize_t n = ::recv(sock_, buffer_, sizeof buffer_, 0);
      if (n <= 0) return;
      total += static_cast<std::size_t>(n);
    }
  }

 private:
  Clock::time_point deadline() const {
    const double seconds = head_done_ ? limits_.request_timeout : limits_.header_timeout;
    return start_ + std::chrono::milliseconds(millis(seconds));
  }
  // How long the next read may wait: the read timeout, cut short by the request's deadline.
  double read_wait() const {
    const double left = std::chrono::duration<double>(deadline() - Clock::now()).count();
    return std::max(0.0, std::min(limits_.read_timeout, left));
  }
  int wait(short events, double seconds) const {
    pollfd p{sock_, events, 0};
    int r = 0;
    do {
      r = ::poll(&p, 1, millis(seconds));
    } while (r < 0 && errno == EINTR);
    if (r > 0 && (p.revents & (POLLERR | POLLNVAL))) return -1;
    return r;
  }
  // Waits up to `seconds` for data, in slices so that it notices other connections waiting
  // for a thread (then an idle connection or a stalled head yields after busy_idle_timeout)
  // and a server that stops. 1 = data, 0 = timed out, -1 = error.
  template <class Running>
  int wait_for_data(double seconds, bool may_yield, Running running) const {
    const auto start = Clock::now();
    for (;;) {
      double limit = seconds;
      if (may_yield && waiting_ > 0) limit = std::min(limit, limits_.busy_idle_timeout);
      const double left = limit - std::chrono::duration<double>(Clock::now() - start).count();
      if (left <= 0 || !running()) return 0;
      const int ready = wait(POLLIN, std::min(left, 0.1));
      if (ready != 0) return ready;
    }
  }
  bool fill() {
    const int ready = wait_for_data(read_wait(), !head_done_, [] { return true; });
    if (ready == 0) {
      state_.timed_out = true;
      return false;
    }
    if (ready < 0) return false;
    ssize_t n = 0;
    do {
      n = ::recv(sock_, buffer_, sizeof buffer_, 0);
    } while (n < 0 && errno == EINTR);
    if (n == 0) closed_ = true;
    if (n <= 0) return false;
    begin_ = 0;
    end_ = static_cast<std::size_t>(n);
    return true;
  }
  void address(int (*get)(int, sockaddr*, socklen_t*), std::string& ip, int& port) const {
    sockaddr_storage addr{};
    socklen_t len = sizeof addr;
    if (get(sock_, reinterpret_cast<sockaddr*>(&addr), &len) != 0) return;
    char text[INET6_ADDRSTRLEN] = {};
    if (addr.ss_family == AF_INET) {
      const auto* a = reinterpret_cast<const sockaddr_in*>(&addr);
      inet_ntop(AF_INET, &a->sin_addr, text, sizeof text);
      port = ntohs(a->sin_port);
    } else if (addr.ss_family == AF_INET6) {
      const auto* a = reinterpret_cast<const sockaddr_in6*>(&addr);
      inet_ntop(AF_INET6, &a->sin6_addr, text, sizeof text);
      port = ntohs(a->sin6_port);
    }
    ip = text;
  }

  socket_t sock_;
  const HttpLimits& limits_;
  const std::atomic<int>& waiting_;
  RequestReadState state_;
  bool head_done_ = false;
  bool closed_ = false;
  std::size_t head_bytes_ = 0, body_bytes_ = 0;
  std::uint32_t tail_ = 0;
  std::size_t line_bytes_ = 0, head_lines_ = 0;
  Clock::time_point start_ = Clock::now();
  char buffer_[4096];
  std::size_t begin_ = 0, end_ = 0;
};

thread_local GuardedStream* current_stream = nullptr;
thread_local bool close_after = false;

}  // namespace

RequestReadState request_read_state() {
  return current_stream ? current_stream->state() : RequestReadState{};
}

bool client_closed() { return current_stream && current_stream->peer_closed(); }

void close_connection_after_response() { close_after = true; }

namespace {

// httplib's pool made elastic: `base` threads always, up to `most` while connections wait
// for one (the extra ones end after kIdleExtra without work); counts the connections that
// wait for a thread.
class ConnectionThreadPool : public httplib::TaskQueue {
 public:
  ConnectionThreadPool(std::size_t base, std::size_t most,
                       std::shared_ptr<std::atomic<int>> waiting)
      : base_(base), most_(std::max(base, most)), waiting_(std::move(waiting)) {
    std::lock_guard lock(mutex_);
    while (threads_.size() < base_) start();
  }
  ~ConnectionThreadPool() override { ConnectionThreadPool::shutdown(); }

  void enqueue(std::function<void()> fn) override {
    ++*waiting_;
    std::list<std::thread> ended;
    {
      std::lock_guard lock(mutex_);
      jobs_.push_back(std::move(fn));
      if (idle_ < jobs_.size() && threads_.size() < most_) start();
      ended.swap(ended_);
    }
    work_.notify_one();
    for (std::thread& t : ended) t.join();
  }

  void shutdown() override {
    std::unique_lock lock(mutex_);
    shutdown_ = true;
    work_.notify_all();
    gone_.wait(lock, [&] { return threads_.empty(); });
    std::list<std::thread> ended;
    ended.swap(ended_);
    lock.unlock();
    for (std::thread& t : ended) t.join();
  }

 private:
  static constexpr auto kIdleExtra = std::chrono::seconds(10);

  // Under mutex_. A thread the system refuses (a container's pids limit) is not fatal: the
  // connection waits for a thread that frees up, as in a fixed pool.
  void start() {
    threads_.emplace_back();
    const auto self = std::prev(threads_.end());
    try {
      *self = std::thread([this, self] { run(self); });
    } catch (const std::system_error&) {
      threads_.erase(self);
      if (threads_.empty()) throw;  // not even one: nothing could be served
    }
  }

  void run(std::list<std::thread>::iterator self) {
    std::unique_lock lock(mutex_);
    for (;;) {
      ++idle_;
      const bool woken =
          work_.wait_for(lock, kIdleExtra, [&] { return shutdown_ || !jobs_.empty(); });
      --idle_;
      if (jobs_.empty() && (shutdown_ || (!woken && threads_.size() > base_))) break;
      if (jobs_.empty()) continue;
      std::function<void()> fn = std::move(jobs_.front());
      jobs_.pop_front();
      lock.unlock();
      --*waiting_;
      fn();
      lock.lock();
    }
    // A thread cannot join itself: the next enqueue or shutdown does.
    ended_.splice(ended_.end(), threads_, self);
    gone_.notify_all();
  }

  const std::size_t base_, most_;
  std::shared_ptr<std::atomic<int>> waiting_;
  std::mutex mutex_;
  std::condition_variable work_, gone_;
  std::deque<std::function<void()>> jobs_;
  std::list<std::thread> threads_, ended_;
  std::size_t idle_ = 0;
  bool shutdown_ = false;
};

}  // namespace

GuardedHttpServer::GuardedHttpServer(const HttpLimits& limits, std::size_t threads,
                                     std::size_t extra_threads)
    : limits_(limits), waiting_(std::make_shared<std::atomic<int>>(0)) {
  new_task_queue = [threads, extra_threads, waiting = waiting_] {
    return new ConnectionThreadPool(threads, threads + extra_threads, waiting);
  };
}

bool GuardedHttpServer::set_listen_backlog(int backlog) {
  // listen() on a listening socket only changes its backlog (Linux).
  return svr_sock_ != INVALID_SOCKET && ::listen(svr_sock_, backlog) == 0;
}

bool GuardedHttpServer::process_and_close_socket(socket_t sock) {
  GuardedStream stream(sock, limits_, *waiting_);
  current_stream = &stream;
  bool linger = false;
  std::size_t left = keep_alive_max_count_;
  while (left > 0 && stream.wait_for_request([this] { return svr_sock_ != INVALID_SOCKET; })) {
    stream.begin_request();
    close_after = false;
    bool connection_closed = false;
    const bool ok = process_request(stream, left == 1, connection_closed, nullptr);
    // A refused body may still be arriving: drain it a moment so the client reads our answer.
    // A client that timed out is slow anyway and gets no such courtesy.
    const RequestReadState& state = stream.state();
    linger = close_after || state.head_too_large || state.body_too_large;
    if (!ok || connection_closed || linger || state.timed_out) break;
    --left;
  }
  if (linger) stream.linger();
  current_stream = nullptr;
  close_after = false;
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return true;
}

}  // namespace papernet::server
