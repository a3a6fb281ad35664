#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "server/job_service.h"

namespace papernet::server {

/// The live progress streams (GET /v1/jobs/{id}/events) of one server, with one thread that
/// reads the watched jobs' states from the service: a change is read once per job, however
/// many streams watch it, and the streams themselves never touch the store (so hundreds of
/// them need no database connection each). A stream waits on a condition variable between
/// events: it costs a thread's stack, no CPU.
class EventStreams {
 public:
  /// A job's state as streamed: its JSON document ("null" once it is gone) and whether it
  /// ended. `generation` grows with every change; 0 = not read yet.
  struct State {
    std::uint64_t generation = 0;
    std::string doc;
    bool final = false;
    bool closing = false;  ///< the server is shutting down: end the stream
  };
  class Watch;

  /// At most `max_streams` open at once.
  EventStreams(JobService& service, std::size_t max_streams);
  ~EventStreams();
  EventStreams(const EventStreams&) = delete;
  EventStreams& operator=(const EventStreams&) = delete;

  /// Starts watching job `id` (already found and authorised); nullptr when `max_streams` are
  /// open. The stream ends when the returned Watch is destroyed.
  std::shared_ptr<Watch> open(const std::string& id);
  /// The job's state once it differs from `seen` (a generation), the server closes, or
  /// `timeout` passes. The first call reads the job at once.
  State next(Watch& watch, std::uint64_t seen, std::chrono::milliseconds timeout);
  std::size_t open_count() const;
  std::size_t max_streams() const { return max_streams_; }
  /// Ends every stream (their next() answers `closing`) and the reading thread. Idempotent.
  void stop();

 private:
  struct Job {
    std::size_t watchers = 0;
    State state;
  };
  void run();
  State read(const std::string& id);
  void publish(const std::string& id, State state);
  void close(const std::string& id);

  JobService& service_;
  const std::size_t max_streams_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::string, Job> jobs_;
  std::size_t open_ = 0;
  std::uint64_t generations_ = 0;  // the last State::generation given, over all jobs
  bool closing_ = false;
  bool stop_ = false;
  std::thread reader_;
};

/// Ends its stream when destroyed.
class EventStreams::Watch {
 public:
  Watch(EventStreams& streams, std::string id) : streams_(streams), id_(std::move(id)) {}
  ~Watch() { streams_.close(id_); }
  Watch(const Watch&) = delete;
  Watch& operator=(const Watch&) = delete;
  const std::string& id() const { return id_; }

 private:
  EventStreams& streams_;
  std::string id_;
};

}  // namespace papernet::server
